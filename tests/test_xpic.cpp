// XPIC(m) (stages.hpp, Hammerquist and Nairn 2017), by its algebra:
// - XPIC(1) is PIC, to rounding;
// - a rigid translation passes any order unchanged (the coefficients sum
//   to one and every round trip reproduces a constant field);
// - it removes what the grid cannot hold: a resting block given random
//   particle velocities keeps nearly all of that energy through a FLIP
//   step and well under half through an XPIC(5) step;
// - on its schedule ([solver] xpic_cells) it runs on the steps that cross
//   a multiple of its period, whatever the Courant number.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "runout/measure/diagnostics.hpp"
#include "runout/mpm/simulation.hpp"
#include "scene_builders.hpp"

using namespace runout;

namespace {

Scene resting_block(TransferKind transfer, int order) {
  Scene s = fixtures::block_scene({1.0, 1.0}, {5.0, 3.0}, {0.0, 0.0}, {6.0, 4.0}, 0.5, 2, 1000.0,
                                  1e6, 0.3);
  s.solver.transfer = transfer;
  s.solver.flip = 0.0;  // PicFlip: pure PIC
  s.solver.xpic_order = order;
  return s;
}

void set_velocities(Particles& P, unsigned seed, double vx, double vy, double noise) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-noise, noise);
  for (int p = 0; p < P.size(); ++p) {
    P.vx[p] = vx + u(rng);
    P.vy[p] = vy + u(rng);
  }
}

double kinetic_energy_after_one_step(TransferKind transfer, int order) {
  Simulation sim(resting_block(transfer, order));
  set_velocities(sim.particles(), 7, 0.0, 0.0, 1e-3);
  sim.step(1e-6);  // short enough that the stress adds nothing visible
  return particle_totals(sim.particles()).kinetic_energy;
}

}  // namespace

TEST(Xpic, OrderOneIsPic) {
  Simulation xpic(resting_block(TransferKind::Xpic, 1));
  Simulation pic(resting_block(TransferKind::PicFlip, 1));
  set_velocities(xpic.particles(), 3, 0.2, -0.1, 0.05);
  set_velocities(pic.particles(), 3, 0.2, -0.1, 0.05);
  for (int k = 0; k < 50; ++k) {
    xpic.step(1e-4);
    pic.step(1e-4);
  }
  const Particles &a = xpic.particles(), &b = pic.particles();
  for (int p = 0; p < a.size(); ++p) {
    ASSERT_NEAR(a.vx[p], b.vx[p], 1e-13);
    ASSERT_NEAR(a.vy[p], b.vy[p], 1e-13);
  }
}

TEST(Xpic, RigidTranslationPassesUnchanged) {
  for (int order : {2, 3, 5, 8}) {
    Simulation sim(resting_block(TransferKind::Xpic, order));
    set_velocities(sim.particles(), 1, 0.3, -0.2, 0.0);
    sim.step(1e-4);
    const Particles& P = sim.particles();
    for (int p = 0; p < P.size(); ++p) {
      ASSERT_NEAR(P.vx[p], 0.3, 1e-12) << "order " << order;
      ASSERT_NEAR(P.vy[p], -0.2, 1e-12) << "order " << order;
    }
  }
}

TEST(Xpic, RemovesWhatTheGridCannotHoldWhereFlipKeepsIt) {
  Simulation sim(resting_block(TransferKind::Flip, 1));
  set_velocities(sim.particles(), 7, 0.0, 0.0, 1e-3);
  const double start = particle_totals(sim.particles()).kinetic_energy;
  const double flip = kinetic_energy_after_one_step(TransferKind::Flip, 1);
  const double xpic2 = kinetic_energy_after_one_step(TransferKind::Xpic, 2);
  const double xpic5 = kinetic_energy_after_one_step(TransferKind::Xpic, 5);
  const double pic = kinetic_energy_after_one_step(TransferKind::PicFlip, 1);
  std::printf("noise energy kept by one step: FLIP %.4f, XPIC(5) %.4f, XPIC(2) %.4f, PIC %.4f\n",
              flip / start, xpic5 / start, xpic2 / start, pic / start);
  EXPECT_GT(flip / start, 0.99);
  EXPECT_LT(xpic5 / start, 0.5);
  // Higher orders keep more of what the grid does hold, so more energy.
  EXPECT_LT(pic, xpic2);
  EXPECT_LT(xpic2, xpic5);
}

TEST(Xpic, ScheduleRunsOnTheStepsThatCrossItsPeriod) {
  StepConfig c;
  c.transfer = TransferKind::Flip;
  c.xpic_period = 0.1;
  int filtered = 0;
  const double dt = 0.1 / 7.3;
  for (double t = 0; t < 1.0 - 1e-12; t += dt) {
    configure_step(c, t, dt);
    filtered += c.xpic_now;
  }
  EXPECT_EQ(filtered, 10);
  c.transfer = TransferKind::Xpic;
  configure_step(c, 0.0, dt);
  EXPECT_TRUE(c.xpic_now);
}
