#pragma once
// Constitutive models behind one interface: a plain parameter record and a
// stress update that switches on the model, so the same call compiles for
// the host and for CUDA without virtual functions.
#include <cmath>

#include "runout/mpm/host_device.hpp"
#include "runout/scene/kinds.hpp"
#include "runout/mpm/lanes.hpp"
#include "runout/mpm/strength.hpp"

namespace runout {

struct MaterialParams {
  MaterialModel model = MaterialModel::Elastic;
  double density = 0;  // initial density [kg/m3]
  double bulk = 0;     // K = E / (3 (1 - 2 nu))
  double shear = 0;    // G = E / (2 (1 + nu))
  StrengthParams strength;  // Tresca only
};

inline MaterialParams elastic_params(double density, double youngs, double poisson) {
  MaterialParams m;
  m.model = MaterialModel::Elastic;
  m.density = density;
  m.bulk = youngs / (3.0 * (1.0 - 2.0 * poisson));
  m.shear = youngs / (2.0 * (1.0 + poisson));
  return m;
}

// Constrained (P-wave) modulus K + 4G/3: the stiffness that sets the
// fastest wave speed sqrt(M / rho) in the CFL condition.
RUNOUT_HD inline double p_wave_modulus(const MaterialParams& m) {
  return m.bulk + 4.0 * m.shear / 3.0;
}

// Stress and internal variables of one material point.
struct StressPoint {
  double sxx, syy, sxy, szz;  // Cauchy stress, tension positive
  double xi;                  // accumulated engineering plastic shear strain
  double su;                  // current strength (0 for elastic)
};

// Plane-strain strain increment (tensor components; dezz = 0) and the
// shear strain rate of the step.
struct StrainIncrement {
  double dexx, deyy, dexy;
  double gamma_dot;
  double dt;
};

// Hypoelastic update: dsigma = lambda tr(de) I + 2 G de with de_zz = 0, so
// sigma_zz picks up lambda tr(de) (plane strain). The objective (Jaumann)
// rotation is applied by the caller before this.
// T: double for one point, Lanes for four (stress_update_x4).
template <class T>
RUNOUT_HD inline void elastic_increment(const MaterialParams& m, const T& dexx, const T& deyy,
                                        const T& dexy, T& sxx, T& syy, T& sxy, T& szz) {
  const double lambda = m.bulk - 2.0 * m.shear / 3.0;
  const T tr = dexx + deyy;
  sxx = sxx + (lambda * tr + 2.0 * m.shear * dexx);
  syy = syy + (lambda * tr + 2.0 * m.shear * deyy);
  szz = szz + lambda * tr;
  sxy = sxy + 2.0 * m.shear * dexy;
}

RUNOUT_HD inline void elastic_update(const MaterialParams& m, const StrainIncrement& d,
                                     StressPoint& s) {
  elastic_increment(m, d.dexx, d.deyy, d.dexy, s.sxx, s.syy, s.sxy, s.szz);
}

// Undrained Tresca in plane strain with the softening, rate-dependent
// strength of strength.hpp, by an elastic predictor (elastic_update) and
// a radial return (tresca_return; de Souza Neto, Peric & Owen 2008,
// "Computational Methods for Plasticity", ch. 7: the return mapping of the
// von Mises model with nonlinear isotropic hardening, one scalar equation
// in the plastic multiplier; here the hardening is softening).
//
// The yield function is the radius of the in-plane Mohr circle,
//   tau = sqrt(((sxx - syy) / 2)^2 + sxy^2),   f = tau - su(xi, gamma_dot).
// Its flow direction is in-plane and traceless, so the plastic strain has
// no zz part: plane strain (de_zz = 0) then leaves szz at its trial value,
// and the mean stress (sxx + syy + szz) / 3 is not changed by the return.
//
// xi is the accumulated engineering plastic shear strain: each plastic
// step adds dxi = (tau_trial - tau) / G, the engineering shear strain the
// elastic shear stress gives up. gamma_dot is the caller's in-plane
// engineering shear strain rate sqrt((Dxx - Dyy)^2 + 4 Dxy^2) (the
// conjugate of tau), held for the step.
//
// Return: find dxi >= 0 with g(dxi) = tau_trial - G dxi - su(xi + dxi) = 0,
// so the stress ends on the yield surface of the end of the increment.
// g(0) > 0 and g(tau_trial / G) = -su < 0 bracket the root, which is
// unique: su is convex in xi, so g is concave. Newton uses the exact slope
// g' = -G - dsu/dxi, dsu/dxi = -(3 / xi95) su0 a (S - d_rem) (a from
// strength.hpp); a step that leaves the bracket, or a slope that is not
// negative (the softening modulus exceeds G: a snap-back), falls back to
// bisection, so the iteration converges for any softening.
//
// k: the rate scaling at the step's gamma_dot; S: the softening at the
// trial's xi (the iteration starts at dxi = 0 from it, so a yielding
// particle evaluates no exp more than a particle that does not yield: xi +
// 0 = xi, and the softening of -0 and +0 is one).
// The radius of the in-plane Mohr circle, Tresca's tau. T: double, or
// Lanes for four particles (the CPU's yield check, stress_update_x4).
template <class T>
RUNOUT_HD inline T mohr_radius(const T& sxx, const T& syy, const T& sxy) {
  const T radius_x = 0.5 * (sxx - syy);
  return square_root(radius_x * radius_x + sxy * sxy);
}

RUNOUT_HD inline void tresca_return(const MaterialParams& m, const RateScaling& k, double S,
                                    StressPoint& s) {
  const StrengthParams& p = m.strength;
  const double center = 0.5 * (s.sxx + s.syy);
  const double radius_x = 0.5 * (s.sxx - s.syy);
  const double tau_trial = mohr_radius(s.sxx, s.syy, s.sxy);
  // S: from here the softening at xi + dxi.
  const double su_trial = strength_at(p, k, S);
  if (tau_trial <= su_trial) {
    s.su = su_trial;
    return;
  }

  constexpr int kMaxIterations = 200;  // bisection alone needs ~60 to reach rounding
  constexpr double kTolerance = 1e-12; // on |g| relative to su
  const double G = m.shear;
  double lo = 0.0, hi = tau_trial / G, dxi = 0.0, su = su_trial;
  for (int it = 1;; ++it) {
    su = strength_at(p, k, S);
    const double g = tau_trial - G * dxi - su;
    if (std::fabs(g) <= kTolerance * su || it == kMaxIterations) break;
    (g > 0.0 ? lo : hi) = dxi;
    double next = 0.5 * (lo + hi);
    const double slope = -G + 3.0 / p.xi95 * p.su0 * k.a * (S - p.d_rem);
    if (slope < 0.0) {
      const double newton = dxi - g / slope;
      if (newton > lo && newton < hi) next = newton;
    }
    if (next == dxi) break;  // the bracket has shrunk to rounding
    dxi = next;
    S = softening(p, s.xi + dxi);
  }

  const double scale = (tau_trial - G * dxi) / tau_trial;
  s.sxx = center + scale * radius_x;
  s.syy = center - scale * radius_x;
  s.sxy *= scale;
  s.xi += dxi;
  s.su = su;
}

// What the model does to an elastic trial s: nothing (elastic), or its
// yield check and return (Tresca).
RUNOUT_HD inline void plastic_correction(const MaterialParams& m, double gamma_dot,
                                         StressPoint& s) {
  if (m.model == MaterialModel::Tresca)
    tresca_return(m, rate_scaling(m.strength, gamma_dot), softening(m.strength, s.xi), s);
}

RUNOUT_HD inline void update_stress(const MaterialParams& m, const StrainIncrement& d,
                                    StressPoint& s) {
  elastic_update(m, d, s);
  plastic_correction(m, d.gamma_dot, s);
}

}  // namespace runout
