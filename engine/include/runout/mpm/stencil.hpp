#pragma once
// A particle's stencil of shape functions for the whole step: GIMP's
// domain half-widths (with the lattice reduction), the weights, and the
// visits of its nodes that every stage uses.
#include <algorithm>
#include <cmath>

#include "runout/mpm/base.hpp"
#include "runout/mpm/grid.hpp"
#include "runout/mpm/host_device.hpp"
#include "runout/mpm/lanes.hpp"
#include "runout/mpm/particles.hpp"
#include "runout/mpm/shape.hpp"
#include "runout/mpm/step_config.hpp"

namespace runout {

// The particle's shape functions for the whole step: every stage evaluates
// them at the start-of-step position, so a particle's stencil is the same
// in every pass. In three parts, by the stages that read them (p2g all
// three, g2p and the momentum remap the weights). The stages take any St
// with members w, d and r of these types: Stencil2D, which every backend
// computes in each pass (the CPU's four particles at a time).
struct StencilWeights {       // every stage
  int first_x, first_y;       // grid indices of the rows' first node and of the first row
  double wx[kStencilNodes];   // weights along x of nodes first_x .. first_x + 3 (one zero)
  double wy[kStencilNodes];   // weights along y of rows first_y .. first_y + 2 (and a zero)
};
struct StencilDerivatives {   // p2g, the gradient, APIC's g2p
  double dwx[kStencilNodes];  // d/dx of wx
  double dwy[kStencilNodes];  // d/dy of wy
};
struct StencilPlace {         // p2g's gap to the base, APIC's offsets
  double lx, ly;              // the half-widths of the particle's domain (domain_half_widths)
  double r0x, r0y;            // the first node's offset from the particle, x_first - x_p
};
struct Stencil2D {
  StencilWeights w;
  StencilDerivatives d;
  StencilPlace r;
};
// The parts from the two directions' Stencil1D (the y stencil's fourth
// node has zero weight) and the domain's half-widths.
RUNOUT_HD inline void set_stencil(const Stencil1D& x, const Stencil1D& y, double lx, double ly,
                                  StencilWeights& w, StencilDerivatives& d, StencilPlace& r) {
  w.first_x = x.first;
  w.first_y = y.first;
  for (int a = 0; a < kStencilNodes; ++a) {
    w.wx[a] = x.w[a];
    d.dwx[a] = x.dw[a];
  }
  for (int b = 0; b < kStencilNodes; ++b) {
    w.wy[b] = y.w[b];
    d.dwy[b] = y.dw[b];
  }
  r = StencilPlace{lx, ly, x.r0, y.r0};
}

// The half-widths of a particle's GIMP domain. Fixed: the initial square of
// half-width lp (uGIMP). Deforming: the particles started on a square
// lattice of spacing 2 lp, which the motion maps, locally, to the lattice
// spanned by a = F e1 and b = F e2; the domains must tile that lattice, so
// that material that is only deformed does not separate. F's columns are
// one basis of it, but under shear a poor one: simple shear gamma maps the
// square to a parallelogram gamma cells long, while the particles still sit
// on rows 2 lp apart, each as far from its neighbours as before. So the
// basis is first reduced (Lagrange-Gauss: the shorter vector subtracted
// from the longer while that shortens it), giving the most nearly
// orthogonal basis of the same lattice; simple shear reduces to the square
// again. Where one reduced vector lies along x, a = (s, 0), b = (t, u), the
// lattice is rows |u| apart of points s apart, which rectangles s by |u|
// tile exactly (as bricks in a wall, each row shifted by t). So the
// domain takes the width |a_x| of the more nearly horizontal reduced
// vector and the height |b_y| of the other, as its aspect ratio, and the
// particle's current area 4 lp^2 J (J = V / V0): lx = lp sqrt(J |a_x| /
// |b_y|), and ly alike. Exact for stretches along the axes and for shear
// along either axis, a square for a rotation. Without the reduction, the
// bounding box of F's parallelogram flattened the domains of a sheared
// layer as 1 / sqrt(1 + gamma), leaving gaps between its rows: a Bingham
// layer on a no-slip incline ran 15 % slow (docs/convergence.md, "Plug
// flow"). This is an axis-aligned convected GIMP (cpGIMP, Bardenhagen and
// Kober 2004, follows the domain's stretch; CPDI, Sadeghirad, Brannon and
// Burghardt 2011, tracks the parallelogram itself). Each half-width is
// capped at h / 2, the widest domain a three-node stencil holds, as CPDI
// codes limit domain size (Homel, Brannon and Guilkey 2016); the floor
// keeps the weights' 1 / (h lp) finite.
RUNOUT_HD inline void reduce_lattice_basis(double& ax, double& ay, double& bx, double& by) {
  // Each pass at least halves the longer vector's excess, so a few dozen
  // passes reach any finite shear; the bound keeps the loop finite on NaN.
  for (int pass = 0; pass < 64; ++pass) {
    // The shorter vector first, by selection: in a barely deformed body
    // which is shorter is a coin toss, and a branch on it unpredictable.
    const bool swap = ax * ax + ay * ay > bx * bx + by * by;
    const double sx = swap ? bx : ax, sy = swap ? by : ay;
    bx = swap ? ax : bx;
    by = swap ? ay : by;
    ax = sx;
    ay = sy;
    const double aa = ax * ax + ay * ay, ab = ax * bx + ay * by;
    // |ab / aa| <= 1/2 rounds to zero: reduced. Tested before dividing,
    // as nearly every particle's basis is (and nearbyint is a libm call).
    if (!(aa > 0.0) || !(std::fabs(ab) > 0.5 * aa)) return;
    const double k = std::nearbyint(ab / aa);
    if (k == 0.0) return;
    bx -= k * ax;
    by -= k * ay;
  }
}

RUNOUT_HD inline void domain_half_widths(const ParticleView& P, int p, const StepConfig& c,
                                         double h, double& lx, double& ly) {
  lx = ly = c.lp;
  if (c.domain == DomainKind::Fixed || c.shape == ShapeKind::Linear) return;
  double ax = P.fxx[p], ay = P.fyx[p], bx = P.fxy[p], by = P.fyy[p];
  reduce_lattice_basis(ax, ay, bx, by);
  // a the more nearly horizontal: a_x^2 / |a|^2 >= b_x^2 / |b|^2.
  const bool a_horizontal = ax * ax * (bx * bx + by * by) >= bx * bx * (ax * ax + ay * ay);
  const double wx = std::fabs(a_horizontal ? ax : bx), wy = std::fabs(a_horizontal ? by : ay);
  const double V = P.vol[p];
  if (!(V > 0.0 && wx > 0.0 && wy > 0.0)) return;  // the guards stop such a run
  const double floor = 1e-3 * c.lp, cap = 0.5 * h;
  // lp sqrt(J wx / wy) = wx t and lp sqrt(J wy / wx) = wy t with
  // t = lp sqrt(J / (wx wy)), J = V / V0: one root and one division.
  const double t = c.lp * std::sqrt(V / (P.vol0[p] * wx * wy));
  // min and max, not fmin and fmax: the bounds are positive, so a NaN
  // width takes the bound either way, and GCC calls libm for fmin and fmax
  // unless it may assume no NaN.
  lx = std::min(cap, std::max(floor, t * wx));
  ly = std::min(cap, std::max(floor, t * wy));
}

// The stencil of a particle at (x, y) whose domain has half-widths lx, ly.
RUNOUT_HD inline void stencil_at(const GridView& g, const StepConfig& c, double x, double y,
                                 double lx, double ly, Stencil2D& s) {
  Stencil1D sx, sy;
  stencil_1d(c.shape, x, g.ox, g.h, lx, sx, StencilStart::CellLeft);
  stencil_1d(c.shape, y, g.oy, g.h, ly, sy, StencilStart::Nearest);
  set_stencil(sx, sy, lx, ly, s.w, s.d, s.r);
}

RUNOUT_HD inline void make_stencil(const GridView& g, const StepConfig& c, const ParticleView& P,
                                   int p, Stencil2D& s) {
  double lx, ly;
  domain_half_widths(P, p, c, g.h, lx, ly);
  stencil_at(g, c, P.x[p], P.y[p], lx, ly, s);
}

// domain_half_widths of particles p .. p + 3, lane k particle p + k's, for
// a basis that needs no reduction (F near a rotation or a stretch: nearly
// every particle at every step); false where one lane's does, and the
// caller falls back to domain_half_widths.
inline bool domain_half_widths_x4(const ParticleView& P, int p, const StepConfig& c, double h,
                                  Lanes& lx, Lanes& ly) {
  lx = ly = splat(c.lp);
  if (c.domain == DomainKind::Fixed || c.shape == ShapeKind::Linear) return true;
  Lanes ax = load_lanes(P.fxx + p), ay = load_lanes(P.fyx + p);
  Lanes bx = load_lanes(P.fxy + p), by = load_lanes(P.fyy + p);
  // reduce_lattice_basis's first pass: the shorter vector first, and the
  // test that ends it.
  const Lanes a2 = ax * ax + ay * ay, b2 = bx * bx + by * by;
  const Lanes sx = select_less(b2, a2, bx, ax), sy = select_less(b2, a2, by, ay);
  bx = select_less(b2, a2, ax, bx);
  by = select_less(b2, a2, ay, by);
  ax = sx;
  ay = sy;
  const Lanes aa = ax * ax + ay * ay, ab = ax * bx + ay * by;
  for (int k = 0; k < 4; ++k)
    if (lane(aa, k) > 0.0 && std::fabs(lane(ab, k)) > 0.5 * lane(aa, k)) return false;
  const Lanes zero = splat(0.0);
  const auto abs = [&](const Lanes& v) { return select_less(v, zero, -v, v); };
  // a the more nearly horizontal (domain_half_widths); a_x^2 |b|^2 < b_x^2
  // |a|^2 picks b.
  const Lanes pick_b = select_less(ax * ax * (bx * bx + by * by), bx * bx * (ax * ax + ay * ay),
                                   splat(1.0), zero);
  const Lanes wx = abs(select_less(zero, pick_b, bx, ax)), wy = abs(select_less(zero, pick_b, ay, by));
  const Lanes V = load_lanes(P.vol + p);
  const double floor = 1e-3 * c.lp, cap = 0.5 * h;
  const Lanes t = c.lp * square_root(V / (load_lanes(P.vol0 + p) * wx * wy));
  const Lanes mx = select_less(splat(floor), t * wx, t * wx, splat(floor));
  const Lanes my = select_less(splat(floor), t * wy, t * wy, splat(floor));
  // Lanes whose V, wx or wy is not positive keep lp, as in domain_half_widths.
  const Lanes ok = select_less(zero, V, select_less(zero, wx, select_less(zero, wy, splat(1.0), zero), zero),
                               zero);
  lx = select_less(zero, ok, select_less(mx, splat(cap), mx, splat(cap)), lx);
  ly = select_less(zero, ok, select_less(my, splat(cap), my, splat(cap)), ly);
  return true;
}

// domain_half_widths of particles p .. p + 3 into lx[0 .. 3] and
// ly[0 .. 3]: four at a time, or one at a time where a lane's basis needs
// reducing.
inline void domain_half_widths_4(const ParticleView& P, int p, const StepConfig& c, double h,
                                 double* lx, double* ly) {
  Lanes wx, wy;
  if (domain_half_widths_x4(P, p, c, h, wx, wy)) {
    store_lanes(lx, wx);
    store_lanes(ly, wy);
    return;
  }
  for (int k = 0; k < 4; ++k) domain_half_widths(P, p + k, c, h, lx[k], ly[k]);
}

// The GIMP stencils (stencil_at) of four particles at (x, y) with
// half-widths (lx, ly), lane k particle k's, into s[0 .. 3], written in
// place, without the copies of a Stencil1D and set_stencil. kDerivatives
// false: the derivatives (s[k].d) are left unset, for the passes that do
// not read them.
template <bool kDerivatives = true>
inline void gimp_stencils_x4(const GridView& g, const Lanes& x, const Lanes& y, const Lanes& lx,
                             const Lanes& ly, Stencil2D s[4]) {
  const Lanes ux = grid_coordinate(x, g.ox, g.h), uy = grid_coordinate(y, g.oy, g.h);
  const Lanes cx = floor_lanes(ux), cy = floor_lanes(uy);
  const Lanes fx = ux - cx, fy = uy - cy;
  // 1 / h once, not in every lane (gimp_scale)
  const Lanes inv_h = splat(1.0 / g.h);
  Lanes wx[kStencilNodes], dwx[kStencilNodes] = {}, wy[kStencilNodes], dwy[kStencilNodes] = {};
  gimp_cell_nodes<kDerivatives>(fx, GimpScaleOf<Lanes>{splat(g.h), lx, inv_h, 1.0 / (g.h * lx)},
                                wx, dwx);
  gimp_cell_nodes<kDerivatives>(fy, GimpScaleOf<Lanes>{splat(g.h), ly, inv_h, 1.0 / (g.h * ly)},
                                wy, dwy);
  // One direction's part of one particle's stencil.
  const auto set = [](int& first, double* w, double* dw, double& r0, double& l, int first_node,
                      double offset, const Lanes& wl, const Lanes& dwl, double half_width) {
    first = first_node;
    store_lanes(w, wl);
    if (kDerivatives) store_lanes(dw, dwl);
    r0 = offset;
    l = half_width;
  };
  stencil_1d_x4<kDerivatives>(x, g.ox, g.h, cx, fx, wx, dwx, StencilStart::CellLeft,
                              [&](int q, int first, double r0, const Lanes& wl, const Lanes& dwl) {
                                Stencil2D& t = s[q];
                                set(t.w.first_x, t.w.wx, t.d.dwx, t.r.r0x, t.r.lx, first, r0, wl,
                                    dwl, lane(lx, q));
                              });
  stencil_1d_x4<kDerivatives>(y, g.oy, g.h, cy, fy, wy, dwy, StencilStart::Nearest,
                              [&](int q, int first, double r0, const Lanes& wl, const Lanes& dwl) {
                                Stencil2D& t = s[q];
                                set(t.w.first_y, t.w.wy, t.d.dwy, t.r.r0y, t.r.ly, first, r0, wl,
                                    dwl, lane(ly, q));
                              });
}

// Visits the 4 x 3 nodes of a stencil (one of each row's four has zero
// weight): f(node, N, dN/dx, dN/dy, rx, ry), with (rx, ry) = x_i - x_p the
// node's offset from the particle.
template <class St, class F>
RUNOUT_HD inline void for_each_node(const GridView& g, const St& s, F&& f) {
  for (int b = 0; b < 3; ++b) {
    const double ry = s.r.r0y + b * g.h;
    for (int a = 0; a < kStencilNodes; ++a) {
      const int node = g.index(s.w.first_x + a, s.w.first_y + b);
      f(node, s.w.wx[a] * s.w.wy[b], s.d.dwx[a] * s.w.wy[b], s.w.wx[a] * s.d.dwy[b],
        s.r.r0x + a * g.h, ry);
    }
  }
}

// The hot stages visit a stencil row by row: f(n0, wy, dwy, ry) for each of
// its three rows, n0 the row's first node; the row's nodes n0 .. n0 + 3 lie
// side by side in every nodal array, with weights wx wy and gradients
// (dwx wy, wx dwy), wx and dwx the stencil's x lanes (Lanes, lanes.hpp).
// The scatter functor adds a row at once (add(a, n0, lanes)).
// (Stages that do not use dwy or ry do not read them: the calls inline.)
template <class St, class F>
RUNOUT_HD inline void for_each_row(const GridView& g, const St& s, F&& f) {
  for (int b = 0; b < 3; ++b)
    f(g.index(s.w.first_x, s.w.first_y + b), s.w.wy[b], s.d.dwy[b], s.r.r0y + b * g.h);
}

// Two nodal fields interpolated at the particle: sum N a and sum N b.
template <class St>
RUNOUT_HD inline void interpolate(const GridView& g, const St& st, const double* a,
                                  const double* b, double& at_a, double& at_b) {
  const Lanes wx = load_lanes(st.w.wx);
  Lanes sa = splat(0.0), sb = sa;
  for_each_row(g, st, [&](int n0, double wy, double, double) {
    const Lanes N = wx * wy;
    sa = sa + N * load_lanes(a + n0);
    sb = sb + N * load_lanes(b + n0);
  });
  const Lanes sums = lane_sums(sa, sb, splat(0.0), splat(0.0));
  at_a = lane(sums, 0);
  at_b = lane(sums, 1);
}

// The particle's velocity at offset (rx, ry) from it: v_p + C_p r, the
// affine field APIC transfers (C = 0 under PIC/FLIP).
struct AffineVelocity {
  double vx, vy, cxx, cxy, cyx, cyy;
  // At a stencil row's nodes: offsets rx along the row, ry across it.
  RUNOUT_HD Lanes x(const Lanes& rx, double ry) const { return cxx * rx + (vx + cxy * ry); }
  RUNOUT_HD Lanes y(const Lanes& rx, double ry) const { return cyx * rx + (vy + cyy * ry); }
};

RUNOUT_HD inline AffineVelocity affine_velocity(const ParticleView& P, int p) {
  return {P.vx[p], P.vy[p], P.cxx[p], P.cxy[p], P.cyx[p], P.cyy[p]};
}

// The velocity a scatter carries: the affine field under APIC; under the
// other transfers C is zero, so its arrays are not read and the scatters
// use vx, vy alone, which v.x(rx, ry) would equal to the bit.
RUNOUT_HD inline AffineVelocity particle_velocity(const ParticleView& P, int p, bool affine) {
  return affine ? affine_velocity(P, p) : AffineVelocity{P.vx[p], P.vy[p], 0.0, 0.0, 0.0, 0.0};
}

// The gap between a particle's domain and the base: its signed distance to
// the base less the half-extent of its rectangle of half-widths lx, ly
// along the normal, lx |n_x| + ly |n_y|. Zero for a particle resting on the
// base, negative for one pressed into it. lp = h / (2 ppc) is half the
// particle spacing, so a linear-shape point stands for the same square.
template <class St>
RUNOUT_HD inline double particle_gap(const St& st, const BasePoint& b) {
  return b.d - (st.r.lx * std::fabs(b.nx) + st.r.ly * std::fabs(b.ny));
}

}  // namespace runout
