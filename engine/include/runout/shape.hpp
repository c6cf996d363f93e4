#pragma once
// Shape functions on a uniform grid of spacing h, one direction at a time;
// the 2D weight is the tensor product N = Nx(x) Ny(y) and its gradient
// (dNx Ny, Nx dNy). Each particle sees a 3-node stencil per direction.
#include <algorithm>
#include <cmath>

#include "runout/host_device.hpp"
#include "runout/kinds.hpp"
#include "runout/lanes.hpp"

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

// The factors gimp_1d multiplies by, once per particle and direction: two
// divisions where the piecewise form divided in each piece it took. T:
// double for one particle, Lanes for four (make_stencils_x4, lane k
// particle k's).
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

RUNOUT_HD inline Lanes as_lanes(double x) { return splat(x); }
RUNOUT_HD inline Lanes as_lanes(const Lanes& x) { return x; }

// uGIMP weight and derivative for a particle at distance r = xp - xi from a
// node, cell size h, particle half-width lp <= h/2: the convolution of the
// linear hat with a box of width 2 lp (Bardenhagen & Kober 2004, eq. 39,
// "uGIMP": lp kept at its initial value), for the four nodes of a stencil
// row at once (lanes.hpp). Every piece is evaluated and one selected,
// without branches: a particle's nodes lie in different pieces, and which
// ones changes from particle to particle, so a branch on the piece is
// unpredictable. The outer piece, with its bracket h + lp - |r| held at
// zero or above, is also the zero beyond the support.
template <class T>
RUNOUT_HD inline void gimp_lanes(const Lanes& r, const GimpScaleOf<T>& k, Lanes& w, Lanes& dw) {
  const Lanes zero = splat(0.0);
  const Lanes a = select_less(r, zero, -r, r);  // |r|
  const Lanes s = select_less(r, zero, splat(-1.0), splat(1.0));
  const Lanes bracket = k.h + k.lp + -a;
  const Lanes b = select_less(bracket, zero, zero, bracket);
  const Lanes w_inner = 1.0 - 0.5 * (r * r + k.lp * k.lp) * k.inv_hlp;
  const Lanes w_linear = 1.0 - a * k.inv_h;
  const Lanes w_outer = 0.25 * b * b * k.inv_hlp;
  const Lanes lp = as_lanes(k.lp), linear_end = as_lanes(k.h - k.lp);
  w = select_less(a, lp, w_inner, select_less(a, linear_end, w_linear, w_outer));
  const Lanes dw_inner = -r * k.inv_hlp, dw_linear = -s * k.inv_h;
  const Lanes dw_outer = -0.5 * s * b * k.inv_hlp;
  dw = select_less(a, lp, dw_inner, select_less(a, linear_end, dw_linear, dw_outer));
}

// One node's weight and derivative.
RUNOUT_HD inline void gimp_1d(double r, const GimpScale& k, double& w, double& dw) {
  Lanes wl, dwl;
  gimp_lanes(splat(r), k, wl, dwl);
  w = lane(wl, 0);
  dw = lane(dwl, 0);
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
  const double u = (xp - origin) / h;
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
  // arithmetic: a branch here is unpredictable
  s.first = c - (start == StencilStart::CellLeft || frac < 0.5 ? 1 : 0);
  s.r0 = origin + s.first * h - xp;
  // The node of the four that is not in the stencil is at least h + lp
  // away: outside the support, its weight and derivative are zero.
  const Lanes r = xp - (origin + lane_offsets(s.first, 1.0) * h);
  Lanes w, dw;
  gimp_lanes(r, gimp_scale(h, lp), w, dw);
  store_lanes(s.w, w);
  store_lanes(s.dw, dw);
}

// stencil_1d (GIMP) of four particles at once: lane k of xp and lp is
// particle k's, whose stencil goes to out(k, cell, first, r0, w, dw) (w and
// dw that particle's four nodes, as Lanes). The same operations, so
// the same weights to rounding (the compiler may fuse other pairs of
// them into multiply-adds); a third of the arithmetic, as each gimp_lanes
// evaluates one node of four particles, not the four of one, whose last
// is always zero.
template <class Out>
inline void stencil_1d_x4(const Lanes& xp, double origin, double h, const Lanes& lp,
                          StencilStart start, Out&& out) {
  const Lanes u = (xp - origin) / h;
  const Lanes cell = floor_lanes(u);
  const Lanes first = start == StencilStart::CellLeft
                          ? cell - 1.0
                          : cell - select_less(u - cell, splat(0.5), splat(1.0), splat(0.0));
  const Lanes r0 = origin + first * h - xp;
  const GimpScaleOf<Lanes> k = gimp_scale(splat(h), lp);
  Lanes w[kStencilNodes], dw[kStencilNodes];
  // Nearest: the fourth node is always outside the support.
  const int nodes = start == StencilStart::CellLeft ? 4 : 3;
  for (int j = 0; j < nodes; ++j) gimp_lanes(xp - (origin + (first + double(j)) * h), k, w[j], dw[j]);
  if (nodes == 3) w[3] = dw[3] = splat(0.0);
  transpose_lanes(w);
  transpose_lanes(dw);
  for (int q = 0; q < 4; ++q)
    out(q, static_cast<int>(lane(cell, q)), static_cast<int>(lane(first, q)), lane(r0, q), w[q],
        dw[q]);
}

}  // namespace runout
