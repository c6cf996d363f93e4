#pragma once
// The pieces of the nonlocal average (nonlocal.hpp) that every backend
// shares, host and device: the lattice's axes and B-spline weights, a
// particle's image in a no-slip base, the band's increment, and the
// average taken element by element (the CUDA backend's kernels; the host's
// NonlocalAverage spreads fixed chunks of particles on the threads and
// adds them in chunk order, and sweeps rows over their non-empty spans,
// for the same bits on any thread count).
#include <cmath>

#include "runout/mpm/base.hpp"
#include "runout/mpm/host_device.hpp"

namespace runout {

constexpr double kLatticePi = 3.14159265358979323846;

// One axis of the lattice: nodes at i * spacing for the lattice indices
// first .. first + count - 1, or, with wrap > 0 (periodic), modulo wrap.
// taps[k] = w(k spacing) for k = 0 .. reach.
struct LatticeAxis {
  double spacing = 0;  // [m]
  int first = 0, count = 0;
  int wrap = 0;
  int reach = 0;
  const double* taps = nullptr;
  RUNOUT_HD int node(int i) const {  // the storage column of lattice index i
    return wrap > 0 ? ((i % wrap) + wrap) % wrap : i - first;
  }
};

// Quadratic B-spline weights of the nodes base - 1, base, base + 1 for a
// point at u lattice spacings from node 0, base the nearest node (de Boor;
// the weights sum to 1 and reproduce the point's first and second moments).
struct LatticeSpline {
  int base;
  double w[3];
};
RUNOUT_HD inline LatticeSpline lattice_spline(double u) {
  const int base = static_cast<int>(std::floor(u + 0.5));
  const double t = u - base;  // in [-1/2, 1/2)
  return {base, {0.5 * (0.5 - t) * (0.5 - t), 0.75 - t * t, 0.5 * (0.5 + t) * (0.5 + t)}};
}

// The lattice: its two axes, x measured from x0 where it wraps.
struct NonlocalLattice {
  LatticeAxis ax, ay;
  double x0 = 0;

  // The weights of x and y along each axis, their nodes' lattice indices
  // base - 1 .. base + 1 (not wrapped).
  RUNOUT_HD LatticeSpline spline_x(double x) const {
    return lattice_spline((x - (ax.wrap > 0 ? x0 : 0.0)) / ax.spacing);
  }
  RUNOUT_HD LatticeSpline spline_y(double y) const { return lattice_spline(y / ay.spacing); }

  // f(storage index, weight) for the 3 x 3 nodes that (x, y) spreads onto.
  template <class F>
  RUNOUT_HD void for_nodes(double x, double y, F&& f) const {
    const LatticeSpline sx = spline_x(x);
    const LatticeSpline sy = spline_y(y);
    for (int b = 0; b < 3; ++b) {
      const int row = ay.node(sy.base - 1 + b) * ax.count;
      for (int a = 0; a < 3; ++a) f(row + ax.node(sx.base - 1 + a), sy.w[b] * sx.w[a]);
    }
  }
  int size() const { return ax.count * ay.count; }  // NonlocalAverage::lattice keeps it an int
};

// Where (x, y)'s image across a no-slip base lies, if the point is within
// reach above it: a band along such a base keeps the whole kernel across
// it by its images' volumes.
RUNOUT_HD inline bool base_image(const BaseView& base, double x, double y, double reach,
                                 double& mx, double& my) {
  if (base.kind == BaseKind::None) return false;
  const BasePoint b = locate_on_base(base, x, y);
  if (b.d < 0.0 || b.d > reach) return false;
  mx = x - 2.0 * b.d * b.nx;
  my = y - 2.0 * b.d * b.ny;
  return true;
}

// The increment of a particle whose own increment is a and whose band
// carries delta / t_s = band: b = delta / a is the width of the zone that
// yields around it, measured. A band (b up to half the averaging width
// sqrt(pi) l) remoulds by delta / t_s; a zone as wide as the average or
// wider is diffuse yield, which no band concentrates, and remoulds by its
// own strain a; between the two, a linear blend.
RUNOUT_HD inline double localised_increment(double a, double band, double t_s, double l) {
  if (a <= 0.0) return 0.0;
  const double x = band * t_s / (a * std::sqrt(kLatticePi) * l);  // b / (sqrt(pi) l)
  double phi = 2.0 * (1.0 - x);
  phi = phi < 0.0 ? 0.0 : (phi > 1.0 ? 1.0 : phi);
  return phi * band + (1.0 - phi) * a;
}

// One particle of the material being averaged spread onto the lattice: V a
// onto increments, V onto volumes, and its image's V where it has one.
// add(array, index, value) adds as a backend's scatter does (atomically on
// the GPU), so the particles may go in any order (the sums' rounding then
// follows it).
template <class Add>
struct SpreadToLattice {
  NonlocalLattice lattice;
  double* increments;
  double* volumes;
  const double *x, *y, *vol;
  const int* material;
  const double* in;  // the local increments a
  int which;         // the material
  BaseView mirror;   // a no-slip base, or BaseKind::None
  double reach;      // of the images: the kernel's cut-off
  Add add;
  RUNOUT_HD void operator()(int p) const {
    if (material[p] != which) return;
    const double v = vol[p], va = vol[p] * in[p];
    lattice.for_nodes(x[p], y[p], [&](int k, double w) {
      if (va > 0.0) add(increments, k, w * va);
      add(volumes, k, w * v);
    });
    double mx, my;
    if (base_image(mirror, x[p], y[p], reach, mx, my))
      lattice.for_nodes(mx, my, [&](int k, double w) { add(volumes, k, w * v); });
  }
};

// One node of the convolution along x (k = row * count + column):
// out = sum over the taps of w(|m| spacing) in[column + m], wrapping where
// the axis does, zero beyond its ends otherwise.
struct ConvolveAlongX {
  const double* in;
  double* out;
  LatticeAxis ax;
  RUNOUT_HD void operator()(int k) const {
    const int nx = ax.count;
    const int row = k / nx;
    const int i = k - row * nx;
    double sum = 0.0;
    for (int m = -ax.reach; m <= ax.reach; ++m) {
      int c = i + m;
      if (ax.wrap > 0)
        c = ((c % nx) + nx) % nx;
      else if (c < 0 || c >= nx)
        continue;
      sum += ax.taps[m < 0 ? -m : m] * in[row * nx + c];
    }
    out[k] = sum;
  }
};

// The same along y (the rows), never wrapping.
struct ConvolveAlongY {
  const double* in;
  double* out;
  LatticeAxis ay;
  int nx;  // row length
  RUNOUT_HD void operator()(int k) const {
    const int j = k / nx;
    const int i = k - j * nx;
    double sum = 0.0;
    for (int m = -ay.reach; m <= ay.reach; ++m) {
      const int r = j + m;
      if (r < 0 || r >= ay.count) continue;
      sum += ay.taps[m < 0 ? -m : m] * in[r * nx + i];
    }
    out[k] = sum;
  }
};

// One particle of the material being averaged takes the convolved sums
// back: delta / t_s = scale sum w V a / sum w V, then its localised
// increment (a particle that does not yield does not soften).
struct GatherBand {
  NonlocalLattice lattice;
  const double* increments;  // convolved V a
  const double* volumes;     // convolved V
  const double *x, *y;
  const int* material;
  const double* in;  // the local increments a
  double* out;
  int which;         // the material
  double scale, t_s, l;
  RUNOUT_HD void operator()(int p) const {
    if (material[p] != which) return;
    if (in[p] <= 0.0) {
      out[p] = 0.0;
      return;
    }
    double sum = 0.0, weight = 0.0;
    lattice.for_nodes(x[p], y[p], [&](int k, double w) {
      sum += w * increments[k];
      weight += w * volumes[k];
    });
    const double band = weight > 0.0 ? scale * sum / weight : 0.0;
    out[p] = localised_increment(in[p], band, t_s, l);
  }
};

}  // namespace runout
