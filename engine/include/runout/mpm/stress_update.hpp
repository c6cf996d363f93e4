#pragma once
// Stage 7 of the step: volume, F and the Jaumann stress update by the
// material, one particle at a time or four (the CPU backend).
#include <algorithm>
#include <cmath>

#include "runout/mpm/host_device.hpp"
#include "runout/mpm/lanes.hpp"
#include "runout/mpm/material.hpp"
#include "runout/mpm/musl_stages.hpp"
#include "runout/mpm/particles.hpp"
#include "runout/mpm/step_config.hpp"

namespace runout {

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
  // Under regularised softening the rate the strength takes is the band's,
  // which the driver sets after the average (stage::SetNonlocalXi); the
  // one read above stays until then.
  if (!mat.strength.regularised) P.gamma_dot[p] = u.gamma_dot;
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
  if (!mat.strength.regularised) store_lanes(P.gamma_dot + p, u.gamma_dot);
  store_lanes(P.x + p, at(P.x) + load_lanes(s.dx + s.at(p)));
  store_lanes(P.y + p, at(P.y) + load_lanes(s.dy + s.at(p)));
  return signal_speed(at(P.mass), u.vol, at(P.vx), at(P.vy), mat);
}

}  // namespace runout
