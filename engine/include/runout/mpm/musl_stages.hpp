#pragma once
// Stages 1 to 6 of the MUSL step (stages.hpp lists them): the scatters,
// the grid updates, the transfers back to the particles (FLIP, APIC,
// XPIC) and the velocity gradient.
#include <algorithm>
#include <cmath>

#include "runout/mpm/geo_contact.hpp"
#include "runout/mpm/grid.hpp"
#include "runout/mpm/host_device.hpp"
#include "runout/mpm/material.hpp"
#include "runout/mpm/particles.hpp"
#include "runout/mpm/step_config.hpp"
#include "runout/mpm/stencil.hpp"

namespace runout {

// The strength of the clay's basal band at particle p (StepConfig::
// clay_band): the clay's at its own plastic shear plus the slip the band
// has carried over its thickness t_s (P.band_xi), and at the faster of its
// own rate and the band's. The band is t_s thick, thinner than any
// particle: its remoulding weakens the base, not the clay above it, which
// keeps its own strength P.su (else a layer as thick as the particles that
// base nodes reach, about a cell, would remould with the band, and the
// answer would move with the cell). An elastic body has no band.
RUNOUT_HD inline double band_strength(const ParticleView& P, int p, const MaterialParams* mats) {
  if (!(P.su[p] > 0.0)) return INFINITY;
  if (P.band_xi[p] == 0.0 && P.band_rate[p] == 0.0) return P.su[p];
  return strength(mats[P.material[p]].strength, P.xi[p] + P.band_xi[p],
                  std::fmax(P.gamma_dot[p], P.band_rate[p]));
}

// Stage 1. add(array, node, value) does array[node] += value and
// lower(array, node, value) array[node] = min(array[node], value): plain
// operations under the CPU's colouring, atomics on a GPU. The nodal gap is
// the smallest gap of the particles a node sees, so it is zero where any of
// them rests on the base: the material there touches it.
template <class St, class Add, class Lower>
RUNOUT_HD inline void p2g(const ParticleView& P, int p, const St& st, const GridView& g,
                          const StepConfig& c, const MaterialParams* mats, Add&& add,
                          Lower&& lower) {
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
  // The base under the particle slips at the weaker of its clay's band and
  // the interface (a no-slip base holds an elastic body).
  const double band_su =
      c.clay_band ? std::fmin(band_strength(P, p, mats), interface_strength(c)) : 0.0;
  for_each_node(g, st, [&](int n, double N, double, double, double, double) {
    add(g.vol, n, N * V);
    if (N > 0.0) {
      lower(g.gap, n, gap);
      if (c.clay_band) add(g.band_su, n, N * V * band_su);
    }
  });
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
    if (c.clay_band) g.band_slip[n] = 0.0;
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
  if (c.clay_band) g.band_slip[n] = 0.0;  // read by band_softening alone
  if (base_contact_normal(g, c, n, nx, ny)) {
    // The base's strength at the node: the mean over its particles of the
    // weaker of their band and the interface (p2g's N V band_su over N V).
    const double band_su = c.clay_band && g.vol[n] > 0.0 ? g.band_su[n] / g.vol[n] : INFINITY;
    const ContactResult r = geo_contact(c, m, g.vol[n], g.h, dt, closing_speed(g, n, dt), nx,
                                        ny, vx, vy, band_su);
    g.fbase[n] = r.force;
    // Which clay the slip shears is each particle's to say (band_softening).
    if (!r.stuck && c.clay_band) g.band_slip[n] = std::fabs(vx * ny - vy * nx) * dt;
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

// The clay's basal band (StepConfig::clay_band), after g2p: a particle
// that slipping base nodes reach takes their mean slip delta in the step
// as the displacement across its band, band_xi += delta / t_s (the crack
// band of Bazant & Oh 1983, as the regularised softening scales a band's
// strain), and delta / (t_s dt) as the band's rate: so the band's strength
// (band_strength) that p2g gathers at the nodes softens after
// delta95 = xi95 t_s and stiffens with the slip's rate, whatever the cell
// and the particles. On a frictional base only where the band is weaker
// than the interface (interface_strength).
template <class St>
RUNOUT_HD inline void band_softening(const ParticleView& P, int p, const St& st,
                                     const GridView& g, const StepConfig& c,
                                     const MaterialParams* mats, double dt) {
  const StrengthParams& s = mats[P.material[p]].strength;
  double slip = 0.0, weight = 0.0;
  if (s.band_thickness > 0.0) {
    for_each_row(g, st, [&](int n0, double wy, double, double) {
      for (int a = 0; a < kStencilNodes; ++a) {
        const double d = g.band_slip[n0 + a];
        if (d > 0.0) {
          const double N = st.w.wx[a] * wy;
          slip += N * d;
          weight += N;
        }
      }
    });
  }
  // The band's strength (an exp and a pow) only for the particles the slip
  // reaches, and only against a finite interface: every clay band is
  // weaker than none.
  const double tau = interface_strength(c);
  if (!(weight > 0.0) || (tau < INFINITY && !(band_strength(P, p, mats) < tau))) {
    P.band_rate[p] = 0.0;
    return;
  }
  const double band = slip / (weight * s.band_thickness);  // the band's shear in the step
  P.band_xi[p] += band;
  P.band_rate[p] = band / dt;
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

}  // namespace runout
