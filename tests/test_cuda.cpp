// The CUDA backend against the CPU driver and the analytic tests. Each test
// first asks for a device and skips, with the reason, when there is none
// (no driver, no GPU): a build machine compiles and runs this file anyway.
//
// Why the backends differ at all: the GPU adds each particle's share to a
// node with atomicAdd, in whatever order the threads arrive, where the CPU
// adds in a fixed order (block colouring); the cell means of the volumetric
// smoothing and the reductions (basal force) likewise. Floating-point
// addition is not associative, so the node sums differ in the last bits
// (about 1e-16 relative), and nvcc contracts a * b + c into fused
// multiply-adds where g++ -O3 (no -march) does not. Elastic, smooth motion
// keeps such differences at round-off; plastic flow can grow them, slowly
// over a few hundred steps. Hence the tolerances below: 1e-6 relative on
// the toe and the kinetic energy, 1e-6 m on positions (cells of 1 m).
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>
#include <cmath>
#include <string>

#include "free_fall.hpp"
#include "runout/cuda_simulation.hpp"
#include "runout/diagnostics.hpp"
#include "runout/morphology.hpp"
#include "runout/scene_parser.hpp"
#include "runout/seeding.hpp"
#include "runout/simulation.hpp"
#include "scene_builders.hpp"

using namespace runout;

#define SKIP_WITHOUT_GPU()                                   \
  do {                                                       \
    std::string why_not;                                     \
    if (!cuda_device_available(why_not)) GTEST_SKIP() << why_not; \
  } while (0)

namespace {

double relative(double a, double b) {
  const double scale = std::max(std::fabs(a), std::fabs(b));
  return scale > 0.0 ? std::fabs(a - b) / scale : 0.0;
}

}  // namespace

// Case 1 (elongation, Tresca with softening and rate, frictional base) at
// 1 m cells and 2 x 2 particles per cell, 300 steps of the same dt on both.
TEST(Cuda, AgreesWithTheCpuOnCoarseCase1) {
  SKIP_WITHOUT_GPU();
  Scene s = load_scene_file(std::string(RUNOUT_SOURCE_DIR) + "/scenes/case1_elongation.toml");
  apply_overrides(s, 1.0, 2);
  Simulation cpu(s);
  CudaSimulation gpu(s);
  ASSERT_EQ(gpu.size(), cpu.particles().size());
  Particles P;
  for (int k = 1; k <= 300; ++k) {
    const double dt = cpu.stable_dt();  // the CPU's dt for both, so that they step alike
    cpu.step(dt);
    gpu.step(dt);
    if (k % 50 != 0) continue;
    gpu.download(P);
    const SlideMorphology a = measure_slide(cpu.particles(), cpu.base().view(), cpu.particle_spacing());
    const SlideMorphology b = measure_slide(P, gpu.base().view(), gpu.particle_spacing());
    EXPECT_LE(relative(a.toe_s, b.toe_s), 1e-6) << "step " << k;
    EXPECT_LE(relative(a.kinetic_energy, b.kinetic_energy), 1e-6) << "step " << k;
    EXPECT_LE(relative(cpu.basal_shear_force(), gpu.basal_shear_force()), 1e-6) << "step " << k;
  }
  // The CPU keeps its particles in block order in memory, the download
  // comes in seeding order: pair them by id (seeded as 0..n-1).
  double dx = 0;
  const Particles& C = cpu.particles();
  ASSERT_EQ(C.size(), P.size());
  std::vector<int> cpu_index(C.size());
  for (int p = 0; p < C.size(); ++p) cpu_index[C.id[p]] = p;
  for (int p = 0; p < P.size(); ++p) {
    const int q = cpu_index[P.id[p]];
    dx = std::max({dx, std::fabs(C.x[q] - P.x[p]), std::fabs(C.y[q] - P.y[p])});
  }
  std::printf("largest CPU-GPU position difference after 300 steps: %.3g m\n", dx);
  EXPECT_LE(dx, 1e-6);
  EXPECT_EQ(gpu.time(), cpu.time());
}

// test_free_fall.cpp on the GPU: x0 + v0 t + g t^2 / 2 to 1e-10 relative.
TEST(Cuda, FreeFallLandsOnTheParabola) {
  SKIP_WITHOUT_GPU();
  for (const ShapeKind shape : {ShapeKind::Gimp, ShapeKind::Linear}) {
    const Scene s = fixtures::free_fall_scene(shape);
    CudaSimulation sim(s);
    const double t = fixtures::kFreeFallTime;
    sim.advance_to(t);
    ASSERT_GT(sim.steps(), 20);
    EXPECT_EQ(sim.time(), t);
    Particles P;
    sim.download(P);
    ASSERT_GT(P.size(), 0);
    fixtures::expect_on_the_parabola(P, s, t);
  }
}

// test_base_contact.cpp's frictional block on a 5-degree incline:
// a = g sin(theta) - tau / (rho H), and the base resists with tau L.
TEST(Cuda, FrictionalBlockAcceleratesAtTheRigidBlockRate) {
  SKIP_WITHOUT_GPU();
  constexpr double kTheta = 5.0 * M_PI / 180.0, kG = 9.81, kRho = 600.0, kH = 2.0, kL = 10.0;
  const double tau = 500.0;
  Scene s = fixtures::block_scene({2.0, 0.0}, {2.0 + kL, kH}, {0.0, 0.0}, {60.0, 8.0}, 0.25, 2,
                                  kRho, 2e6, 0.3);
  s.gravity.vector = {kG * std::sin(kTheta), -kG * std::cos(kTheta)};
  s.boundary.bottom = BoundaryKind::Free;
  s.base.kind = BaseKind::Planar;
  s.base.interface = InterfaceKind::Frictional;
  s.base.shear_strength = tau;
  Particles start = seed_particles(s);
  fixtures::set_geostatic(start, kRho, kG * std::cos(kTheta), kH, 0.3 / 0.7);
  CudaSimulation sim(s, start);
  Particles P;
  const auto mean_vx = [&] {
    sim.download(P);
    const ParticleTotals t = particle_totals(P);
    return t.momentum_x / t.mass;
  };
  sim.advance_to(1.0);
  const double v1 = mean_vx();
  sim.advance_to(3.0);
  const double a = (mean_vx() - v1) / 2.0;
  const double exact = kG * std::sin(kTheta) - tau / (kRho * kH);
  std::printf("GPU frictional: a = %.6g, exact %.6g\n", a, exact);
  EXPECT_NEAR(a, exact, 0.01 * exact);
  EXPECT_NEAR(sim.basal_shear_force(), -tau * kL, 0.01 * tau * kL);
}
