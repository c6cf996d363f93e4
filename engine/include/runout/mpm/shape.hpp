#pragma once
// Shape functions on a uniform grid of spacing h, one direction at a time;
// the 2D weight is the tensor product N = Nx(x) Ny(y) and its gradient
// (dNx Ny, Nx dNy). Each particle sees a 3-node stencil per direction.
#include <algorithm>
#include <cmath>

#include "runout/mpm/host_device.hpp"
#include "runout/scene/kinds.hpp"
#include "runout/mpm/lanes.hpp"

namespace runout {

// The nodes a particle sees along one direction, four in a row: one AVX
// register of doubles (lanes.hpp). Where they start (StencilStart):
// Nearest, at the neighbour on the nearer side of the particle's cell c,
// first = c - 1 or c, so the three nodes it touches come first and the
// fourth's weight is zero (the grid box has a column to spare for it,
// place_box); CellLeft, at c - 1 whatever the particle's place in its cell,
// so the four nodes c - 1 .. c + 2 hold the three it touches and a zero at
// one end. Along x (the lanes of a stencil row) GIMP stencils start
// CellLeft: every particle of a cell then adds into the same four doubles
// of a row, where with Nearest the particles of a cell's two halves added
// into rows one node apart, and a row loaded just after the previous
// particle's store of the row one node over cannot be forwarded from the
// store (it partly overlaps it) but waits for it to reach the cache. Along
// y (across the rows) they start Nearest: three rows, not four.
constexpr int kStencilNodes = 4;

enum class StencilStart { Nearest, CellLeft };

struct Stencil1D {
  int cell;                  // grid index of the cell the particle is in
  int first;                 // grid index of the stencil's first node
  double r0;                 // that node's offset from the particle, x_first - xp
  double w[kStencilNodes];   // weights of nodes first .. first + 3 (one of them zero)
  double dw[kStencilNodes];  // their derivatives d/dx
};

// A position's coordinate (x - origin) / h in cells, as every stencil and
// every cell key takes it: times 1 / h, where the division was the slowest
// step of making a stencil.
RUNOUT_HD inline double grid_coordinate(double x, double origin, double h) {
  return (x - origin) * (1.0 / h);
}
inline Lanes grid_coordinate(const Lanes& x, double origin, double h) {
  return (x - origin) * (1.0 / h);
}
// The cell a position is in along one direction.
RUNOUT_HD inline int cell_of(double x, double origin, double h) {
  return static_cast<int>(std::floor(grid_coordinate(x, origin, h)));
}

// The factors gimp_cell_nodes multiplies by, once per particle and
// direction: two divisions where the piecewise form divided in each piece
// it took. T: double for one particle, Lanes for four (stencil_1d_x4, lane
// k particle k's).
template <class T>
struct GimpScaleOf {
  T h, lp;
  T inv_h;    // 1 / h
  T inv_hlp;  // 1 / (h lp)
};
using GimpScale = GimpScaleOf<double>;

template <class T>
RUNOUT_HD inline GimpScaleOf<T> gimp_scale(const T& h, const T& lp) {
  return {h, lp, 1.0 / h, 1.0 / (h * lp)};
}

// uGIMP weights and derivatives (Bardenhagen & Kober 2004, eq. 39, "uGIMP":
// lp kept at its initial value): the convolution of the linear hat of
// cell size h with a box of half-width lp <= h / 2. For a particle at
// distance r = xp - x_i from a node, a = |r|, s = sign(r):
//   a < lp:             N = 1 - (r^2 + lp^2) / (2 h lp),  dN/dx = -r / (h lp)
//   lp <= a < h - lp:   N = 1 - a / h,                    dN/dx = -s / h
//   h - lp <= a:        N = b^2 / (4 h lp),               dN/dx = -s b / (2 h lp)
// with b = h + lp - a held at zero or above, which is also the zero beyond
// the support. Here for the four nodes c - 1 .. c + 2 around a particle at
// fraction f = (xp - x_c) / h in [0, 1) of its cell c, one particle (T
// double) or four (T Lanes, lane k particle k's). The nodes lie at
// r = h (1 + f), h f, h (f - 1) and h (f - 2): the outer two are at least h
// away, where only the last piece applies, so only the inner two take the
// three-piece form. Every piece is evaluated and one selected, without
// branches: which piece a node is in changes from particle to particle, so
// a branch on it is unpredictable.
RUNOUT_HD inline double select_less(double a, double b, double x, double y) { return a < b ? x : y; }
RUNOUT_HD inline double splat_like(const double&, double v) { return v; }
RUNOUT_HD inline Lanes splat_like(const Lanes&, double v) { return splat(v); }

// kDerivatives false: the weights alone (dw is not written), for the
// passes that interpolate or scatter without gradients; the weights are
// the same operations either way.
template <bool kDerivatives = true, class T>
RUNOUT_HD inline void gimp_cell_nodes(const T& f, const GimpScaleOf<T>& k, T w[4], T dw[4]) {
  const T zero = splat_like(f, 0.0);
  const T hf = k.h * f, hg = k.h + -hf;  // distances to the cell's nodes c and c + 1
  const T half = 0.5 * k.inv_hlp, quarter = 0.25 * k.inv_hlp;
  // The outer nodes: the bracket h + lp - |r| is lp - h f and lp - h (1 - f).
  const T b0 = k.lp + -hf, b3 = k.lp + -hg;
  const T c0 = select_less(b0, zero, zero, b0), c3 = select_less(b3, zero, zero, b3);
  w[0] = c0 * c0 * quarter;
  w[3] = c3 * c3 * quarter;
  if (kDerivatives) {
    dw[0] = -(c0 * half);
    dw[3] = c3 * half;
  }
  // The inner nodes at distance a, on the side s (+1: the node behind the
  // particle, -1: ahead of it).
  const T lp = k.lp, linear_end = k.h + -k.lp, reach = k.h + k.lp;
  const auto inner = [&](const T& a, double s, T& wi, T& dwi) {
    const T b = reach + -a;
    const T w_inner = 1.0 - (a * a + lp * lp) * half, w_linear = 1.0 - a * k.inv_h;
    const T w_outer = b * b * quarter;
    wi = select_less(a, lp, w_inner, select_less(a, linear_end, w_linear, w_outer));
    if (!kDerivatives) return;
    const T dw_inner = -s * a * k.inv_hlp, dw_linear = -s * k.inv_h;
    const T dw_outer = -s * b * half;
    dwi = select_less(a, lp, dw_inner, select_less(a, linear_end, dw_linear, dw_outer));
  };
  inner(hf, 1.0, w[1], dw[1]);
  inner(hg, -1.0, w[2], dw[2]);
}

// Stencil of a particle at xp on the grid whose node 0 lies at origin.
// GIMP support reaches h + lp <= 1.5 h from the particle, so three nodes
// suffice: the cell's two nodes and the neighbour on the nearer side
// (start: where the four start, StencilStart). Linear MPM uses the cell's
// two nodes with the cell's constant gradient, which keeps the gradient
// sum at exactly zero on a node (where the hat's derivative is undefined);
// its third and fourth weights are zero.
RUNOUT_HD inline void stencil_1d(ShapeKind kind, double xp, double origin, double h,
                                 double lp, Stencil1D& s,
                                 StencilStart start = StencilStart::Nearest) {
  const double u = grid_coordinate(xp, origin, h);
  const double cell = std::floor(u);
  const double frac = u - cell;
  const int c = static_cast<int>(cell);
  s.cell = c;
  if (kind == ShapeKind::Linear) {
    s.first = c;
    s.r0 = -frac * h;
    s.w[0] = 1.0 - frac;
    s.w[1] = frac;
    s.w[2] = 0.0;
    s.dw[0] = -1.0 / h;
    s.dw[1] = 1.0 / h;
    s.dw[2] = 0.0;
    s.w[3] = s.dw[3] = 0.0;
    return;
  }
  double w[kStencilNodes], dw[kStencilNodes];
  gimp_cell_nodes(frac, gimp_scale(h, lp), w, dw);
  // Nearest: from the particle's half of its cell, the nodes c - 1 .. c + 1
  // or c .. c + 2 (the fourth node has zero weight either way); by
  // selection: a branch here is unpredictable.
  const bool shift = start == StencilStart::Nearest && !(frac < 0.5);
  s.first = c - (shift ? 0 : 1);
  s.r0 = origin + s.first * h - xp;
  for (int j = 0; j < kStencilNodes; ++j) {
    s.w[j] = shift ? (j < 3 ? w[j + 1] : 0.0) : w[j];
    s.dw[j] = shift ? (j < 3 ? dw[j + 1] : 0.0) : dw[j];
  }
}

// The rest of stencil_1d (GIMP) for four particles at once, lane k of xp
// particle k's: from the cell and the fraction of it, and the weights w
// and derivatives dw of the nodes cell - 1 .. cell + 2 (gimp_cell_nodes),
// where the stencil starts and its node offsets; each particle's stencil goes to
// out(k, first, r0, w, dw) (w and dw that particle's four nodes, as
// Lanes). The same operations as stencil_1d, so the same weights to
// rounding (the compiler may fuse other pairs of them into multiply-adds).
// kDerivatives false: dw is neither read nor passed on (zero).
template <bool kDerivatives = true, class Out>
inline void stencil_1d_x4(const Lanes& xp, double origin, double h, const Lanes& cell,
                          const Lanes& frac, Lanes w[kStencilNodes], Lanes dw[kStencilNodes],
                          StencilStart start, Out&& out) {
  Lanes first = cell - 1.0;
  if (start == StencilStart::Nearest) {
    const Lanes half = splat(0.5);
    first = first + select_less(frac, half, splat(0.0), splat(1.0));
    for (int j = 0; j < 3; ++j) {
      w[j] = select_less(frac, half, w[j], w[j + 1]);
      if (kDerivatives) dw[j] = select_less(frac, half, dw[j], dw[j + 1]);
    }
    w[3] = dw[3] = splat(0.0);
  }
  const Lanes r0 = origin + first * h - xp;
  transpose_lanes(w);
  if (kDerivatives) transpose_lanes(dw);
  for (int q = 0; q < 4; ++q)
    out(q, static_cast<int>(lane(first, q)), lane(r0, q), w[q], dw[q]);
}

}  // namespace runout
