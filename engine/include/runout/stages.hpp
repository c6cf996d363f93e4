#pragma once
// One explicit MPM step, stage by stage, as per-particle and per-node
// functions. They take plain views and a scatter functor, hold no state and
// allocate nothing, so the CPU driver (simulation.cpp) and a CUDA kernel can
// call them unchanged.
//
// The step is MUSL (modified update-stress-last, Sulsky et al. 1995):
//   1. p2g:            m_i, p_i = sum N m v, f_i = sum (-V sigma grad N + N m g),
//                      gap_i = min over the node's particles of their gap to the base
//   2. grid_update:    v0_i = p_i/m_i, v_i = v0_i + dt f_i/m_i, Geo-contact with
//                      the rigid base where the material reaches it, boundary
//                      conditions
//   3. g2p:            v_p += FLIP/PIC blend
//   4. p2g_momentum:   p_i = sum N m v_p(new)            (the MUSL remap)
//   5. remap_velocity: v_i = p_i/m_i and the mid-step vm_i = (v0_i + v_i)/2,
//                      contact kinematics, boundary conditions
//   6. velocity_gradient, displacement: L = sum v_i (x) grad N (its
//                      volumetric part averaged per cell against locking),
//                      step displacement dt sum N vm_i
//   7. stress_update:  volume, Jaumann stress; then move
// MUSL rather than USL because the stress is computed from the remapped
// velocity: at nodes with a tiny share of mass (free surface, a particle
// entering a cell) v0 + dt f/m is spurious, and USL turns it into stress.
// The price is a second scatter of momentum. Every stage evaluates the
// shape functions at the positions of the start of the step, so the
// particle moves only in the last stage.
#include <cmath>

#include "runout/base.hpp"
#include "runout/grid.hpp"
#include "runout/host_device.hpp"
#include "runout/material.hpp"
#include "runout/particles.hpp"
#include "runout/shape.hpp"

namespace runout {

struct StepConfig {
  ShapeKind shape = ShapeKind::Gimp;
  double lp = 0;                 // GIMP particle half-width h / (2 ppc)
  double gx = 0, gy = 0;         // gravity
  double flip = 0.99;            // PIC/FLIP blend
  double min_node_mass = 0;      // nodes at or below this are not accelerated
  double damping = 0;            // Cundall local damping coefficient
  // Boundary conditions on the domain's sides; the domain spans global
  // nodes 0..domain_nx by 0..domain_ny, and ghost nodes beyond a side take
  // that side's condition.
  BoundaryKind left = BoundaryKind::Slip, right = BoundaryKind::Slip;
  BoundaryKind bottom = BoundaryKind::Fixed, top = BoundaryKind::Free;
  int domain_nx = 0, domain_ny = 0;
  // The rigid base and its interface (Geo-contact); base.kind None: none.
  BaseView base;
  InterfaceKind interface = InterfaceKind::NoSlip;
  double shear_strength = 0;     // tau, Frictional
  double friction = 0;           // mu, Coulomb
};

// Per-particle scratch of one step: the displacement, applied at the end.
struct StepScratch {
  double *dx, *dy;
};

// P-wave speed sqrt(M / rho) at the current density plus the particle's
// speed: the signal speed of the CFL condition dt = C h / max(c + |v|).
RUNOUT_HD inline double cfl_speed(const ParticleView& P, int p, const MaterialParams& mat) {
  const double rho = P.mass[p] / P.vol[p];
  const double speed = std::sqrt(P.vx[p] * P.vx[p] + P.vy[p] * P.vy[p]);
  return std::sqrt(p_wave_modulus(mat) / rho) + speed;
}

// The particle's shape functions for the whole step: every stage evaluates
// them at the start-of-step position, so they are computed once.
struct Stencil2D {
  Stencil1D x, y;
};

RUNOUT_HD inline void make_stencil(const GridView& g, const StepConfig& c, double xp, double yp,
                                   Stencil2D& s) {
  stencil_1d(c.shape, xp, g.ox, g.h, c.lp, s.x);
  stencil_1d(c.shape, yp, g.oy, g.h, c.lp, s.y);
}

// Visits the 3 x 3 nodes of a stencil: f(node, N, dN/dx, dN/dy).
template <class F>
RUNOUT_HD inline void for_each_node(const GridView& g, const Stencil2D& s, F&& f) {
  for (int b = 0; b < 3; ++b) {
    for (int a = 0; a < 3; ++a) {
      const int node = g.index(s.x.first + a, s.y.first + b);
      f(node, s.x.w[a] * s.y.w[b], s.x.dw[a] * s.y.w[b], s.x.w[a] * s.y.dw[b]);
    }
  }
}

// The gap between a particle's domain and the base: its signed distance to
// the base less the half-extent of its square of half-width lp along the
// normal, lp (|n_x| + |n_y|). Zero for a particle resting on the base,
// negative for one pressed into it. lp = h / (2 ppc) is half the particle
// spacing, so a linear-shape point stands for the same square.
RUNOUT_HD inline double particle_gap(const StepConfig& c, const BasePoint& b) {
  return b.d - c.lp * (std::fabs(b.nx) + std::fabs(b.ny));
}

// Stage 1. add(array, node, value) does array[node] += value and
// lower(array, node, value) array[node] = min(array[node], value): plain
// operations under the CPU's colouring, atomics on a GPU. The nodal gap is
// the smallest gap of the particles a node sees, so it is zero where any of
// them rests on the base: the material there touches it.
template <class Add, class Lower>
RUNOUT_HD inline void p2g(const ParticleView& P, int p, const Stencil2D& st, const GridView& g,
                          const StepConfig& c, Add&& add, Lower&& lower) {
  const double m = P.mass[p], V = P.vol[p];
  const double vx = P.vx[p], vy = P.vy[p];
  const double sxx = P.sxx[p], syy = P.syy[p], sxy = P.sxy[p];
  // Nodes on or inside the base (distance <= 0) are the only ones that read
  // the gap, and a particle reaches nodes at most h + lp away along x and y,
  // so at most sqrt(2) (h + lp) away: the distance is 1-Lipschitz.
  bool near_base = false;
  double gap = 0.0;
  if (c.base.kind != BaseKind::None) {
    const BasePoint b = locate_on_base(c.base, P.x[p], P.y[p]);
    near_base = b.d < std::sqrt(2.0) * (g.h + c.lp);
    gap = particle_gap(c, b);
  }
  for_each_node(g, st, [&](int n, double N, double dNx, double dNy) {
    if (N == 0.0 && dNx == 0.0 && dNy == 0.0) return;
    add(g.m, n, N * m);
    add(g.vol, n, N * V);
    add(g.px, n, N * m * vx);
    add(g.py, n, N * m * vy);
    add(g.fx, n, -V * (sxx * dNx + sxy * dNy) + N * m * c.gx);
    add(g.fy, n, -V * (sxy * dNx + syy * dNy) + N * m * c.gy);
    if (near_base && N > 0.0) lower(g.gap, n, gap);
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
// rounding of the base's position). Zero on a no-slip base too: there,
// letting separated material come back made the case 2 slide (soft clay,
// no-slip) rattle at 5-10 % of its peak kinetic energy instead of coming
// to rest (tests/test_reference_scenes.cpp), for a reason not yet found,
// so a no-slip base removes all approach, as before.
RUNOUT_HD inline double closing_speed(const GridView& g, const StepConfig& c, int n, double dt) {
  if (c.interface == InterfaceKind::NoSlip) return 0.0;
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
// direction (+s): m dv / dt, negative while it resists down-slope motion.
RUNOUT_HD inline double geo_contact(const StepConfig& c, double m, double vol, double h,
                                    double dt, double closing, double nx, double ny, double& vx,
                                    double& vy) {
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
  const double dvt = std::fmin(std::fabs(vt), limit) * (vt < 0.0 ? -1.0 : 1.0);
  vx -= dvt * tx;
  vy -= dvt * ty;
  return -m * dvt / dt;
}

// The kinematic part of Geo-contact, for velocities that carry no impulse
// of their own (the mid-step and remapped velocities): no approach beyond
// closing the gap, and no slip on a no-slip base.
RUNOUT_HD inline void contact_kinematics(const StepConfig& c, double closing, double nx,
                                         double ny, double& vx, double& vy) {
  const double vn = vx * nx + vy * ny;
  if (c.interface == InterfaceKind::NoSlip) {
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
RUNOUT_HD inline void grid_update(const GridView& g, int n, const StepConfig& c, double dt) {
  const double m = g.m[n];
  if (m <= c.min_node_mass) {
    g.v0x[n] = g.v0y[n] = g.vx[n] = g.vy[n] = g.fbase[n] = 0.0;
    return;
  }
  const double v0x = g.px[n] / m, v0y = g.py[n] / m;
  double fx = g.fx[n], fy = g.fy[n];
  if (c.damping > 0.0) {
    fx -= c.damping * std::fabs(fx) * (v0x > 0.0 ? 1.0 : (v0x < 0.0 ? -1.0 : 0.0));
    fy -= c.damping * std::fabs(fy) * (v0y > 0.0 ? 1.0 : (v0y < 0.0 ? -1.0 : 0.0));
  }
  double vx = v0x + dt * fx / m, vy = v0y + dt * fy / m;
  double nx, ny;
  g.fbase[n] = 0.0;
  if (base_contact_normal(g, c, n, nx, ny))
    g.fbase[n] = geo_contact(c, m, g.vol[n], g.h, dt, closing_speed(g, c, n, dt), nx, ny, vx, vy);
  constrain(g, c, n, vx, vy);
  g.v0x[n] = v0x;
  g.v0y[n] = v0y;
  g.vx[n] = vx;
  g.vy[n] = vy;
}

// Stage 3. FLIP carries the particle's own velocity plus the grid's change
// (little dissipation), PIC takes the grid velocity (stable, dissipative).
RUNOUT_HD inline void g2p(const ParticleView& P, int p, const Stencil2D& st, const GridView& g,
                          const StepConfig& c) {
  double pic_x = 0, pic_y = 0, dvx = 0, dvy = 0;
  for_each_node(g, st, [&](int n, double N, double, double) {
    pic_x += N * g.vx[n];
    pic_y += N * g.vy[n];
    dvx += N * (g.vx[n] - g.v0x[n]);
    dvy += N * (g.vy[n] - g.v0y[n]);
  });
  P.vx[p] = c.flip * (P.vx[p] + dvx) + (1.0 - c.flip) * pic_x;
  P.vy[p] = c.flip * (P.vy[p] + dvy) + (1.0 - c.flip) * pic_y;
}

// Stage 4: the MUSL remap of the updated particle momentum.
template <class Add>
RUNOUT_HD inline void p2g_momentum(const ParticleView& P, int p, const Stencil2D& st,
                                   const GridView& g, Add&& add) {
  const double mvx = P.mass[p] * P.vx[p], mvy = P.mass[p] * P.vy[p];
  for_each_node(g, st, [&](int n, double N, double, double) {
    if (N == 0.0) return;
    add(g.px, n, N * mvx);
    add(g.py, n, N * mvy);
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
    g.vx[n] = g.vy[n] = g.vmx[n] = g.vmy[n] = 0.0;
    return;
  }
  double vx = g.px[n] / m, vy = g.py[n] / m;
  double vmx = 0.5 * (g.v0x[n] + vx), vmy = 0.5 * (g.v0y[n] + vy);
  double nx, ny;
  if (base_contact_normal(g, c, n, nx, ny)) {
    const double closing = closing_speed(g, c, n, dt);
    contact_kinematics(c, closing, nx, ny, vx, vy);
    contact_kinematics(c, closing, nx, ny, vmx, vmy);
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
RUNOUT_HD inline VelocityGradient velocity_gradient(const Stencil2D& st, const GridView& g) {
  VelocityGradient L{0, 0, 0, 0};
  for_each_node(g, st, [&](int n, double, double dNx, double dNy) {
    L.xx += g.vx[n] * dNx;
    L.xy += g.vx[n] * dNy;
    L.yx += g.vy[n] * dNx;
    L.yy += g.vy[n] * dNy;
  });
  return L;
}

// Stage 6b: the step displacement, applied in stress_update.
RUNOUT_HD inline void displacement(int p, const Stencil2D& st, const GridView& g, double dt,
                                   const StepScratch& s) {
  double mid_x = 0, mid_y = 0;
  for_each_node(g, st, [&](int n, double N, double, double) {
    mid_x += N * g.vmx[n];
    mid_y += N * g.vmy[n];
  });
  s.dx[p] = dt * mid_x;
  s.dy[p] = dt * mid_y;
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
RUNOUT_HD inline void set_volumetric_rate(VelocityGradient& L, double trace) {
  const double shift = 0.5 * (trace - (L.xx + L.yy));
  L.xx += shift;
  L.yy += shift;
}

// Stage 7. Volume by J = det(I + dt L); stress rotated with the spin
// W = skew(L) (Jaumann rate) and then updated by the material with the
// strain increment dt sym(L). gamma_dot = sqrt((D_xx - D_yy)^2 + 4 D_xy^2),
// D = sym(L): the largest in-plane engineering shear strain rate (twice the
// radius of the in-plane Mohr circle of D), the rate conjugate to the
// Tresca shear stress; |dv_x/dy| in simple shear, and equal to
// sqrt(2 e:e) (e the deviator of D, D_zz = 0) for isochoric flow. Then the
// particle moves. Returns its P-wave speed plus its speed, for the CFL
// condition of the next step.
RUNOUT_HD inline double stress_update(const ParticleView& P, int p, const VelocityGradient& L,
                                      const MaterialParams* materials, double dt,
                                      const StepScratch& s) {
  const double J = (1.0 + dt * L.xx) * (1.0 + dt * L.yy) - dt * dt * L.xy * L.yx;
  P.vol[p] *= J;

  const double w = 0.5 * (L.xy - L.yx);  // spin W_xy
  const double sxx = P.sxx[p], syy = P.syy[p], sxy = P.sxy[p];
  StressPoint sp{sxx + 2.0 * w * sxy * dt, syy - 2.0 * w * sxy * dt,
                 sxy + w * (syy - sxx) * dt, P.szz[p], P.xi[p], P.su[p]};

  const double Dxy = 0.5 * (L.xy + L.yx);
  const double gamma_dot = std::sqrt((L.xx - L.yy) * (L.xx - L.yy) + 4.0 * Dxy * Dxy);
  const MaterialParams& mat = materials[P.material[p]];
  update_stress(mat, StrainIncrement{dt * L.xx, dt * L.yy, dt * Dxy, gamma_dot, dt}, sp);

  P.sxx[p] = sp.sxx;
  P.syy[p] = sp.syy;
  P.sxy[p] = sp.sxy;
  P.szz[p] = sp.szz;
  P.xi[p] = sp.xi;
  P.su[p] = sp.su;
  P.gamma_dot[p] = gamma_dot;
  P.x[p] += s.dx[p];
  P.y[p] += s.dy[p];
  return cfl_speed(P, p, mat);
}

}  // namespace runout
