#pragma once
// The undrained shear strength of the slide (SCENES.md, "Strength of the
// slide"; docs/strength.md): strain softening times or plus a power-law
// rate factor. Kept apart from the stress update so that every
// method with a base shear (the MPM return mapping, the depth-averaged
// model) evaluates one law.
//
//   S(xi)        = d_rem + (1 - d_rem) exp(-3 xi / xi95)
//   R(gamma_dot) = eta (gamma_dot / gamma_dot_ref)^n
//   su           = su0 S + su0 R         (additive)
//   su           = su0 S (1 + R)         (multiplicative)
//
// xi is the accumulated engineering plastic shear strain and gamma_dot the
// engineering shear strain rate; how a method measures them is its own
// definition (the MPM one is in material.hpp). Sources: the softening law
// is Einav & Randolph (2005), Int. J. Numer. Meth. Eng. 63; softening and
// rate together as in Dey et al. (2016), Geotechnique 66, and in the MPM
// runout study of SCENES.md (Dong, Wang & Randolph 2017, J. Rock Mech.
// Geotech. Eng. 9).
#include <cmath>

#include "runout/mpm/host_device.hpp"
#include "runout/scene/kinds.hpp"
#include "runout/mpm/lanes.hpp"

namespace runout {

struct StrengthParams {
  double su0 = 0;             // intact undrained strength [Pa]
  double d_rem = 1;           // remoulded fraction 1 / St; 1: no softening
  double xi95 = 1;            // xi at which 95 % of the remoulding has happened
  double eta = 0;             // viscosity coefficient; 0: no rate effect
  double rate_exponent = 0.1; // n, shear-thinning index
  double reference_rate = 1;  // gamma_dot_ref [1/s]
  StrengthForm form = StrengthForm::Multiplicative;
  // Regularised softening (nonlocal.hpp): xi is the band's displacement
  // over t_s, and the rate that enters R is its rate, delta_dot / t_s, of
  // the step before (the particle's gamma_dot as the driver leaves it),
  // not the numerical band's strain rate, which grows as the cell shrinks.
  bool regularised = false;
  double band_thickness = 0;  // t_s [m]; 0: none (MaterialSpec::band_thickness)
};

// exp(-3) = 0.0498: at xi = xi95, 95 % of the drop 1 - d_rem has happened.
// Without softening (d_rem = 1) the exp is skipped: it was 4.5 % of a
// step of the non-softening reference cases.
RUNOUT_HD inline double softening(const StrengthParams& p, double xi) {
  if (p.d_rem == 1.0) return 1.0;
  return p.d_rem + (1.0 - p.d_rem) * std::exp(-3.0 * xi / p.xi95);
}

// R = 0 at rest (0^n = 0 for n > 0) and without a rate effect (eta = 0),
// where the pow is skipped.
RUNOUT_HD inline double rate_factor(const StrengthParams& p, double gamma_dot) {
  if (p.eta == 0.0 || gamma_dot <= 0.0) return 0.0;
  return p.eta * std::pow(gamma_dot / p.reference_rate, p.rate_exponent);
}

// At a fixed rate both forms are affine in S: su = su0 (a S + b), with
// (a, b) = (1, R) additive and (1 + R, 0) multiplicative. A return mapping
// holds the rate for the step, so it computes (a, b), and the pow in R,
// once and iterates on S alone.
struct RateScaling {
  double a, b;
};

RUNOUT_HD inline RateScaling rate_scaling(const StrengthParams& p, double gamma_dot) {
  const double R = rate_factor(p, gamma_dot);
  if (p.form == StrengthForm::Additive) return {1.0, R};
  return {1.0 + R, 0.0};
}

// su from a softening value S already at hand (the return mapping needs S
// for its slope too).
// T: double, or Lanes for four particles (the CPU's yield check,
// stress_update_x4), with the rate scaling's a and b as values of T.
template <class T>
RUNOUT_HD inline T strength_at(const StrengthParams& p, const T& a, const T& b, const T& S) {
  return p.su0 * (a * S + b);
}
RUNOUT_HD inline double strength_at(const StrengthParams& p, const RateScaling& k, double S) {
  return strength_at(p, k.a, k.b, S);
}

RUNOUT_HD inline double strength(const StrengthParams& p, const RateScaling& k, double xi) {
  return strength_at(p, k, softening(p, xi));
}

RUNOUT_HD inline double strength(const StrengthParams& p, double xi, double gamma_dot) {
  return strength(p, rate_scaling(p, gamma_dot), xi);
}

// softening and rate_scaling of four particles, lane k particle k's (the
// CPU's stress update, stress_update_x4): the same formulas, with the exp
// and log of lanes.hpp.
inline Lanes softening_x4(const StrengthParams& p, const Lanes& xi) {
  if (p.d_rem == 1.0) return splat(1.0);
  return p.d_rem + (1.0 - p.d_rem) * exp_lanes(-3.0 * xi / p.xi95);
}

inline void rate_scaling_x4(const StrengthParams& p, const Lanes& gamma_dot, Lanes& a, Lanes& b) {
  const Lanes zero = splat(0.0);
  Lanes R = zero;
  if (p.eta != 0.0) {
    // x^n = exp(n ln x): a few ulp from pow for the rates and exponents of
    // a rate law (n ln x is small). A lane at rest or with a negative rate
    // takes ln 1 and the select puts R = 0 there: ln 0 = -inf and exp(-inf)
    // send the vector exp and log down their scalar path for special
    // values, which made them the slowest part of a step where most of a
    // slide is at rest or, under regularised softening, not yielding.
    const Lanes moving = select_less(zero, gamma_dot, gamma_dot, splat(p.reference_rate));
    const Lanes power = exp_lanes(p.rate_exponent * log_lanes(moving / p.reference_rate));
    R = select_less(zero, gamma_dot, p.eta * power, zero);
  }
  a = p.form == StrengthForm::Additive ? splat(1.0) : 1.0 + R;
  b = p.form == StrengthForm::Additive ? R : zero;
}

}  // namespace runout
