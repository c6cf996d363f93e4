#pragma once
// Shape functions on a uniform grid of spacing h, one direction at a time;
// the 2D weight is the tensor product N = Nx(x) Ny(y) and its gradient
// (dNx Ny, Nx dNy). Each particle sees a 3-node stencil per direction.
#include <algorithm>
#include <cmath>

#include "runout/host_device.hpp"
#include "runout/kinds.hpp"

namespace runout {

struct Stencil1D {
  int cell;      // grid index of the cell the particle is in
  int first;     // grid index of the stencil's first node
  double r0;     // that node's offset from the particle, x_first - xp
  double w[3];   // weights of nodes first, first+1, first+2
  double dw[3];  // their derivatives d/dx
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
// "uGIMP": lp kept at its initial value). Every piece is evaluated and one
// selected, without branches: a particle's three nodes lie in different
// pieces, and which ones changes from particle to particle, so a branch
// on the piece is unpredictable. The outer piece, with its bracket
// h + lp - |r| held at zero or above, is also the zero beyond the support.
RUNOUT_HD inline void gimp_1d(double r, const GimpScale& k, double& w, double& dw) {
  const double a = std::fabs(r);
  const double s = r < 0.0 ? -1.0 : 1.0;
  const double b = std::max(k.h + k.lp - a, 0.0);
  const bool inner = a < k.lp, linear = a < k.h - k.lp;
  const double w_inner = 1.0 - 0.5 * (r * r + k.lp * k.lp) * k.inv_hlp;
  const double w_linear = 1.0 - a * k.inv_h;
  const double w_outer = 0.25 * b * b * k.inv_hlp;
  w = inner ? w_inner : linear ? w_linear : w_outer;
  const double dw_inner = -r * k.inv_hlp, dw_linear = -s * k.inv_h;
  const double dw_outer = -0.5 * s * b * k.inv_hlp;
  dw = inner ? dw_inner : linear ? dw_linear : dw_outer;
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
    return;
  }
  s.first = c - (frac < 0.5 ? 1 : 0);  // arithmetic: a branch here is unpredictable
  s.r0 = origin + s.first * h - xp;
  const GimpScale scale = gimp_scale(h, lp);
  for (int k = 0; k < 3; ++k) {
    const double r = xp - (origin + (s.first + k) * h);
    gimp_1d(r, scale, s.w[k], s.dw[k]);
  }
}

}  // namespace runout
