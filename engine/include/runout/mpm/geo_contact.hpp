#pragma once
// The grid's boundary conditions and the Geo-contact with the rigid base,
// per node (used by stages 2 and 5, musl_stages.hpp).
#include <algorithm>
#include <cmath>

#include "runout/mpm/base.hpp"
#include "runout/mpm/grid.hpp"
#include "runout/mpm/host_device.hpp"
#include "runout/mpm/step_config.hpp"

namespace runout {

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
// despite the rounding of their coordinates. Only a node whose gap p2g
// lowered can be: every particle that reaches a node on or inside the base
// lies near enough to it to lower the node's gap (p2g), so a gap left at
// +infinity spares the search along the base.
RUNOUT_HD inline bool base_contact_normal(const GridView& g, const StepConfig& c, int n,
                                          double& nx, double& ny) {
  if (c.base.kind == BaseKind::None || !(g.gap[n] < INFINITY)) return false;
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

// A base node's share of the interface, 2 V_i / h. Under the clay's band
// it is at most the base's length per node, h over the larger of the
// normal's components (a straight base at angle a to the grid passes
// h / cos a of itself per node column): a basal layer whose particles
// crowd the node's support (V_i over h^2 / 2) otherwise widens the band
// by as much, and the runout then moves with the particles per cell.
RUNOUT_HD inline double interface_share(const StepConfig& c, double vol, double h, double nx,
                                        double ny) {
  const double share = 2.0 * vol / h;
  if (!c.clay_band) return share;
  return std::fmin(share, h / std::fmax(std::fabs(nx), std::fabs(ny)));
}

// The interface's own strength under StepConfig::clay_band: tau on a
// frictional base, none on a no-slip one. The base under a particle slips
// at the weaker of its clay's band and this, and the slip shears the clay
// only where the clay is the weaker: intact clay beside a remoulded patch
// then takes at most tau through the interface, under its peak su, and the
// patch does not spread along the base by the slip (only the clay's own
// bands remould it). Taken per particle, not from a node's mean su, which
// would hand a patch's slip to the intact clay within a cell of it.
RUNOUT_HD inline double interface_strength(const StepConfig& c) {
  return c.interface == InterfaceKind::Frictional ? c.shear_strength : INFINITY;
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
// Under StepConfig::clay_band, band_su is the mean over the particles the
// node carries of the weaker of their clay and the interface
// (interface_strength; +infinity without the band), and the node slips
// beyond band_su A (interface_share).
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
                                           double& vx, double& vy, double band_su) {
  const double vn = vx * nx + vy * ny;
  const double dvn = vn < -closing ? -closing - vn : 0.0;
  vx += dvn * nx;
  vy += dvn * ny;
  const double tx = ny, ty = -nx;  // +s direction: the normal turned clockwise
  const double vt = vx * tx + vy * ty;
  double limit = std::fabs(vt);
  const double share = interface_share(c, vol, h, nx, ny);
  if (c.interface == InterfaceKind::NoSlip) {
    if (c.clay_band) limit = band_su * share * dt / m;
  } else if (c.interface == InterfaceKind::Frictional) {
    limit = std::fmin(c.shear_strength, band_su) * share * dt / m;
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

}  // namespace runout
