#pragma once
// Checks of every particle at the end of a step, so that a step gone wrong
// stops the run before its state reaches a frame, a history row or a
// checkpoint (docs/engine.md, "Guards"). particle_fault runs in the CPU
// step and in the CUDA stress kernel; describing a fault (which particle,
// where) is done on the host once a step has failed.
#include <cmath>
#include <string>
#include <vector>

#include "runout/mpm/host_device.hpp"
#include "runout/mpm/lanes.hpp"
#include "runout/mpm/material.hpp"
#include "runout/mpm/particles.hpp"
#include "runout/scene/scene.hpp"

namespace runout {

// Gravest first: a non-finite value makes the rest meaningless.
enum class Fault { None, NonFinite, Outside, Runaway, Volume };

struct GuardLimits {
  // The domain widened by a cell: GIMP lets a particle sit up to lp past a
  // wall, a whole cell past it means it went through.
  double xmin = 0, ymin = 0, xmax = 0, ymax = 0;
  double max_speed = 0;  // [m/s], see guard_limits
  // J = vol / vol0 outside [min_j, max_j]: inverted (J <= 0) or collapsed
  // or blown-up volume.
  double min_j = 0, max_j = 0;
};

// Largest credible volume ratios. Undrained clay barely changes volume
// (K >> G) and an elastic slide strains by per cent, so a particle whose
// volume shrank 100-fold or grew 100-fold is a tangled or torn-off point
// whose stress means nothing, and a negative volume is an inverted one.
inline constexpr double kMinVolumeRatio = 1e-2;
inline constexpr double kMaxVolumeRatio = 1e2;

// The limits of a scene whose particles start as given. The speed bound:
// a point that falls freely along the whole domain diagonal L reaches
// sqrt(2 |g| L) (energy: no resistance, no other source), a plane P-wave
// carries particle velocity v = c eps < c for strains below 1, with c =
// sqrt(M / rho0) of the stiffest material, and no particle is faster than
// its start speed v0 unless one of these accelerates it; their sum bounds
// any physical speed in the run. Twice that sum leaves room for the local
// overshoot of FLIP transfers; a blow-up grows by orders of magnitude per
// step, so the margin costs at most a step or two in catching one.
GuardLimits guard_limits(const Scene& scene, const std::vector<MaterialParams>& materials,
                         const Particles& particles);

RUNOUT_HD inline bool finite_state(const ParticleView& P, int p) {
  return std::isfinite(P.x[p]) && std::isfinite(P.y[p]) && std::isfinite(P.vx[p]) &&
         std::isfinite(P.vy[p]) && std::isfinite(P.vol[p]) && std::isfinite(P.sxx[p]) &&
         std::isfinite(P.syy[p]) && std::isfinite(P.sxy[p]) && std::isfinite(P.szz[p]) &&
         std::isfinite(P.xi[p]) && std::isfinite(P.su[p]) && std::isfinite(P.gamma_dot[p]);
}

// What is wrong with particle p after a step, the first check that fails.
RUNOUT_HD inline Fault particle_fault(const ParticleView& P, int p, const GuardLimits& g) {
  if (!finite_state(P, p)) return Fault::NonFinite;
  if (!(P.x[p] >= g.xmin && P.x[p] <= g.xmax && P.y[p] >= g.ymin && P.y[p] <= g.ymax))
    return Fault::Outside;
  if (P.vx[p] * P.vx[p] + P.vy[p] * P.vy[p] > g.max_speed * g.max_speed) return Fault::Runaway;
  const double j = P.vol[p] / P.vol0[p];
  if (!(j >= g.min_j && j <= g.max_j)) return Fault::Volume;
  return Fault::None;
}

// Whether particles p .. p + 3 all pass particle_fault, four at a time
// (the CPU's stress update, stress_update_x4): false where one does not,
// and particle_fault then says which and why. v - v is zero for a finite
// v and NaN for an infinite or NaN one, so the sum of those differences is
// zero only where every value is finite.
inline bool no_fault_x4(const ParticleView& P, int p, const GuardLimits& g) {
  const auto at = [p](const double* a) { return load_lanes(a + p); };
  Lanes not_finite = splat(0.0);
  for (const double* a : {P.x, P.y, P.vx, P.vy, P.vol, P.sxx, P.syy, P.sxy, P.szz, P.xi, P.su,
                          P.gamma_dot}) {
    const Lanes v = at(a);
    not_finite = not_finite + (v - v);
  }
  const Lanes x = at(P.x), y = at(P.y), vx = at(P.vx), vy = at(P.vy);
  const Lanes speed2 = vx * vx + vy * vy, j = at(P.vol) / at(P.vol0);
  const double max2 = g.max_speed * g.max_speed;
  bool ok = true;
  for (int k = 0; k < 4; ++k)
    ok = ok && lane(not_finite, k) == 0.0 && lane(x, k) >= g.xmin && lane(x, k) <= g.xmax &&
         lane(y, k) >= g.ymin && lane(y, k) <= g.ymax && !(lane(speed2, k) > max2) &&
         lane(j, k) >= g.min_j && lane(j, k) <= g.max_j;
  return ok;
}

// The message of a failed step: how many particles are at fault, and one
// of them by id, position and what is wrong with it: of the gravest fault,
// the lowest id (the same whatever the memory order or the thread count).
// A non-finite value spreads through the grid to the neighbours within the
// step, so the particle named is then one of those it reached.
std::string describe_faults(const Particles& particles, const GuardLimits& limits, long step,
                            double time, double dt);

}  // namespace runout
