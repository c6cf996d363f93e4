// The undrained Tresca model with softening and rate dependency
// (strength.hpp, material.hpp; docs/strength.md) at a single material
// point: the strength law against its formulas, and the return mapping
// driven by strain increments.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <initializer_list>
#include <vector>

#include "runout/mpm/material.hpp"
#include "runout/mpm/particles.hpp"
#include "runout/mpm/stages.hpp"

namespace runout {
namespace {

constexpr double kSu0 = 2500.0;  // the parametric cases of SCENES.md
constexpr double kYoungs = 100.0 * kSu0;
constexpr double kPoisson = 0.49;

MaterialParams tresca(double sensitivity, double xi95, double eta, StrengthForm form) {
  MaterialParams m = elastic_params(600.0, kYoungs, kPoisson);
  m.model = MaterialModel::Tresca;
  m.strength = {kSu0, 1.0 / sensitivity, xi95, eta, 0.1, 0.01, form};
  return m;
}

// The formulas of SCENES.md written out again, independently of strength.hpp.
double expected_su(const StrengthParams& p, double xi, double gamma_dot) {
  const double S = p.d_rem + (1.0 - p.d_rem) * std::exp(-3.0 * xi / p.xi95);
  const double R = gamma_dot > 0.0 && p.eta > 0.0
                       ? p.eta * std::pow(gamma_dot / p.reference_rate, p.rate_exponent)
                       : 0.0;
  return p.form == StrengthForm::Additive ? p.su0 * S + p.su0 * R : p.su0 * S * (1.0 + R);
}

double in_plane_tau(const StressPoint& s) {
  const double r = 0.5 * (s.sxx - s.syy);
  return std::sqrt(r * r + s.sxy * s.sxy);
}

double mean_stress(const StressPoint& s) { return (s.sxx + s.syy + s.szz) / 3.0; }

// Simple shear: dexy = dgamma / 2 (tensor component), no normal strain, so
// the stress stays pure shear and tau = sxy.
StrainIncrement simple_shear(double dgamma, double gamma_dot) {
  return {0.0, 0.0, 0.5 * dgamma, gamma_dot, 1e-3};
}

TEST(Tresca, SimpleShearRisesWithSlopeGThenYieldsAtSu) {
  const MaterialParams m = tresca(1.0, 1.0, 0.0, StrengthForm::Multiplicative);
  const double G = m.shear;
  const double gamma_y = kSu0 / G;
  const double dgamma = gamma_y / 7.3;  // yield falls inside a step
  StressPoint s{0, 0, 0, 0, 0, 0};
  double gamma = 0.0;
  int elastic_steps = 0, plastic_steps = 0;
  for (int step = 0; step < 30; ++step) {
    update_stress(m, simple_shear(dgamma, 0.0), s);
    gamma += dgamma;
    EXPECT_EQ(s.sxx, 0.0);
    EXPECT_EQ(s.syy, 0.0);
    EXPECT_EQ(s.szz, 0.0);
    EXPECT_DOUBLE_EQ(s.su, kSu0);
    if (gamma < gamma_y) {
      ++elastic_steps;
      EXPECT_NEAR(s.sxy / (G * gamma), 1.0, 1e-12);
      EXPECT_EQ(s.xi, 0.0);
    } else {
      ++plastic_steps;
      EXPECT_NEAR(s.sxy / kSu0, 1.0, 1e-10);
      // Every bit of shear beyond yield is plastic: xi = gamma - su / G.
      EXPECT_NEAR(s.xi / (gamma - gamma_y), 1.0, 1e-9);
    }
  }
  EXPECT_EQ(elastic_steps, 7);
  EXPECT_EQ(plastic_steps, 23);
}

TEST(Tresca, SofteningFollowsTheFormula) {
  const StrengthParams p = tresca(40.0, 5.0, 0.0, StrengthForm::Multiplicative).strength;
  const double d_rem = 0.025;
  EXPECT_NEAR(softening(p, 0.0), 1.0, 1e-12);
  // At xi95, exp(-3) = 4.98 % of the drop 1 - d_rem is left: "95 % remoulded".
  EXPECT_NEAR((softening(p, 5.0) - d_rem) / (1.0 - d_rem), std::exp(-3.0), 1e-12);
  EXPECT_NEAR((softening(p, 5.0) - d_rem) / (1.0 - d_rem), 0.05, 3e-4);
  EXPECT_NEAR(softening(p, 2.0), d_rem + (1.0 - d_rem) * std::exp(-1.2), 1e-12);
  EXPECT_NEAR(softening(p, 1e3), d_rem, 1e-12);
  // St = 1: no softening whatever xi95 is.
  const StrengthParams intact = tresca(1.0, 0.3, 0.0, StrengthForm::Multiplicative).strength;
  EXPECT_EQ(softening(intact, 7.0), 1.0);
}

TEST(Tresca, RateFactorFollowsTheFormula) {
  const StrengthParams p = tresca(1.0, 1.0, 0.4, StrengthForm::Multiplicative).strength;
  EXPECT_EQ(rate_factor(p, 0.0), 0.0);
  EXPECT_NEAR(rate_factor(p, 0.01), 0.4, 1e-12);  // at the reference rate
  EXPECT_NEAR(rate_factor(p, 1.0), 0.4 * std::pow(100.0, 0.1), 1e-12);
  EXPECT_NEAR(rate_factor(p, 1e-4), 0.4 * std::pow(0.01, 0.1), 1e-12);
  const StrengthParams no_rate = tresca(1.0, 1.0, 0.0, StrengthForm::Multiplicative).strength;
  EXPECT_EQ(rate_factor(no_rate, 5.0), 0.0);
}

// Driven past yield at a fixed rate, the in-plane shear stress follows the
// softened, rate-scaled strength of the stored xi at every step.
void expect_stress_on_strength_curve(const MaterialParams& m, double gamma_dot) {
  SCOPED_TRACE(testing::Message() << "form " << static_cast<int>(m.strength.form) << ", eta "
                                  << m.strength.eta << ", gamma_dot " << gamma_dot);
  const double dgamma = 0.4 * kSu0 / m.shear;
  StressPoint s{0, 0, 0, 0, 0, 0};
  int plastic_steps = 0;
  for (int step = 0; step < 400; ++step) {
    update_stress(m, simple_shear(dgamma, gamma_dot), s);
    const double su = expected_su(m.strength, s.xi, gamma_dot);
    EXPECT_NEAR(s.su / su, 1.0, 1e-12);
    if (s.xi == 0.0) {
      EXPECT_LE(s.sxy, su);
      continue;
    }
    ++plastic_steps;
    EXPECT_NEAR(s.sxy / su, 1.0, 1e-8);
  }
  EXPECT_GT(plastic_steps, 300);
  EXPECT_GT(s.xi, 2.0 * m.strength.xi95);  // well into the remoulding
}

TEST(Tresca, SoftenedYieldStressBothForms) {
  for (const StrengthForm form : {StrengthForm::Additive, StrengthForm::Multiplicative})
    expect_stress_on_strength_curve(tresca(5.0, 0.5, 0.0, form), 0.0);
}

TEST(Tresca, RateScaledYieldStressBothForms) {
  for (const StrengthForm form : {StrengthForm::Additive, StrengthForm::Multiplicative})
    for (const double gamma_dot : {1e-4, 0.01, 1.0, 50.0})
      expect_stress_on_strength_curve(tresca(5.0, 0.5, 0.6, form), gamma_dot);
  // The two forms differ where it matters: su0 (S + R) against su0 S (1 + R).
  const StrengthParams add = tresca(5.0, 0.5, 0.6, StrengthForm::Additive).strength;
  const StrengthParams mul = tresca(5.0, 0.5, 0.6, StrengthForm::Multiplicative).strength;
  const double S = softening(add, 1.0), R = rate_factor(add, 1.0);
  EXPECT_NEAR(strength(add, 1.0, 1.0), kSu0 * (S + R), 1e-8 * kSu0);
  EXPECT_NEAR(strength(mul, 1.0, 1.0), kSu0 * S * (1.0 + R), 1e-8 * kSu0);
  EXPECT_GT(std::fabs(strength(add, 1.0, 1.0) - strength(mul, 1.0, 1.0)), 0.1 * kSu0);
}

TEST(Tresca, ElasticStepStoresTheCurrentStrength) {
  const MaterialParams m = tresca(5.0, 0.5, 0.6, StrengthForm::Additive);
  StressPoint s{-1.5e4, -1.6e4, 100.0, -1.55e4, 0.3, 0.0};
  update_stress(m, simple_shear(1e-4, 2.0), s);
  EXPECT_EQ(s.xi, 0.3);
  EXPECT_NEAR(s.su / expected_su(m.strength, 0.3, 2.0), 1.0, 1e-12);
  EXPECT_LT(in_plane_tau(s), s.su);
}

// One large increment on a stress point with unequal normal stresses and
// strong softening: the return must keep szz and the mean stress, scale
// the in-plane deviator radially, and end on the yield surface of the
// strength at the end of the increment. The xi95 values put the softening
// modulus 3 su0 (1 - d_rem) / xi95 below and far above G (a snap-back),
// where a plain Newton iteration fails.
TEST(Tresca, LargeIncrementReturnsToTheEndOfIncrementStrength) {
  for (const double xi95 : {0.05, 0.002}) {
    SCOPED_TRACE(testing::Message() << "xi95 " << xi95);
    const MaterialParams m = tresca(40.0, xi95, 0.3, StrengthForm::Multiplicative);
    const StrainIncrement d{0.02, -0.012, 0.015, 0.8, 1e-3};
    const StressPoint start{-5e4, -8e4, 1e3, -6.5e4, 0.0, 0.0};
    StressPoint trial = start;
    elastic_update(m, d, trial);
    StressPoint s = start;
    update_stress(m, d, s);

    const double scale = std::fabs(mean_stress(trial));
    EXPECT_NEAR(mean_stress(s), mean_stress(trial), 1e-12 * scale);
    EXPECT_NEAR(s.szz, trial.szz, 1e-12 * scale);
    EXPECT_NEAR(0.5 * (s.sxx + s.syy), 0.5 * (trial.sxx + trial.syy), 1e-12 * scale);

    const double tau_trial = in_plane_tau(trial), tau = in_plane_tau(s);
    const double dxi = s.xi - start.xi;
    EXPECT_GT(dxi, 0.0);
    EXPECT_NEAR((tau_trial - tau) / m.shear / dxi, 1.0, 1e-9);
    // Radial: the deviator keeps its direction.
    EXPECT_NEAR(s.sxy / tau, trial.sxy / tau_trial, 1e-12);
    EXPECT_NEAR((s.sxx - s.syy) / tau, (trial.sxx - trial.syy) / tau_trial, 1e-12);

    const double su_end = expected_su(m.strength, s.xi, d.gamma_dot);
    const double su_start = expected_su(m.strength, start.xi, d.gamma_dot);
    EXPECT_NEAR(tau / su_end, 1.0, 1e-10);
    EXPECT_NEAR(s.su / su_end, 1.0, 1e-12);
    EXPECT_LT(su_end, 0.5 * su_start);  // the softening within the step matters
  }
}

}  // namespace
}  // namespace runout

namespace runout {
namespace {

// The strength law four particles at a time (strength.hpp, lanes.hpp) uses
// glibc's vector exp and log where the build has them: within a few ulp of
// the scalar law over the strains and rates a run meets (the rate factor
// as exp(n ln x): the error of ln x, times n < 1, adds at most an ulp or
// two to exp's own).
TEST(Tresca, FourAtATimeStrengthLawIsWithinUlpsOfTheScalarOne) {
  const MaterialParams m = tresca(40.0, 5.0, 1.0, StrengthForm::Additive);
  const StrengthParams& p = m.strength;
  const auto ulps = [](double a, double b) {
    return std::fabs(a - b) / (std::numeric_limits<double>::epsilon() * std::fabs(b));
  };
  double worst_softening = 0, worst_rate = 0;
  for (int i = 0; i < 4000; i += 4) {
    double xi[4], rate[4];
    for (int k = 0; k < 4; ++k) {
      xi[k] = 1e-3 * (i + k) * (i + k) / 400.0;            // 0 .. 40 = 8 xi95
      rate[k] = std::pow(10.0, -8.0 + 12.0 * (i + k) / 4000.0);  // 1e-8 .. 1e4 1/s
    }
    const Lanes S = softening_x4(p, load_lanes(xi));
    Lanes a, b;
    rate_scaling_x4(p, load_lanes(rate), a, b);
    for (int k = 0; k < 4; ++k) {
      worst_softening = std::max(worst_softening, ulps(lane(S, k), softening(p, xi[k])));
      const RateScaling one = rate_scaling(p, rate[k]);
      EXPECT_EQ(lane(a, k), one.a);
      worst_rate = std::max(worst_rate, ulps(lane(b, k), one.b));
    }
  }
  std::printf("four at a time: softening within %.2f ulp, rate factor within %.2f ulp\n",
              worst_softening, worst_rate);
  EXPECT_LE(worst_softening, 4.0);
  EXPECT_LE(worst_rate, 8.0);
  Lanes a, b;
  rate_scaling_x4(p, load_lanes(std::array<double, 4>{0.0, -1.0, 0.0, p.reference_rate}.data()), a, b);
  EXPECT_EQ(lane(b, 0), 0.0);  // at rest, and for a negative rate: no rate factor
  EXPECT_EQ(lane(b, 1), 0.0);
  EXPECT_NEAR(lane(b, 3), p.eta, 4e-16 * p.eta);  // at the reference rate, eta
}

// The CPU backend updates four particles at a time (stress_update_x4): the
// same state as stress_update one at a time, to rounding, for elastic
// particles and for softening, rate-dependent Tresca ones, some yielding
// (the plastic correction, one lane at a time) and some not.
TEST(Tresca, FourAtATimeStressUpdateMatchesOneAtATime) {
  const MaterialParams mats[] = {elastic_params(600.0, kYoungs, kPoisson),
                                 tresca(3.0, 0.5, 0.2, StrengthForm::Multiplicative)};
  const int n = 4 * 200;
  const double dt = 2e-4;
  Particles one;
  one.resize(n);
  std::vector<double> lxx(n), lxy(n), lyx(n), lyy(n), dx(n), dy(n);
  ParticleView P = one.view();
  int yielding = 0;
  for (int p = 0; p < n; ++p) {
    const double s = std::sin(1.3 * p + 0.2), t = std::cos(2.9 * p);
    P.material[p] = (p / 8) % 2;
    P.mass[p] = 6.0 * (1.0 + 0.1 * s);
    P.vol0[p] = 0.01;
    P.vol[p] = 0.01 * (1.0 + 0.02 * t);
    P.x[p] = 3.0 + s;
    P.y[p] = 1.0 + t;
    P.vx[p] = 0.4 * t;
    P.vy[p] = -0.3 * s;
    P.sxx[p] = -8000.0 + 2400.0 * s;
    P.syy[p] = -9000.0 - 2400.0 * t;
    P.szz[p] = -8500.0;
    P.sxy[p] = 2000.0 * s * t;
    P.xi[p] = 0.3 * (1.0 + t);
    P.su[p] = kSu0;
    P.fxx[p] = 1.0 + 0.05 * s;
    P.fxy[p] = 0.2 * t;
    P.fyx[p] = -0.1 * s;
    P.fyy[p] = 1.0 - 0.03 * t;
    lxx[p] = 2.0 * s;
    lxy[p] = 40.0 * t;
    lyx[p] = -3.0 * s * t;
    lyy[p] = -1.5 * t;
    dx[p] = 1e-4 * s;
    dy[p] = -1e-4 * t;
  }
  Particles four = one;
  const StepScratch scratch{dx.data(), dy.data()};
  std::vector<double> speed_one(n), speed_four(n);
  for (int p = 0; p < n; ++p) {
    const double xi = P.xi[p];
    speed_one[p] = stress_update(P, p, {lxx[p], lxy[p], lyx[p], lyy[p]}, mats, dt, scratch);
    yielding += P.xi[p] > xi;
  }
  const ParticleView Q = four.view();
  for (int p = 0; p < n; p += 4) {
    const auto at = [p](const std::vector<double>& a) { return load_lanes(a.data() + p); };
    store_lanes(speed_four.data() + p, stress_update_x4(Q, p, at(lxx), at(lxy), at(lyx), at(lyy),
                                                        mats[Q.material[p]], dt, scratch));
  }
  EXPECT_GT(yielding, n / 8);
  EXPECT_LT(yielding, n / 2);  // the Tresca half, not all of it
  const auto a = one.double_arrays(), b = four.double_arrays();
  for (std::size_t k = 0; k < a.size(); ++k)
    for (int p = 0; p < n; ++p)
      EXPECT_NEAR((*b[k])[p], (*a[k])[p], 1e-13 * (1.0 + std::fabs((*a[k])[p])))
          << "array " << k << ", particle " << p;
  for (int p = 0; p < n; ++p) EXPECT_NEAR(speed_four[p], speed_one[p], 1e-13 * speed_one[p]);
}

}  // namespace
}  // namespace runout
