#pragma once
// The step's configuration (StepConfig, made by step_config.cpp), the parts
// of it that change every step, the step's per-particle scratch and the
// signal speed of the CFL condition.
#include <cmath>

#include "runout/mpm/base.hpp"
#include "runout/mpm/host_device.hpp"
#include "runout/scene/kinds.hpp"
#include "runout/mpm/lanes.hpp"
#include "runout/mpm/material.hpp"
#include "runout/mpm/particles.hpp"

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
  bool clay_band = false;        // BaseSpec::clay_band
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

}  // namespace runout
