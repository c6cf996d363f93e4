#pragma once
// Shape functions on a uniform grid of spacing h, one direction at a time;
// the 2D weight is the tensor product N = Nx(x) Ny(y) and its gradient
// (dNx Ny, Nx dNy). Each particle sees a 3-node stencil per direction.
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

// uGIMP weight and derivative for a particle at distance r = xp - xi from a
// node, cell size h, particle half-width lp <= h/2: the convolution of the
// linear hat with a box of width 2 lp (Bardenhagen & Kober 2004, eq. 39,
// "uGIMP": lp kept at its initial value).
RUNOUT_HD inline void gimp_1d(double r, double h, double lp, double& w, double& dw) {
  const double a = std::fabs(r);
  const double s = r < 0.0 ? -1.0 : 1.0;
  if (a < lp) {
    w = 1.0 - (r * r + lp * lp) / (2.0 * h * lp);
    dw = -r / (h * lp);
  } else if (a < h - lp) {
    w = 1.0 - a / h;
    dw = -s / h;
  } else if (a < h + lp) {
    const double b = h + lp - a;
    w = b * b / (4.0 * h * lp);
    dw = -s * b / (2.0 * h * lp);
  } else {
    w = 0.0;
    dw = 0.0;
  }
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
  s.first = frac < 0.5 ? c - 1 : c;
  s.r0 = origin + s.first * h - xp;
  for (int k = 0; k < 3; ++k) {
    const double r = xp - (origin + (s.first + k) * h);
    gimp_1d(r, h, lp, s.w[k], s.dw[k]);
  }
}

}  // namespace runout
