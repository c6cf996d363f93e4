// An elastic column under its own weight, slip sides and a fixed base,
// settled by local damping: sigma_yy = -rho g (H - Y), Y the initial height
// (the weight above a material point does not change as the column
// compresses). With shape functions linear within a cell the strain, and so
// the stress, is one value per cell: the particles of a cell straddle the
// exact line by +-rho g h / 4 around the value at their centroid. So the
// check is the cell's mean stress against the exact stress at the cell's
// mean Y, away from the ends (0.2 H .. 0.8 H), at two resolutions; the finer
// must be closer.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "runout/measure/diagnostics.hpp"
#include "runout/mpm/simulation.hpp"
#include "scene_builders.hpp"

using namespace runout;

namespace {

constexpr double kH = 10.0, kRho = 1000.0, kG = 10.0;

double column_error(double h) {
  Simulation sim(fixtures::column_scene(kH, h, kRho, 1e7, kG));
  sim.advance_to(4.0);
  const Particles& P = sim.particles();
  EXPECT_LT(particle_totals(P).max_speed, 1e-6) << "column not settled";

  struct Cell { double stress = 0, y = 0; int n = 0; };
  std::map<int, Cell> cells;
  for (int p = 0; p < P.size(); ++p) {
    Cell& c = cells[static_cast<int>(std::floor(P.y0[p] / h))];
    c.stress += P.syy[p];
    c.y += P.y0[p];
    ++c.n;
  }
  double worst = 0;
  for (const auto& [index, c] : cells) {
    const double Y = c.y / c.n, exact = -kRho * kG * (kH - Y);
    if (Y >= 0.2 * kH && Y <= 0.8 * kH)
      worst = std::max(worst, std::fabs(c.stress / c.n - exact) / std::fabs(exact));
  }
  return worst;
}

}  // namespace

TEST(ElasticColumn, SelfWeightStressConverges) {
  const double coarse = column_error(0.5);
  const double fine = column_error(0.25);
  std::printf("column: max relative error %.3g (h = 0.5), %.3g (h = 0.25)\n", coarse, fine);
  EXPECT_LT(coarse, 0.02);
  EXPECT_LT(fine, 0.02);
  EXPECT_LT(fine, coarse);
}
