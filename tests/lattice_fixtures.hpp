#pragma once
// Particle lattices of slabs crossed by straight shear bands, whose bands
// and blocks are known: shared by the tests of the analysis' algorithms
// (test_analysis_algorithms.cpp) and of the VTK filters that wrap them
// (test_strain_filters.cpp). No VTK.
#include <cmath>
#include <functional>
#include <vector>

#include "runout/analysis/vec2.hpp"

namespace runout::lattice_fixtures {

using analysis::Vec2;

constexpr double kPi = 3.14159265358979323846;

// A straight band through (surface_x, top of the slab) at `dip` degrees to
// the base, positive descending towards +x, `width` thick.
struct BandLine {
  double surface_x, dip, width;
};

// A slab of particles on a square lattice of spacing h over [0, length] x
// [0, top(x)], the base the x axis; xi is band_xi within a band, else
// background_xi.
struct Slab {
  double length = 20, height = 5, h = 0.1;
  std::vector<BandLine> bands;
  double band_xi = 10, background_xi = 0.05;
  std::function<double(double)> top;  // default: height everywhere
};

struct Lattice {
  std::vector<Vec2> points;
  std::vector<double> xi;
};

inline double distance_to(const BandLine& b, double height, Vec2 q) {
  const double d = b.dip * kPi / 180;
  return std::abs((q.x - b.surface_x) * -std::sin(d) - (q.y - height) * std::cos(d));
}

inline Lattice make_lattice(const Slab& slab) {
  Lattice out;
  const int nx = static_cast<int>(std::lround(slab.length / slab.h));
  const int ny = static_cast<int>(std::lround(2 * slab.height / slab.h));  // room for a raised top
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Vec2 q{(i + 0.5) * slab.h, (j + 0.5) * slab.h};
      if (q.y > (slab.top ? slab.top(q.x) : slab.height)) continue;
      bool in_band = false;
      for (const BandLine& b : slab.bands) in_band |= distance_to(b, slab.height, q) <= b.width / 2;
      out.points.push_back(q);
      out.xi.push_back(in_band ? slab.band_xi : slab.background_xi);
    }
  return out;
}

}  // namespace runout::lattice_fixtures
