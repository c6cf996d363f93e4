// Conservation through a step and the zero-stress response to rigid
// translation; repeatability of the coloured scatter.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <random>

#include "runout/measure/diagnostics.hpp"
#include "runout/mpm/simulation.hpp"
#include "scene_builders.hpp"

using namespace runout;

namespace {

// A block with random velocities and random stresses: a hard case for
// conservation, since every node gets unbalanced contributions.
Simulation random_block(ShapeKind shape, double flip, double h = 0.5, double length = 6.0) {
  Scene s = fixtures::block_scene({3.0, 3.0}, {3.0 + length, 6.0}, {0.0, 0.0},
                                  {6.0 + length, 9.0}, h, 2, 1500.0, 1e6, 0.3);
  s.grid.shape = shape;
  s.solver.transfer = TransferKind::PicFlip;
  s.solver.flip = flip;
  s.solver.mass_threshold = 0.0;
  Simulation sim(s);
  Particles& P = sim.particles();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int p = 0; p < P.size(); ++p) {
    P.vx[p] = u(rng);
    P.vy[p] = u(rng);
    P.sxx[p] = 1e3 * u(rng);
    P.syy[p] = 1e3 * u(rng);
    P.sxy[p] = 1e3 * u(rng);
  }
  return sim;
}

double grid_sum(const double* a, int n) {
  double s = 0;
  for (int i = 0; i < n; ++i) s += a[i];
  return s;
}

}  // namespace

TEST(Conservation, MassIsExactAndMomentumToRoundOff) {
  for (ShapeKind shape : {ShapeKind::Gimp, ShapeKind::Linear}) {
    for (double flip : {0.0, 0.5, 1.0}) {
      Simulation sim = random_block(shape, flip);
      const ParticleTotals before = particle_totals(sim.particles());
      double scale = 0;
      for (int p = 0; p < sim.particles().size(); ++p)
        scale += sim.particles().mass[p] *
                 std::hypot(sim.particles().vx[p], sim.particles().vy[p]);
      for (int k = 0; k < 5; ++k) sim.step(1e-3);
      const ParticleTotals after = particle_totals(sim.particles());
      EXPECT_EQ(after.mass, before.mass);
      EXPECT_NEAR(after.momentum_x, before.momentum_x, 1e-13 * scale) << "flip " << flip;
      EXPECT_NEAR(after.momentum_y, before.momentum_y, 1e-13 * scale) << "flip " << flip;
      // The grid carries the same mass and (remapped) momentum as the particles.
      const GridView& g = sim.grid().view();
      EXPECT_NEAR(grid_sum(g.m, g.size()), after.mass, 1e-13 * after.mass);
      EXPECT_NEAR(grid_sum(g.px, g.size()), after.momentum_x, 1e-13 * scale);
      EXPECT_NEAR(grid_sum(g.py, g.size()), after.momentum_y, 1e-13 * scale);
    }
  }
}

TEST(Conservation, RigidTranslationStaysStressFree) {
  for (ShapeKind shape : {ShapeKind::Gimp, ShapeKind::Linear}) {
    Scene s = fixtures::block_scene({3.0, 3.0}, {7.0, 5.0}, {0.0, 0.0}, {60.0, 20.0}, 0.5, 2,
                                   1000.0, 1e6, 0.3);
    s.grid.shape = shape;
    s.bodies[0].velocity = {7.0, 1.3};
    Simulation sim(s);
    sim.advance_to(3.0);  // crosses about 40 cells
    const Particles& P = sim.particles();
    for (int p = 0; p < P.size(); ++p) {
      EXPECT_LT(std::fabs(P.sxx[p]) + std::fabs(P.syy[p]) + std::fabs(P.sxy[p]), 1e-6);
      EXPECT_NEAR(P.x[p], P.x0[p] + 7.0 * 3.0, 1e-10 * P.x[p]);
      EXPECT_NEAR(P.vol[p], P.vol0[p], 1e-12 * P.vol0[p]);
    }
  }
}

TEST(Conservation, ScatterIsRepeatableAcrossThreadCounts) {
  const int threads = omp_get_max_threads();
  // Fine enough (28 800 particles) for every loop to go parallel, and long
  // enough (a grid box of about 245 cells: eight 32-cell strips of the CPU
  // scatter, four of each colour) for two threads to scatter side by side.
  Simulation a = random_block(ShapeKind::Gimp, 0.99, 0.1, 24.0);
  Simulation b = random_block(ShapeKind::Gimp, 0.99, 0.1, 24.0);
  ASSERT_GT(a.particles().size(), 4096);
  omp_set_num_threads(1);
  for (int k = 0; k < 10; ++k) a.step(1e-3);
  omp_set_num_threads(std::max(2, threads));
  for (int k = 0; k < 10; ++k) b.step(1e-3);
  omp_set_num_threads(threads);
  for (int p = 0; p < a.particles().size(); ++p) {
    ASSERT_EQ(a.particles().x[p], b.particles().x[p]);
    ASSERT_EQ(a.particles().sxx[p], b.particles().sxx[p]);
  }
}

TEST(Conservation, PermutingParticlesMovesEveryFieldTogether) {
  Simulation sim = random_block(ShapeKind::Gimp, 0.99);
  Particles P = sim.particles();
  const Particles before = P;
  std::vector<int> order(P.size());
  for (int k = 0; k < P.size(); ++k) order[k] = (7 * k + 3) % P.size();  // 7 is coprime with n
  ASSERT_NE(P.size() % 7, 0);
  P.permute(order);
  for (int k = 0; k < P.size(); ++k) {
    const int from = order[k];
    ASSERT_EQ(P.id[k], before.id[from]);
    ASSERT_EQ(P.x[k], before.x[from]);
    ASSERT_EQ(P.vy[k], before.vy[from]);
    ASSERT_EQ(P.sxy[k], before.sxy[from]);
    ASSERT_EQ(P.y0[k], before.y0[from]);
    ASSERT_EQ(P.material[k], before.material[from]);
  }
}
