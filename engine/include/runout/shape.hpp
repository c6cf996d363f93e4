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

// The nodes a particle sees along one direction, first .. first + 2, and a
// fourth, first + 3, whose weight and derivative are always zero: a row of
// the stencil is then four nodes, one AVX register of doubles (lanes.hpp;
// the grid box has a column to spare for it, place_box).
constexpr int kStencilNodes = 4;

struct Stencil1D {
  int cell;                  // grid index of the cell the particle is in
  int first;                 // grid index of the stencil's first node
  double r0;                 // that node's offset from the particle, x_first - xp
  double w[kStencilNodes];   // weights of nodes first .. first + 3
  double dw[kStencilNodes];  // their derivatives d/dx
};

// The factors gimp_1d multiplies by, once per particle and direction: two
// divisions where the piecewise form divided in each piece it took.
struct GimpScale {
  double h, lp;
  double inv_h;    // 1 / h
  double inv_hlp;  // 1 / (h lp)
};

RUNOUT_HD inline GimpScale gimp_scale(double h, double lp) {
  return {h, lp, 1.0 / h, 1.0 / (h * lp)};
}

// uGIMP weight and derivative for a particle at distance r = xp - xi from a
// node, cell size h, particle half-width lp <= h/2: the convolution of the
// linear hat with a box of width 2 lp (Bardenhagen & Kober 2004, eq. 39,
// "uGIMP": lp kept at its initial value), for the four nodes of a stencil
// row at once (lanes.hpp). Every piece is evaluated and one selected,
// without branches: a particle's nodes lie in different pieces, and which
// ones changes from particle to particle, so a branch on the piece is
// unpredictable. The outer piece, with its bracket h + lp - |r| held at
// zero or above, is also the zero beyond the support.
RUNOUT_HD inline void gimp_lanes(const Lanes& r, const GimpScale& k, Lanes& w, Lanes& dw) {
  const Lanes zero = splat(0.0);
  const Lanes a = select_less(r, zero, -r, r);  // |r|
  const Lanes s = select_less(r, zero, splat(-1.0), splat(1.0));
  const Lanes bracket = k.h + k.lp + -a;
  const Lanes b = select_less(bracket, zero, zero, bracket);
  const Lanes w_inner = 1.0 - 0.5 * (r * r + k.lp * k.lp) * k.inv_hlp;
  const Lanes w_linear = 1.0 - a * k.inv_h;
  const Lanes w_outer = 0.25 * b * b * k.inv_hlp;
  const Lanes lp = splat(k.lp), linear_end = splat(k.h - k.lp);
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
// suffice: the cell's two nodes and the neighbour on the nearer side.
// Linear MPM uses the cell's two nodes with the cell's constant gradient,
// which keeps the gradient sum at exactly zero on a node (where the hat's
// derivative is undefined); its third weight is zero.
RUNOUT_HD inline void stencil_1d(ShapeKind kind, double xp, double origin, double h,
                                 double lp, Stencil1D& s) {
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
  s.first = c - (frac < 0.5 ? 1 : 0);  // arithmetic: a branch here is unpredictable
  s.r0 = origin + s.first * h - xp;
  // The fourth node is at least 1.5 h >= h + lp away: outside the support,
  // its weight and derivative are zero.
  const Lanes r = xp - (origin + lane_offsets(s.first, 1.0) * h);
  Lanes w, dw;
  gimp_lanes(r, gimp_scale(h, lp), w, dw);
  store_lanes(s.w, w);
  store_lanes(s.dw, dw);
}

}  // namespace runout
