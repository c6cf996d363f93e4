// Periodic boundaries along x (boundary.left = right = "periodic"):
// - the seam conserves: an elastic block drifting across it keeps its
//   mass, momentum and shape, and its displacement is the distance it
//   travelled;
// - an infinite layer: a Bingham layer (the additive rate form with n = 1)
//   on a no-slip incline reaches the analytic plug-flow velocity profile
//   within 2 %;
// - particles that cross the seam between reorders join cell groups at the
//   other end of the box without growing the threads' buffers to the
//   particle count, and the results stay those of one thread.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "runout/mpm/simulation.hpp"
#include "scene_builders.hpp"

using namespace runout;

namespace {

constexpr double kPi = 3.14159265358979323846;

void make_periodic(Scene& s) {
  s.boundary.left = s.boundary.right = BoundaryKind::Periodic;
}

double momentum_x(const Particles& P) {
  double px = 0;
  for (int p = 0; p < P.size(); ++p) px += P.mass[p] * P.vx[p];
  return px;
}

}  // namespace

// A block 1 m wide in a period of 3 m, drifting at 2 m/s with no gravity,
// crosses the seam twice in 4 s. A rigid translation is exact under FLIP
// and GIMP, so the particles keep their spacing and speed to round-off.
TEST(Periodic, BlockDriftsAcrossTheSeamUnchanged) {
  Scene s = fixtures::block_scene({1.5, 1.0}, {2.5, 2.0}, {0.0, 0.0}, {3.0, 3.0}, 0.25, 2, 1000.0,
                                  1e6, 0.3);
  make_periodic(s);
  s.bodies[0].velocity = {2.0, 0.0};
  Simulation sim(s);
  const Particles start = sim.particles();
  sim.advance_to(4.0);
  const Particles& P = sim.particles();
  const double px0 = momentum_x(start);
  EXPECT_NEAR(momentum_x(P), px0, 1e-9 * px0);
  std::map<std::int64_t, int> at_start;  // the driver reorders the particles
  for (int p = 0; p < start.size(); ++p) at_start[start.id[p]] = p;
  double worst_speed = 0, worst_travel = 0, worst_wrap = 0, worst_gap = 0;
  for (int p = 0; p < P.size(); ++p) {
    const int q = at_start.at(P.id[p]);
    worst_speed = std::max({worst_speed, std::abs(P.vx[p] - 2.0), std::abs(P.vy[p])});
    // 8 m travelled; the particle is back in the period, x0 moved with it.
    worst_travel = std::max(worst_travel, std::abs((P.x[p] - P.x0[p]) - 8.0));
    worst_wrap = std::max(worst_wrap, std::abs(P.x[p] - std::fmod(start.x[q] + 8.0, 3.0)));
    worst_gap = std::max(worst_gap, std::abs(P.y[p] - start.y[q]));
    ASSERT_GE(P.x[p], 0.0);
    ASSERT_LT(P.x[p], 3.0);
  }
  std::printf("worst |v - v0| %.2e m/s, travel error %.2e m, wrap error %.2e m, dy %.2e m\n",
              worst_speed, worst_travel, worst_wrap, worst_gap);
  EXPECT_LT(worst_speed, 1e-9);
  EXPECT_LT(worst_travel, 1e-9);
  EXPECT_LT(worst_wrap, 1e-9);
  EXPECT_LT(worst_gap, 1e-9);
}

// A block of 72 000 particles drifting across the seam: between reorders
// the particles that crossed keep their indices, from the far end of the
// order, so the cell groups they join span nearly all the particles. Each
// thread's buffers stay within the span limit (one thread's share of the
// particles here), and two threads give one thread's results bit for bit.
TEST(Periodic, SeamCrossingsKeepCellGroupBuffersBounded) {
  Scene s = fixtures::block_scene({1.9, 0.5}, {5.9, 3.3125}, {0.0, 0.0}, {6.0, 4.0}, 0.05, 4, 1000.0,
                                  1e6, 0.3);
  make_periodic(s);
  s.bodies[0].velocity = {5.0, 0.0};
  const auto run = [&](int threads, int& buffer) {
    const int before = omp_get_max_threads();
    omp_set_num_threads(threads);
    Simulation sim(s);
    sim.advance_to(0.05);  // the front 0.25 m past the seam, five reorders
    omp_set_num_threads(before);
    buffer = sim.backend().group_buffer_particles();
    return sim.particles();
  };
  int one_buffer = 0, two_buffer = 0;
  const Particles one = run(1, one_buffer);
  const Particles two = run(2, two_buffer);
  ASSERT_EQ(one.size(), 72000);
  int crossed = 0;
  for (int p = 0; p < two.size(); ++p) crossed += two.x[p] < 1.0;
  EXPECT_GT(crossed, 1000);
  std::printf("%d particles crossed; buffers of %d particles on one thread, %d on two\n", crossed,
              one_buffer, two_buffer);
  EXPECT_LE(two_buffer, std::max(OpenMpBackend::kGroupSpanMin, one.size() / 2));
  for (int p = 0; p < one.size(); ++p) {
    ASSERT_EQ(one.id[p], two.id[p]) << p;
    ASSERT_EQ(one.x[p], two.x[p]) << p;
    ASSERT_EQ(one.vx[p], two.vx[p]) << p;
    ASSERT_EQ(one.sxx[p], two.sxx[p]) << p;
  }
}

// A Bingham layer of depth H on a slope theta, no-slip at its base:
// the shear stress tau(z) = rho g sin(theta) (H - z) exceeds the yield
// stress tau_y above a plug of thickness H_p = tau_y / (rho g sin theta),
// and below it tau - tau_y = mu du/dz, so
//   u(z) = rho g sin(theta) (z_p z - z^2 / 2) / mu  for z <= z_p = H - H_p,
//   u    = rho g sin(theta) z_p^2 / (2 mu)          in the plug
// (the Bingham film on an incline, e.g. Liu and Mei 1989, J. Fluid Mech.
// 207). The additive strength su0 (S + eta gamma_dot / gamma_dot_ref) with
// no softening (S = 1) and n = 1 is Bingham with tau_y = su0 and
// mu = su0 eta / gamma_dot_ref. Here H = 2 m, H_p = 1 m and the plug runs at
// 1.000 m/s. The flow starts from rest: the plug of mass rho H_p over a
// sheared layer z_p deep settles with a time constant of about
// rho z_p (H_p + z_p / 3) / mu = 1.6 s, so by 12 s the start is gone to
// 1e-3. The layer is 4 cells long and periodic, so it is infinite. E is
// stiff enough (1e7 Pa, 3700 tau_y) for its elastic compression under its
// weight, 0.2 %, not to matter: at E = 1e6 Pa the layer is 1.7 % thinner
// and its plug 2.8 % slower, as u_plug ~ z_p^2 says.
TEST(Periodic, BinghamLayerReachesThePlugFlowProfile) {
  const double rho = 1600, g = 9.81, theta = 10.0, H = 2.0, Hp = 1.0, h = 0.1;
  const double drive = rho * g * std::sin(theta * kPi / 180);  // d tau / d(depth)
  const double tau_y = drive * Hp, mu = 0.5 * drive, zp = H - Hp;
  Scene s = fixtures::block_scene({0.0, 0.0}, {0.4, H}, {0.0, 0.0}, {0.4, 3.0}, h, 2, rho, 1e7,
                                  0.3);
  make_periodic(s);
  s.boundary.top = BoundaryKind::Free;
  s.base.kind = BaseKind::Planar;
  s.base.interface = InterfaceKind::NoSlip;
  s.gravity.vector = {g * std::sin(theta * kPi / 180), -g * std::cos(theta * kPi / 180)};
  MaterialSpec& m = s.materials[0];
  m.model = MaterialModel::Tresca;
  m.su0 = tau_y;
  m.eta = mu / tau_y;
  m.rate_exponent = 1.0;
  m.reference_rate = 1.0;
  m.strength_form = StrengthForm::Additive;
  Simulation sim(s);
  sim.advance_to(12.0);

  const double plug = drive * zp * zp / (2.0 * mu);
  const auto analytic = [&](double z) {
    return z < zp ? drive * (zp * z - 0.5 * z * z) / mu : plug;
  };
  const Particles& P = sim.particles();
  double worst = 0, plug_sum = 0, plug_mass = 0;
  for (int p = 0; p < P.size(); ++p) {
    worst = std::max(worst, std::abs(P.vx[p] - analytic(P.y[p])));
    if (P.y[p] > zp) {
      plug_sum += P.mass[p] * P.vx[p];
      plug_mass += P.mass[p];
    }
  }
  const double plug_mpm = plug_sum / plug_mass;
  std::printf("plug %.4f m/s (analytic %.4f), worst particle error %.4f m/s\n", plug_mpm, plug,
              worst);
  for (double z = 0.025; z < H; z += 0.2) {
    double sum = 0;
    int count = 0;
    for (int p = 0; p < P.size(); ++p)
      if (std::abs(P.y[p] - z) < 0.03) {
        sum += P.vx[p];
        ++count;
      }
    if (count > 0) std::printf("  z %.3f: u %.4f, analytic %.4f\n", z, sum / count, analytic(z));
  }
  EXPECT_NEAR(plug_mpm, plug, 0.02 * plug);
  EXPECT_LT(worst, 0.02 * plug);
}
