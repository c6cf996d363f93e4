#pragma once
// One explicit MPM step, stage by stage, as per-particle and per-node
// functions. They take plain views and a scatter functor, hold no state and
// allocate nothing, so the CPU driver (simulation.cpp) and a CUDA kernel can
// call them unchanged.
//
// The step is MUSL (modified update-stress-last, Sulsky et al. 1995):
//   1. p2g:            m_i, p_i = sum N m v, f_i = sum -V sigma grad N,
//                      gap_i = min over the node's particles of their gap to the base
//   2. grid_update:    v0_i = p_i/m_i, v_i = v0_i + dt (f_i/m_i + g), Geo-contact with
//                      the rigid base where the material reaches it, boundary
//                      conditions
//   3. g2p:            FLIP, v_p += sum N (v_i - v0_i), with an optional PIC
//                      share at a physical rate; or APIC, v_p = sum N v_i
//                      and the affine velocity C_p; or a per-step blend
//   4. p2g_momentum:   p_i = sum N m (v_p + C_p (x_i - x_p))   (the MUSL remap)
//   5. remap_velocity: v_i = p_i/m_i and the mid-step vm_i = (v0_i + v_i)/2,
//                      contact kinematics, boundary conditions
//   6. velocity_gradient, displacement: L = sum v_i (x) grad N (its
//                      volumetric part averaged per cell against locking),
//                      step displacement dt sum N vm_i
//   7. stress_update:  volume, F, Jaumann stress; then move
// MUSL rather than USL because the stress is computed from the remapped
// velocity: at nodes with a tiny share of mass (free surface, a particle
// entering a cell) v0 + dt f/m is spurious, and USL turns it into stress.
// The price is a second scatter of momentum. Every stage evaluates the
// shape functions at the positions of the start of the step, so the
// particle moves only in the last stage.
#include <algorithm>
#include <cmath>

#include "runout/base.hpp"
#include "runout/grid.hpp"
#include "runout/lanes.hpp"
#include "runout/host_device.hpp"
#include "runout/material.hpp"
#include "runout/particles.hpp"
#include "runout/shape.hpp"

namespace runout {

struct StepConfig {
  ShapeKind shape = ShapeKind::Gimp;
  DomainKind domain = DomainKind::Deforming;
  double lp = 0;                 // initial GIMP particle half-width h / (2 ppc)
  double gx = 0, gy = 0;         // full gravity
  double gravity_scale = 1;      // this step's share of it (gravity_factor)
  double gravity_ramp = 0;       // [s], GravitySpec::ramp
  TransferKind transfer = TransferKind::Flip;
  double flip = 0.99;            // PIC/FLIP blend, TransferKind::PicFlip
  double pic_time = 0;           // [s], TransferKind::Flip
  double flip_step = 0.99;       // this step's FLIP share (flip_share)
  double min_node_mass = 0;      // nodes at or below this are not accelerated
  double damping = 0;            // Cundall local damping coefficient
  // Boundary conditions on the domain's sides; the domain spans global
  // nodes 0..domain_nx by 0..domain_ny, and ghost nodes beyond a side take
  // that side's condition.
  BoundaryKind left = BoundaryKind::Slip, right = BoundaryKind::Slip;
  BoundaryKind bottom = BoundaryKind::Fixed, top = BoundaryKind::Free;
  int domain_nx = 0, domain_ny = 0;
  // Periodic along x (left and right BoundaryKind::Periodic): the period
  // L = domain_nx h from domain_x0; 0: not periodic.
  double period = 0, domain_x0 = 0;
  // The rigid base and its interface (Geo-contact); base.kind None: none.
  BaseView base;
  InterfaceKind interface = InterfaceKind::NoSlip;
  double shear_strength = 0;     // tau, Frictional
  double friction = 0;           // mu, Coulomb
  int xpic_order = 5;            // m of XPIC(m)
  double xpic_period = 0;        // [s] FLIP with an XPIC step every period
  bool xpic_now = false;         // this step is an XPIC one
};

// The largest Courant number a scene may ask for. Measured with FLIP,
// GIMP and lattice-reduced deforming domains (docs/convergence.md,
// "Courant limit"): the coarse case 2 runout at 12 s is 19.35, 19.26,
// 19.49 and 19.64 m at Courant 0.05, 0.1, 0.2 and 0.25, and 19.91 m at
// 0.3, 2.9 % above 0.05; beyond 0.25 the time step is part of the answer.
// The column collapse moves 0.4 % up to 1.0. The other transfers and
// linear shape functions are held to the same limit.
inline double max_courant(ShapeKind, TransferKind) { return 0.25; }

// Per-particle scratch of one step: the displacement, applied at the end,
// of particle p at dx[p - first], dy[p - first]: over all particles
// (first 0), or over a CPU cell group's (a buffer of its own, from its
// lowest particle index).
struct StepScratch {
  double *dx, *dy;
  int first = 0;
  RUNOUT_HD int at(int p) const { return p - first; }
};

// The share of gravity acting at time t: all of it, or with a ramp of
// length T > 0 the half cosine (1 - cos(pi t / T)) / 2, which starts and
// ends with zero rate, so the slide is loaded without the shock of a sudden
// start (the elastic waves of gravity switched on at once in a stress-free
// body, which a soft clay yields under before it has its own weight).
RUNOUT_HD inline double gravity_factor(double t, double ramp) {
  if (!(ramp > 0.0) || t >= ramp) return 1.0;
  return 0.5 * (1.0 - std::cos(3.14159265358979323846 * t / ramp));
}

// The FLIP share of a step of length dt. Flip: exp(-dt / T), so the PIC
// share 1 - exp(-dt / T) relaxes the particle velocity towards the grid's
// at the rate 1 / T whatever dt is (over a time t, exp(-t / T) is left,
// however many steps it takes); T = 0: pure FLIP. PicFlip: the scene's
// blend, fixed per step. APIC: unused.
RUNOUT_HD inline double flip_share(TransferKind transfer, double blend, double pic_time,
                                   double dt) {
  if (transfer != TransferKind::Flip) return blend;
  return pic_time > 0.0 ? std::exp(-dt / pic_time) : 1.0;
}

// The parts of the configuration that depend on the step: the gravity of
// its mid-time, its FLIP share and whether it is an XPIC step. Both
// drivers call it before a step.
RUNOUT_HD inline void configure_step(StepConfig& c, double t, double dt) {
  c.gravity_scale = gravity_factor(t + 0.5 * dt, c.gravity_ramp);
  c.flip_step = flip_share(c.transfer, c.flip, c.pic_time, dt);
  const double T = c.xpic_period;  // the steps that cross a multiple of T
  c.xpic_now = c.transfer == TransferKind::Xpic ||
               (T > 0.0 && std::floor((t + dt) / T) > std::floor(t / T));
}

// P-wave speed sqrt(M / rho) at the current density plus the particle's
// speed: the signal speed of the CFL condition dt = C h / max(c + |v|).
// T: double for one particle, Lanes for four (stress_update_x4).
template <class T>
RUNOUT_HD inline T signal_speed(const T& mass, const T& vol, const T& vx, const T& vy,
                                const MaterialParams& mat) {
  const T rho = mass / vol;
  const T speed = square_root(vx * vx + vy * vy);
  return square_root(p_wave_modulus(mat) / rho) + speed;
}

RUNOUT_HD inline double cfl_speed(const ParticleView& P, int p, const MaterialParams& mat) {
  return signal_speed(P.mass[p], P.vol[p], P.vx[p], P.vy[p], mat);
}

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

// Stage 1. add(array, node, value) does array[node] += value and
// lower(array, node, value) array[node] = min(array[node], value): plain
// operations under the CPU's colouring, atomics on a GPU. The nodal gap is
// the smallest gap of the particles a node sees, so it is zero where any of
// them rests on the base: the material there touches it.
template <class St, class Add, class Lower>
RUNOUT_HD inline void p2g(const ParticleView& P, int p, const St& st, const GridView& g,
                          const StepConfig& c, Add&& add, Lower&& lower) {
  const double m = P.mass[p], V = P.vol[p];
  const bool affine = c.transfer == TransferKind::Apic;
  const AffineVelocity v = particle_velocity(P, p, affine);
  // The internal force -V sigma grad N, with V sigma formed once rather
  // than at each of the nine nodes; gravity is added at the node
  // (grid_update).
  const double vsxx = V * P.sxx[p], vsyy = V * P.syy[p], vsxy = V * P.sxy[p];
  // Nodes on or inside the base (distance <= 0) are the only ones that read
  // the gap and the volume (geo_contact's interface area), and a particle
  // reaches nodes at most h + lp away along x and y, so at most
  // sqrt(2) (h + lp) away: the distance is 1-Lipschitz.
  bool near_base = false;
  double gap = 0.0;
  if (c.base.kind != BaseKind::None) {
    const BasePoint b = locate_on_base(c.base, P.x[p], P.y[p]);
    near_base = b.d < std::sqrt(2.0) * (g.h + std::max(st.r.lx, st.r.ly));
    gap = particle_gap(st, b);
  }
  const Lanes wx = load_lanes(st.w.wx), dwx = load_lanes(st.d.dwx);
  const Lanes rx = lane_offsets(st.r.r0x, g.h);
  for_each_row(g, st, [&](int n0, double wy, double dwy, double ry) {
    // (no zero-weight test: adding an exact zero changes no sum)
    const Lanes Nm = wx * wy * m, dNx = dwx * wy, dNy = wx * dwy;
    add(g.m, n0, Nm);
    add(g.px, n0, affine ? Nm * v.x(rx, ry) : Nm * v.vx);
    add(g.py, n0, affine ? Nm * v.y(rx, ry) : Nm * v.vy);
    add(g.fx, n0, -(vsxx * dNx + vsxy * dNy));
    add(g.fy, n0, -(vsxy * dNx + vsyy * dNy));
  });
  if (!near_base) return;
  for_each_node(g, st, [&](int n, double N, double, double, double, double) {
    add(g.vol, n, N * V);
    if (N > 0.0) lower(g.gap, n, gap);
  });
}

// Projects a nodal velocity onto the domain's boundary conditions.
RUNOUT_HD inline void constrain(const GridView& g, const StepConfig& c, int n, double& vx,
                                double& vy) {
  const int gi = g.i0 + n % g.nx;
  const int gj = g.j0 + n / g.nx;
  auto apply = [&](BoundaryKind kind, bool normal_is_x) {
    if (kind == BoundaryKind::Fixed) {
      vx = 0.0;
      vy = 0.0;
    } else if (kind == BoundaryKind::Slip) {
      (normal_is_x ? vx : vy) = 0.0;
    }
  };
  if (gi <= 0) apply(c.left, true);
  if (gi >= c.domain_nx) apply(c.right, true);
  if (gj <= 0) apply(c.bottom, false);
  if (gj >= c.domain_ny) apply(c.top, false);
}

// Whether node n lies on or inside the rigid base, and the base's outward
// normal there. The tolerance keeps nodes on a planar base line in contact
// despite the rounding of their coordinates.
RUNOUT_HD inline bool base_contact_normal(const GridView& g, const StepConfig& c, int n,
                                          double& nx, double& ny) {
  if (c.base.kind == BaseKind::None) return false;
  const BasePoint b =
      locate_on_base(c.base, g.ox + (n % g.nx) * g.h, g.oy + (n / g.nx) * g.h);
  nx = b.nx;
  ny = b.ny;
  return b.d <= 1e-9 * g.h;
}

// The speed at which a base node's material closes its gap to the base
// within the step, gap_i / dt; zero where it touches (a gap below the
// rounding of the base's position). The same on every interface, so a
// no-slip base is a frictional one whose limit is never reached: holding
// approach at zero on a no-slip base instead made the coarse case 2 runout
// grow from 24.9 m at Courant 0.05 to 39.2 m at 0.3 under FLIP, where the
// frictional path gives 14.2 m at both (docs/convergence.md).
RUNOUT_HD inline double closing_speed(const GridView& g, int n, double dt) {
  const double gap = g.gap[n];
  return gap > 1e-9 * g.h ? gap / dt : 0.0;
}

// Geo-contact at a base node (SCENES.md): the velocity towards the base
// beyond closing the material's gap to it within the step, -gap / dt, is
// removed (separation is free, and so is coming back: a base node stands
// for the material up to a cell above the base, and with approach removed
// outright, as in a velocity-only contact check (Bardenhagen et al. 2000),
// material that an elastic rebound lifted off the base could never fall
// back: a sliding block crept upwards, losing interface share 2 V_i / h,
// and accelerated 2 % too fast. The gap is a displacement check in the
// sense of Nairn et al. 2018); the tangential velocity is removed
// (no-slip) or reduced by min(|v_t|, tau A dt / m) (frictional) or by
// min(|v_t|, mu |dv_n|) (Coulomb: the tangential impulse at most mu times
// the normal one, Bardenhagen et al. 2001). A = 2 V_i / h is the node's
// share of the interface: a base node of a full row carries half a cell of
// volume, h^2 / 2, and so h of interface, and a partly covered one its part.
// Returns the tangential force of the base on the slide along the base
// direction (+s), m dv / dt, negative while it resists down-slope motion,
// and whether the tangential velocity was removed whole (the node sticks:
// always on a no-slip base).
struct ContactResult {
  double force;
  bool stuck;
};

RUNOUT_HD inline ContactResult geo_contact(const StepConfig& c, double m, double vol, double h,
                                           double dt, double closing, double nx, double ny,
                                           double& vx, double& vy) {
  const double vn = vx * nx + vy * ny;
  const double dvn = vn < -closing ? -closing - vn : 0.0;
  vx += dvn * nx;
  vy += dvn * ny;
  const double tx = ny, ty = -nx;  // +s direction: the normal turned clockwise
  const double vt = vx * tx + vy * ty;
  double limit = std::fabs(vt);
  if (c.interface == InterfaceKind::Frictional) {
    limit = c.shear_strength * (2.0 * vol / h) * dt / m;
  } else if (c.interface == InterfaceKind::Coulomb) {
    limit = c.friction * dvn;
  }
  const bool stuck = std::fabs(vt) <= limit;
  const double dvt = std::fmin(std::fabs(vt), limit) * (vt < 0.0 ? -1.0 : 1.0);
  vx -= dvt * tx;
  vy -= dvt * ty;
  return {-m * dvt / dt, stuck};
}

// A velocity less its part along the base (+s, the normal (nx, ny) turned
// clockwise): what a stuck node keeps of its start velocity, in grid_update
// and in XPIC's round trips alike (B in xpic_term's comment).
RUNOUT_HD inline void hold_tangential(double nx, double ny, double& vx, double& vy) {
  const double tx = ny, ty = -nx;
  const double vt = vx * tx + vy * ty;
  vx -= vt * tx;
  vy -= vt * ty;
}

// The kinematic part of Geo-contact, for velocities that carry no impulse
// of their own (the mid-step and remapped velocities): no approach beyond
// closing the gap, and no slip where grid_update held the node still, so a
// frictional base whose limit is not reached strains the slide as a
// no-slip one does.
RUNOUT_HD inline void contact_kinematics(bool stuck, double closing, double nx, double ny,
                                         double& vx, double& vy) {
  const double vn = vx * nx + vy * ny;
  if (stuck) {
    const double kept = std::fmax(vn, -closing);
    vx = kept * nx;
    vy = kept * ny;
  } else if (vn < -closing) {
    vx -= (vn + closing) * nx;
    vy -= (vn + closing) * ny;
  }
}

// Stage 2. Cundall's local damping, f - alpha |f| sign(v) per component,
// removes energy without a viscosity scale, for quasi-static settling.
// The velocity of a node at or below min_node_mass: a node at the edge of
// the particles' support, with a sliver of their mass, is not accelerated
// (f / m would be huge) but moves with them at p / m, the mass-weighted
// mean of their velocities, under the boundary conditions. Held at zero,
// it put a spurious gradient v dN into every particle beside it (a rigid
// translation built stress wherever a particle's support edge came within
// 1e-4 h of a node).
RUNOUT_HD inline void light_node_velocity(const GridView& g, const StepConfig& c, int n,
                                          double& vx, double& vy) {
  const double m = g.m[n];
  vx = m > 0.0 ? g.px[n] / m : 0.0;
  vy = m > 0.0 ? g.py[n] / m : 0.0;
  constrain(g, c, n, vx, vy);
}

// The node's momentum is spent here: px, py are left zero for the scatter
// of the remapped momentum (stage 4), which then needs no clearing pass.
RUNOUT_HD inline void grid_update(const GridView& g, int n, const StepConfig& c, double dt) {
  const double m = g.m[n];
  if (m <= c.min_node_mass) {
    double vx, vy;
    light_node_velocity(g, c, n, vx, vy);
    g.px[n] = g.py[n] = 0.0;
    g.v0x[n] = g.vx[n] = vx;
    g.v0y[n] = g.vy[n] = vy;
    g.dvx[n] = g.dvy[n] = 0.0;
    g.fbase[n] = g.stuck[n] = 0.0;
    return;
  }
  double v0x = g.px[n] / m, v0y = g.py[n] / m;
  g.px[n] = g.py[n] = 0.0;
  // Gravity as m_i g: the same force as the particles' sum N m_p g (their
  // weights sum their masses into m_i), formed once per node rather than
  // at each of every particle's nine.
  const double gs = c.gravity_scale;
  double fx = g.fx[n] + m * gs * c.gx, fy = g.fy[n] + m * gs * c.gy;
  if (c.damping > 0.0) {
    fx -= c.damping * std::fabs(fx) * (v0x > 0.0 ? 1.0 : (v0x < 0.0 ? -1.0 : 0.0));
    fy -= c.damping * std::fabs(fy) * (v0y > 0.0 ? 1.0 : (v0y < 0.0 ? -1.0 : 0.0));
  }
  double vx = v0x + dt * fx / m, vy = v0y + dt * fy / m;
  double nx, ny;
  g.fbase[n] = 0.0;
  g.stuck[n] = 0.0;
  if (base_contact_normal(g, c, n, nx, ny)) {
    const ContactResult r =
        geo_contact(c, m, g.vol[n], g.h, dt, closing_speed(g, n, dt), nx, ny, vx, vy);
    g.fbase[n] = r.force;
    if (r.stuck) {
      // The node's material is held still, and so is its start velocity:
      // that is a projection of particle velocities from up to a cell above
      // the base, and left in, FLIP would take it off those particles at
      // every step, a damping at the rate 1 / dt (the Courant dependence of
      // no-slip runouts, docs/convergence.md). The base then acts through
      // the strain rate it imposes, with the reaction -f_t, as a fixed
      // node does in CB-Geo mpm and MPM-Geomechanics.
      hold_tangential(nx, ny, v0x, v0y);
      g.fbase[n] = -(fx * ny - fy * nx);  // along +s = (ny, -nx)
      g.stuck[n] = 1.0;
    }
  }
  constrain(g, c, n, vx, vy);
  g.v0x[n] = v0x;
  g.v0y[n] = v0y;
  g.vx[n] = vx;
  g.vy[n] = vy;
  g.dvx[n] = vx - v0x;
  g.dvy[n] = vy - v0y;
}

// Stage 3. APIC (Jiang et al. 2015): the particle takes the grid velocity
// v_p = sum N v_i and its affine part C_p = B_p D_p^-1, with
// B_p = sum N v_i r^T and D_p = sum N r r^T (r = x_i - x_p), which the
// next transfers carry to the grid. An affine velocity field goes through
// the round trip unchanged, and with it rigid rotation and uniform shear;
// only the part of the field the grid cannot hold is filtered, so there is
// no fixed share of velocity lost per step and no null-space noise kept.
// D is diagonal (GIMP and linear weights reproduce linear fields, so
// sum N r = 0). A linear-shape particle on a node has D_xx = 0, where
// B_xx / D_xx tends to the cell gradient sum v_i dN_i/dx; that is used
// where D is degenerate.
// PIC/FLIP: FLIP carries the particle's own velocity plus the grid's change
// (little dissipation), PIC takes the grid velocity; a per-step blend damps
// at a rate (1 - flip) / dt, which grows as the step shrinks.
template <class St>
RUNOUT_HD inline void g2p_apic(const ParticleView& P, int p, const St& st,
                               const GridView& g) {
  double vx = 0, vy = 0, bxx = 0, bxy = 0, byx = 0, byy = 0, dxx = 0, dyy = 0;
  double gxx = 0, gxy = 0, gyx = 0, gyy = 0;
  for_each_node(g, st, [&](int n, double N, double dNx, double dNy, double rx, double ry) {
    const double ux = g.vx[n], uy = g.vy[n];
    vx += N * ux;
    vy += N * uy;
    bxx += N * ux * rx;
    bxy += N * ux * ry;
    byx += N * uy * rx;
    byy += N * uy * ry;
    dxx += N * rx * rx;
    dyy += N * ry * ry;
    gxx += ux * dNx;
    gxy += ux * dNy;
    gyx += uy * dNx;
    gyy += uy * dNy;
  });
  const double degenerate = 1e-12 * g.h * g.h;
  const bool use_x = dxx > degenerate, use_y = dyy > degenerate;
  P.vx[p] = vx;
  P.vy[p] = vy;
  P.cxx[p] = use_x ? bxx / dxx : gxx;
  P.cyx[p] = use_x ? byx / dxx : gyx;
  P.cxy[p] = use_y ? bxy / dyy : gxy;
  P.cyy[p] = use_y ? byy / dyy : gyy;
}

template <class St>
RUNOUT_HD inline void g2p(const ParticleView& P, int p, const St& st, const GridView& g,
                          const StepConfig& c) {
  if (c.transfer == TransferKind::Apic) {
    g2p_apic(P, p, st, g);
    return;
  }
  const Lanes wx = load_lanes(st.w.wx);
  if (c.xpic_now) {
    Lanes ux = splat(0.0), uy = ux;
    for_each_row(g, st, [&](int n0, double wy, double, double) {
      const Lanes N = wx * wy;
      ux = ux + N * (load_lanes(g.dvx + n0) + load_lanes(g.xvx + n0));
      uy = uy + N * (load_lanes(g.dvy + n0) + load_lanes(g.xvy + n0));
    });
    const Lanes u = lane_sums(ux, uy, splat(0.0), splat(0.0));
    P.vx[p] = lane(u, 0);
    P.vy[p] = lane(u, 1);
    return;
  }
  // The change sum N (v - v0) from the grid update's v - v0 at the nodes:
  // pure FLIP (flip_step 1, the default) reads two nodal arrays, not four.
  double dvx, dvy;
  if (c.flip_step == 1.0) {
    interpolate(g, st, g.dvx, g.dvy, dvx, dvy);
    P.vx[p] += dvx;
    P.vy[p] += dvy;
    return;
  }
  Lanes ux = splat(0.0), uy = ux, dx = ux, dy = ux;
  for_each_row(g, st, [&](int n0, double wy, double, double) {
    const Lanes N = wx * wy;
    ux = ux + N * load_lanes(g.vx + n0);
    uy = uy + N * load_lanes(g.vy + n0);
    dx = dx + N * load_lanes(g.dvx + n0);
    dy = dy + N * load_lanes(g.dvy + n0);
  });
  const Lanes sums = lane_sums(ux, uy, dx, dy);
  const double pic_x = lane(sums, 0), pic_y = lane(sums, 1);
  dvx = lane(sums, 2);
  dvy = lane(sums, 3);
  P.vx[p] = c.flip_step * (P.vx[p] + dvx) + (1.0 - c.flip_step) * pic_x;
  P.vy[p] = c.flip_step * (P.vy[p] + dvy) + (1.0 - c.flip_step) * pic_y;
}

// XPIC(m) (Hammerquist and Nairn 2017). With S the interpolation to the
// particles, S+ the mass-weighted projection to the nodes and B the
// constraints grid_update puts on the start velocity (a stuck base node
// holds it still), P = S B S+ maps particle velocities to the part the
// grid holds, and v0 = B S+ v_p. FLIP keeps v_p - P v_p, all that the grid
// cannot hold, including modes no node ever sees (its null space); PIC
// drops it with everything sub-cell. XPIC(m) replaces v_p in the FLIP
// update by v* = (I - (I - P)^m) v_p = sum_k (-1)^(k+1) C(m,k) P^k v_p,
// which removes the null space (P e = 0 leaves (I - P)^m e = e), and of a
// mode that one round trip keeps to 1 - eps it keeps 1 - eps^m. Since
// P^k v_p = S Q^(k-1) v0 with Q = B S+ S, the update is the interpolation of
// one grid field, v_p = S (v - v0 + V*), V* = sum_k (-1)^(k+1) C(m,k)
// Q^(k-1) v0, built by m - 1 round trips on the grid: xpic_start, then
// p2g_smoothed and xpic_term for k = 2 .. m. XPIC(1) is PIC.
RUNOUT_HD inline double xpic_coefficient(int m, int k) {
  double c = 1.0;  // C(m, k)
  for (int i = 1; i <= k; ++i) c = c * (m - k + i) / i;
  return k % 2 == 1 ? c : -c;
}

RUNOUT_HD inline void xpic_start(const GridView& g, int n, const StepConfig& c) {
  g.qx[n] = g.v0x[n];
  g.qy[n] = g.v0y[n];
  const double a = xpic_coefficient(c.xpic_order, 1);
  g.xvx[n] = a * g.v0x[n];
  g.xvy[n] = a * g.v0y[n];
}

// S of the current term at the particle, scattered as momentum into px, py.
template <class St, class Add>
RUNOUT_HD inline void p2g_smoothed(const ParticleView& P, int p, const St& st,
                                   const GridView& g, Add&& add) {
  double ux, uy;
  interpolate(g, st, g.qx, g.qy, ux, uy);
  const double m = P.mass[p];
  const Lanes wx = load_lanes(st.w.wx);
  for_each_row(g, st, [&](int n0, double wy, double, double) {
    const Lanes Nm = wx * wy * m;
    add(g.px, n0, Nm * ux);
    add(g.py, n0, Nm * uy);
  });
}

// The next term, B S+ of the scattered momentum, added into V* with its
// coefficient.
RUNOUT_HD inline void xpic_term(const GridView& g, int n, const StepConfig& c, int k) {
  const double m = g.m[n];
  double ux = m > 0.0 ? g.px[n] / m : 0.0, uy = m > 0.0 ? g.py[n] / m : 0.0;
  double nx, ny;
  if (g.stuck[n] != 0.0 && base_contact_normal(g, c, n, nx, ny)) hold_tangential(nx, ny, ux, uy);
  g.qx[n] = ux;
  g.qy[n] = uy;
  const double a = xpic_coefficient(c.xpic_order, k);
  g.xvx[n] += a * ux;
  g.xvy[n] += a * uy;
}

// Stage 4: the MUSL remap of the updated particle momentum.
template <class St, class Add>
RUNOUT_HD inline void p2g_momentum(const ParticleView& P, int p, const St& st,
                                   const GridView& g, const StepConfig& c, Add&& add) {
  const double m = P.mass[p];
  const bool affine = c.transfer == TransferKind::Apic;
  const AffineVelocity v = particle_velocity(P, p, affine);
  const Lanes wx = load_lanes(st.w.wx), rx = lane_offsets(st.r.r0x, g.h);
  for_each_row(g, st, [&](int n0, double wy, double, double ry) {
    // (no zero-weight test, as in p2g: whether a weight is zero depends on
    // where the particle sits in its cell, so the branch was unpredictable)
    const Lanes Nm = wx * wy * m;
    add(g.px, n0, affine ? Nm * v.x(rx, ry) : Nm * v.vx);
    add(g.py, n0, affine ? Nm * v.y(rx, ry) : Nm * v.vy);
  });
}

// Stage 5. The remapped velocity v_i strains the particles (stage 6); the
// mid-step vm_i = (v0_i + v_i) / 2 moves them. Both nodal velocities are
// projections of particle velocities (at the start and at the end of the
// step), so the particles move as the velocity that strains them says:
// the displacement's gradient and the strain increment differ by
// dt grad(v0 - v) / 2, which telescopes over the steps. Moving them with
// the grid update's (v0 + v0 + dt f/m) / 2 instead, as MUSL usually does,
// leaves dt^2 grad((1/2 - S) a) a step between the two (S the projection
// of the interpolated acceleration a), which under a contact's one-signed
// accelerations adds up: the particle spacing drifts with no strain and no
// stress to pull it back (a block ringing on the base grew taller by
// 1 mm a second). The trapezoidal rule is exact under constant acceleration:
// x0 + v0 t + g t^2 / 2 at any dt, where x += dt v would be off by g t dt / 2.
RUNOUT_HD inline void remap_velocity(const GridView& g, int n, const StepConfig& c, double dt) {
  const double m = g.m[n];
  if (m <= c.min_node_mass) {
    double vx, vy;
    light_node_velocity(g, c, n, vx, vy);
    g.vmx[n] = 0.5 * (g.v0x[n] + vx);
    g.vmy[n] = 0.5 * (g.v0y[n] + vy);
    g.vx[n] = vx;
    g.vy[n] = vy;
    return;
  }
  double vx = g.px[n] / m, vy = g.py[n] / m;
  double vmx = 0.5 * (g.v0x[n] + vx), vmy = 0.5 * (g.v0y[n] + vy);
  double nx, ny;
  if (base_contact_normal(g, c, n, nx, ny)) {
    const double closing = closing_speed(g, n, dt);
    const bool stuck = g.stuck[n] != 0.0;
    contact_kinematics(stuck, closing, nx, ny, vx, vy);
    contact_kinematics(stuck, closing, nx, ny, vmx, vmy);
  }
  constrain(g, c, n, vx, vy);
  constrain(g, c, n, vmx, vmy);
  g.vx[n] = vx;
  g.vy[n] = vy;
  g.vmx[n] = vmx;
  g.vmy[n] = vmy;
}

// Velocity gradient L_ab = sum_i v_ia dN_i/dx_b.
struct VelocityGradient {
  double xx, xy, yx, yy;
};

// Stage 6a: L from the remapped velocity.
template <class St>
RUNOUT_HD inline VelocityGradient velocity_gradient(const St& st, const GridView& g) {
  const Lanes wx = load_lanes(st.w.wx), dwx = load_lanes(st.d.dwx);
  Lanes xx = splat(0.0), xy = xx, yx = xx, yy = xx;
  for_each_row(g, st, [&](int n0, double wy, double dwy, double) {
    const Lanes dNx = dwx * wy, dNy = wx * dwy;
    const Lanes ux = load_lanes(g.vx + n0), uy = load_lanes(g.vy + n0);
    xx = xx + ux * dNx;
    xy = xy + ux * dNy;
    yx = yx + uy * dNx;
    yy = yy + uy * dNy;
  });
  const Lanes L = lane_sums(xx, xy, yx, yy);
  return {lane(L, 0), lane(L, 1), lane(L, 2), lane(L, 3)};
}

// Stage 6b: the step displacement, applied in stress_update.
template <class St>
RUNOUT_HD inline void displacement(int p, const St& st, const GridView& g, double dt,
                                   const StepScratch& s) {
  double mid_x, mid_y;
  interpolate(g, st, g.vmx, g.vmy, mid_x, mid_y);
  s.dx[s.at(p)] = dt * mid_x;
  s.dy[s.at(p)] = dt * mid_y;
}

// Stage 6c (optional): volumetric locking relief. Undrained clay is nearly
// incompressible (nu = 0.49) and its plastic flow is isochoric; with shape
// functions linear in a cell, every particle's volumetric strain rate
// cannot vanish independently, the mesh locks and the slide is too stiff
// (a vertical cut at 1.4 Hc slumps half as far at 10 cells over its height).
// The driver replaces each particle's volumetric rate tr L by the
// volume-weighted mean of its cell, and after the stress update its mean
// stress by the cell's mean: one volumetric constraint and one pressure per
// cell, as in mixed (B-bar, Hughes 1980) elements and their MPM forms (Mast
// et al. 2012; Coombs et al. 2018). The deviatoric parts are untouched.
template <class T>
RUNOUT_HD inline void set_volumetric_rate(T& xx, T& yy, const T& trace) {
  const T shift = 0.5 * (trace - (xx + yy));
  xx = xx + shift;
  yy = yy + shift;
}

RUNOUT_HD inline void set_volumetric_rate(VelocityGradient& L, double trace) {
  set_volumetric_rate(L.xx, L.yy, trace);
}

// Stage 7. Volume by J = det(I + dt L), F by F <- (I + dt L) F (forward
// Euler on dF/dt = L F, consistent with J); stress rotated with the spin
// W = skew(L) (Jaumann rate) and then updated by the material with the
// strain increment dt sym(L). gamma_dot = sqrt((D_xx - D_yy)^2 + 4 D_xy^2),
// D = sym(L): the largest in-plane engineering shear strain rate (twice the
// radius of the in-plane Mohr circle of D), the rate conjugate to the
// Tresca shear stress; |dv_x/dy| in simple shear, and equal to
// sqrt(2 e:e) (e the deviator of D, D_zz = 0) for isochoric flow. Then the
// particle moves. Returns its P-wave speed plus its speed, for the CFL
// condition of the next step.
//
// StressStep is the part every particle computes alike, up to the elastic
// trial (the model's plastic correction follows), for one particle (T
// double) or four (T Lanes, stress_update_x4): in, the state at the start
// of the step; out, the updated volume and F, the trial stress and gamma_dot.
template <class T>
struct StressStep {
  T vol, fxx, fxy, fyx, fyy;
  T sxx, syy, sxy, szz;
  T gamma_dot;
};

template <class T>
RUNOUT_HD inline void stress_step(StressStep<T>& u, const T& xx, const T& xy, const T& yx,
                                  const T& yy, const MaterialParams& mat, double dt) {
  const T J = (1.0 + dt * xx) * (1.0 + dt * yy) - dt * dt * xy * yx;
  u.vol = u.vol * J;
  const T fxx = u.fxx, fxy = u.fxy, fyx = u.fyx, fyy = u.fyy;
  u.fxx = fxx + dt * (xx * fxx + xy * fyx);
  u.fxy = fxy + dt * (xx * fxy + xy * fyy);
  u.fyx = fyx + dt * (yx * fxx + yy * fyx);
  u.fyy = fyy + dt * (yx * fxy + yy * fyy);

  const T w = 0.5 * (xy - yx);  // spin W_xy
  const T sxx = u.sxx, syy = u.syy, sxy = u.sxy;
  u.sxx = sxx + 2.0 * w * sxy * dt;
  u.syy = syy - 2.0 * w * sxy * dt;
  u.sxy = sxy + w * (syy - sxx) * dt;

  const T Dxy = 0.5 * (xy + yx);
  u.gamma_dot = square_root((xx - yy) * (xx - yy) + 4.0 * Dxy * Dxy);
  elastic_increment(mat, dt * xx, dt * yy, dt * Dxy, u.sxx, u.syy, u.sxy, u.szz);
}

RUNOUT_HD inline void store_stress_point(const ParticleView& P, int p, const StressPoint& sp) {
  P.sxx[p] = sp.sxx;
  P.syy[p] = sp.syy;
  P.sxy[p] = sp.sxy;
  P.szz[p] = sp.szz;
  P.xi[p] = sp.xi;
  P.su[p] = sp.su;
}

RUNOUT_HD inline double stress_update(const ParticleView& P, int p, const VelocityGradient& L,
                                      const MaterialParams* materials, double dt,
                                      const StepScratch& s) {
  const MaterialParams& mat = materials[P.material[p]];
  StressStep<double> u{P.vol[p], P.fxx[p], P.fxy[p], P.fyx[p], P.fyy[p],
                       P.sxx[p], P.syy[p], P.sxy[p], P.szz[p], 0.0};
  stress_step(u, L.xx, L.xy, L.yx, L.yy, mat, dt);
  StressPoint sp{u.sxx, u.syy, u.sxy, u.szz, P.xi[p], P.su[p]};
  plastic_correction(mat, mat.strength.regularised ? P.gamma_dot[p] : u.gamma_dot, sp);

  P.vol[p] = u.vol;
  P.fxx[p] = u.fxx;
  P.fxy[p] = u.fxy;
  P.fyx[p] = u.fyx;
  P.fyy[p] = u.fyy;
  store_stress_point(P, p, sp);
  P.gamma_dot[p] = u.gamma_dot;
  P.x[p] += s.dx[s.at(p)];
  P.y[p] += s.dy[s.at(p)];
  return cfl_speed(P, p, mat);
}

// stress_update of particles p .. p + 3 of one material, lane k particle
// p + k's (the CPU backend): the kinematics, the elastic trial, the
// strength law's exp and pow and the signal speed four at a time, the
// yield check and return one particle at a time (a yielding particle
// iterates on its own). Its two square roots and two divisions a particle
// were most of the stage's time, each waiting on the one before it.
inline Lanes stress_update_x4(const ParticleView& P, int p, const Lanes& xx, const Lanes& xy,
                              const Lanes& yx, const Lanes& yy, const MaterialParams& mat,
                              double dt, const StepScratch& s) {
  const auto at = [p](const double* a) { return load_lanes(a + p); };
  StressStep<Lanes> u{at(P.vol), at(P.fxx), at(P.fxy), at(P.fyx), at(P.fyy),
                      at(P.sxx), at(P.syy), at(P.sxy), at(P.szz), splat(0.0)};
  stress_step(u, xx, xy, yx, yy, mat, dt);
  const bool tresca = mat.model == MaterialModel::Tresca;
  Lanes a = splat(1.0), b = splat(0.0), S = splat(1.0);
  // Tresca's yield check (tresca_return's first lines) four at a time:
  // where all four trials lie within the strength, nearly every particle of
  // a slide at nearly every step, they are the new stress as they are.
  bool elastic = !tresca;
  if (tresca) {
    rate_scaling_x4(mat.strength, mat.strength.regularised ? at(P.gamma_dot) : u.gamma_dot, a,
                    b);
    S = softening_x4(mat.strength, at(P.xi));
    const Lanes tau_trial = mohr_radius(u.sxx, u.syy, u.sxy);
    const Lanes su_trial = strength_at(mat.strength, a, b, S);
    elastic = true;
    for (int k = 0; k < 4; ++k) elastic = elastic && lane(tau_trial, k) <= lane(su_trial, k);
    if (elastic) store_lanes(P.su + p, su_trial);
  }
  if (elastic) {
    store_lanes(P.sxx + p, u.sxx);
    store_lanes(P.syy + p, u.syy);
    store_lanes(P.sxy + p, u.sxy);
    store_lanes(P.szz + p, u.szz);
  } else {
    for (int k = 0; k < 4; ++k) {
      StressPoint sp{lane(u.sxx, k), lane(u.syy, k), lane(u.sxy, k), lane(u.szz, k),
                     P.xi[p + k], P.su[p + k]};
      tresca_return(mat, RateScaling{lane(a, k), lane(b, k)}, lane(S, k), sp);
      store_stress_point(P, p + k, sp);
    }
  }
  store_lanes(P.vol + p, u.vol);
  store_lanes(P.fxx + p, u.fxx);
  store_lanes(P.fxy + p, u.fxy);
  store_lanes(P.fyx + p, u.fyx);
  store_lanes(P.fyy + p, u.fyy);
  store_lanes(P.gamma_dot + p, u.gamma_dot);
  store_lanes(P.x + p, at(P.x) + load_lanes(s.dx + s.at(p)));
  store_lanes(P.y + p, at(P.y) + load_lanes(s.dy + s.at(p)));
  return signal_speed(at(P.mass), u.vol, at(P.vx), at(P.vy), mat);
}

// Periodic along x, as halo exchange in a domain-decomposed MPM (ExaMPM,
// Cabana's periodic halos): the box spans the period and one ghost column
// below it and two above (global columns -1, N and N+1 of N cells), and
// the spare column of the stencil rows (N+2, never written but by zeros), where
// the stencils of particles near the seam reach. After a scatter each
// ghost's sums are added into the column it repeats (N - 1, 0 and 1) and
// copied back, so the nodes on both sides of the seam hold the same sums;
// after a node stage the results are copied out again, so that every
// stage downstream reads one value per physical node. The scatter itself
// is unchanged (the CPU's colouring and the GPU's atomics never wrap).
// periodic_span gives place_box the span of such a box; the rest are
// called for each node row j.
inline void periodic_span(const StepConfig& c, double h, double& xmin, double& xmax) {
  xmin = c.domain_x0;
  xmax = c.domain_x0 + c.period - 0.5 * h;  // in the last cell: box columns -1 .. N + 2
}

// The box columns of the ghosts, and of the columns they repeat.
struct PeriodicColumns {
  int ghost[3], image[3];
};

RUNOUT_HD inline PeriodicColumns periodic_columns(const GridView& g) {
  const int n = g.nx - 4;  // cells in the period; box column k is global k - 1
  return {{0, n + 1, n + 2}, {n, 1, 2}};
}

// After a node stage: the ghosts take their columns' values.
RUNOUT_HD inline void copy_periodic(const GridView& g, int j, double* a) {
  const PeriodicColumns k = periodic_columns(g);
  for (int q = 0; q < 3; ++q) a[g.index(k.ghost[q], j)] = a[g.index(k.image[q], j)];
}

// After a scatter: the row's ghost sums into their columns, and back.
// lower: the array is a minimum (the gap), not a sum.
RUNOUT_HD inline void fold_periodic(const GridView& g, int j, double* a, bool lower = false) {
  const PeriodicColumns k = periodic_columns(g);
  for (int q = 0; q < 3; ++q) {
    double& into = a[g.index(k.image[q], j)];
    const double ghost = a[g.index(k.ghost[q], j)];
    into = lower ? std::fmin(into, ghost) : into + ghost;
  }
  copy_periodic(g, j, a);
}

// The periodic exchange after each grid stage, per node row. The base
// force of a ghost is zeroed after the copy, so that its sum counts each
// node once.
enum class Exchange { AfterP2g, AfterGridUpdate, AfterMomentum, AfterXpicTerm, AfterRemap };

RUNOUT_HD inline void exchange_periodic(const GridView& g, int j, Exchange after) {
  switch (after) {
    case Exchange::AfterP2g: {
      double* const sums[] = {g.m, g.vol, g.px, g.py, g.fx, g.fy};
      for (double* a : sums) fold_periodic(g, j, a);
      fold_periodic(g, j, g.gap, true);
      break;
    }
    case Exchange::AfterGridUpdate: {
      double* const results[] = {g.v0x, g.v0y, g.vx, g.vy, g.dvx, g.dvy, g.stuck};
      for (double* a : results) copy_periodic(g, j, a);
      const PeriodicColumns k = periodic_columns(g);
      for (int q = 0; q < 3; ++q) g.fbase[g.index(k.ghost[q], j)] = 0.0;
      break;
    }
    case Exchange::AfterMomentum:
      fold_periodic(g, j, g.px);
      fold_periodic(g, j, g.py);
      break;
    case Exchange::AfterXpicTerm: {
      double* const results[] = {g.qx, g.qy, g.xvx, g.xvy};
      for (double* a : results) copy_periodic(g, j, a);
      break;
    }
    case Exchange::AfterRemap: {
      double* const results[] = {g.vx, g.vy, g.vmx, g.vmy};
      for (double* a : results) copy_periodic(g, j, a);
      break;
    }
  }
}

// A particle that has left the period re-enters on the other side. Its
// initial position moves with it, so its displacement x - x0 stays the
// distance it travelled.
RUNOUT_HD inline void wrap_periodic(const ParticleView& P, int p, const StepConfig& c) {
  if (!(c.period > 0.0)) return;
  const double shift = c.period * std::floor((P.x[p] - c.domain_x0) / c.period);
  P.x[p] -= shift;
  P.x0[p] -= shift;
}

}  // namespace runout
