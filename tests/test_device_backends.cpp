// The driver's device backends against the CPU backend and the analytic
// tests: the serial device backend (backend_serial.hpp: the CUDA backend's
// order of work on one CPU thread) everywhere, and the CUDA backend where
// the build has CUDA and the machine a device (it skips, with the reason,
// otherwise). So the step the GPU runs is exercised on every machine.
//
// Why the backends differ at all: a device backend adds each particle's
// share to a node in particle order (the GPU with atomicAdd, in whatever
// order the threads arrive), where the CPU adds block by block in a fixed
// colouring; the cell means of the volumetric smoothing and the reductions
// (basal force) likewise. Floating-point addition is not associative, so
// the node sums differ in the last bits (about 1e-16 relative), and nvcc
// contracts a * b + c into fused multiply-adds where g++ -O3 (no -march)
// does not. Elastic, smooth motion keeps such differences at round-off;
// plastic flow can grow them, slowly over a few hundred steps. Hence the
// tolerances below: 1e-6 relative on the toe and the kinetic energy, 1e-6 m
// on positions (cells of 1 m).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <type_traits>
#include <vector>

#include "free_fall.hpp"
#include "runout/measure/diagnostics.hpp"
#include "runout/measure/morphology.hpp"
#include "runout/scene/scene_parser.hpp"
#include "runout/mpm/seeding.hpp"
#include "runout/mpm/simulation.hpp"
#include "scene_builders.hpp"
#ifdef RUNOUT_HAVE_CUDA
#include "runout/mpm/cuda_simulation.hpp"
#endif

using namespace runout;

namespace {

// What the tests need of a backend: its driver, whether it can run here,
// and its particles on the host in seeding order.
struct SerialDevice {
  using Sim = SerialDeviceSimulation;
  static bool available(std::string&) { return true; }
  static void download(const Sim& sim, Particles& out) {
    // The serial backend keeps them sorted by cell: back to seeding order
    // (ids are seeded 0..n-1), as the CUDA backend's download gives them.
    const Particles& P = sim.particles();
    std::vector<int> order(P.size());
    for (int p = 0; p < P.size(); ++p) order[P.id[p]] = p;
    out = P;
    out.permute(order);
  }
};
#ifdef RUNOUT_HAVE_CUDA
struct Cuda {
  using Sim = CudaSimulation;
  static bool available(std::string& why_not) { return cuda_device_available(why_not); }
  static void download(const Sim& sim, Particles& out) { sim.download(out); }
};
using Backends = ::testing::Types<SerialDevice, Cuda>;
#else
using Backends = ::testing::Types<SerialDevice>;
#endif

struct BackendName {
  template <class T>
  static std::string GetName(int) {
    return std::is_same<T, SerialDevice>::value ? "SerialDevice" : "Cuda";
  }
};

template <class B>
class DeviceBackend : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string why_not;
    if (!B::available(why_not)) GTEST_SKIP() << why_not;
  }
};
TYPED_TEST_SUITE(DeviceBackend, Backends, BackendName);

double relative(double a, double b) {
  const double scale = std::max(std::fabs(a), std::fabs(b));
  return scale > 0.0 ? std::fabs(a - b) / scale : 0.0;
}

// The CPU and the device backend stepped with the CPU's dt for `steps`
// steps; every 50 steps toe, kinetic energy and basal force compared, at
// the end every particle's position and xi (paired by id).
struct Difference {
  double largest;  // position [m] or xi
  double xi_max;   // the CPU's largest xi: that the run yielded at all
};
template <class B>
Difference largest_difference_from_the_cpu(const Scene& s, int steps) {
  Simulation cpu(s);
  typename B::Sim device(s);
  Particles P;
  for (int k = 1; k <= steps; ++k) {
    const double dt = cpu.stable_dt();  // the CPU's dt for both, so that they step alike
    cpu.step(dt);
    device.step(dt);
    if (k % 50 != 0 && k != steps) continue;
    B::download(device, P);
    const SlideMorphology a =
        measure_slide(cpu.particles(), cpu.base().view(), cpu.particle_spacing());
    const SlideMorphology b = measure_slide(P, device.base().view(), device.particle_spacing());
    EXPECT_LE(relative(a.toe_s, b.toe_s), 1e-6) << "step " << k;
    EXPECT_LE(relative(a.kinetic_energy, b.kinetic_energy), 1e-6) << "step " << k;
    EXPECT_LE(relative(cpu.basal_shear_force(), device.basal_shear_force()), 1e-6)
        << "step " << k;
  }
  EXPECT_EQ(device.time(), cpu.time());
  const Particles& C = cpu.particles();
  EXPECT_EQ(C.size(), P.size());
  std::vector<int> cpu_index(C.size());
  for (int p = 0; p < C.size(); ++p) cpu_index[C.id[p]] = p;
  Difference d{0.0, 0.0};
  for (int p = 0; p < P.size() && p < C.size(); ++p) {
    const int q = cpu_index[P.id[p]];
    d.largest = std::max({d.largest, std::fabs(C.x[q] - P.x[p]), std::fabs(C.y[q] - P.y[p]),
                          std::fabs(C.xi[q] - P.xi[p])});
    d.xi_max = std::max(d.xi_max, C.xi[q]);
  }
  return d;
}

}  // namespace

// Case 1 (elongation, Tresca with softening and rate, frictional base) at
// 1 m cells and 2 x 2 particles per cell, 300 steps.
TYPED_TEST(DeviceBackend, AgreesWithTheCpuOnCoarseCase1) {
  Scene s = load_scene_file(std::string(RUNOUT_SOURCE_DIR) + "/scenes/case1_elongation.toml");
  apply_overrides(s, 1.0, 2);
  const Difference d = largest_difference_from_the_cpu<TypeParam>(s, 300);
  std::printf("largest CPU-device difference after 300 steps: %.3g (m, and in xi; xi up to "
              "%.3g)\n", d.largest, d.xi_max);
  EXPECT_LE(d.largest, 1e-6);
}

// Regularised softening (nonlocal.hpp) runs in the one driver, so on every
// backend: case 4's sensitive clay with t_s = 0.2 m and l = 2 m at 1 m
// cells, 400 steps (past the start of yield, where the averaging moves xi).
TYPED_TEST(DeviceBackend, AgreesWithTheCpuWithNonlocalSoftening) {
  Scene s = load_scene_file(std::string(RUNOUT_SOURCE_DIR) + "/scenes/case4_spreading.toml");
  s.materials[0].band_thickness = 0.2;
  s.materials[0].nonlocal_length = 2.0;
  apply_overrides(s, 1.0, 2);
  const Difference d = largest_difference_from_the_cpu<TypeParam>(s, 400);
  std::printf("largest CPU-device difference, nonlocal, after 400 steps: %.3g (xi up to %.3g)\n",
              d.largest, d.xi_max);
  EXPECT_GT(d.xi_max, 0.0);  // it yielded, so the averaging had increments to spread
  EXPECT_LE(d.largest, 1e-6);
}

// test_free_fall.cpp on the device: x0 + v0 t + g t^2 / 2 to 1e-10 relative.
TYPED_TEST(DeviceBackend, FreeFallLandsOnTheParabola) {
  for (const ShapeKind shape : {ShapeKind::Gimp, ShapeKind::Linear}) {
    const Scene s = fixtures::free_fall_scene(shape);
    typename TypeParam::Sim sim(s);
    const double t = fixtures::kFreeFallTime;
    sim.advance_to(t);
    ASSERT_GT(sim.steps(), 20);
    EXPECT_EQ(sim.time(), t);
    Particles P;
    TypeParam::download(sim, P);
    ASSERT_GT(P.size(), 0);
    fixtures::expect_on_the_parabola(P, s, t);
  }
}

// test_base_contact.cpp's frictional block on a 5-degree incline:
// a = g sin(theta) - tau / (rho H), and the base resists with tau L.
TYPED_TEST(DeviceBackend, FrictionalBlockAcceleratesAtTheRigidBlockRate) {
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
  typename TypeParam::Sim sim(s, start);
  Particles P;
  const auto mean_vx = [&] {
    TypeParam::download(sim, P);
    const ParticleTotals t = particle_totals(P);
    return t.momentum_x / t.mass;
  };
  sim.advance_to(1.0);
  const double v1 = mean_vx();
  sim.advance_to(3.0);
  const double a = (mean_vx() - v1) / 2.0;
  const double exact = kG * std::sin(kTheta) - tau / (kRho * kH);
  std::printf("device frictional: a = %.6g, exact %.6g\n", a, exact);
  EXPECT_NEAR(a, exact, 0.01 * exact);
  EXPECT_NEAR(sim.basal_shear_force(), -tau * kL, 0.01 * tau * kL);
}

namespace {

// A layer 4 m long repeating along x (boundary.left = right =
// "periodic") on a planar base inclined at 10 degrees, cells of 0.25 m.
Scene periodic_incline(double thickness, double density, double youngs,
                       InterfaceKind interface) {
  Scene s = fixtures::block_scene({0.0, 0.0}, {4.0, thickness}, {0.0, 0.0},
                                  {4.0, thickness + 2.0}, 0.25, 2, density, youngs, 0.3);
  s.boundary.left = s.boundary.right = BoundaryKind::Periodic;
  s.boundary.bottom = BoundaryKind::Free;
  s.gravity.vector = {9.81 * std::sin(0.1745), -9.81 * std::cos(0.1745)};
  s.base.kind = BaseKind::Planar;
  s.base.interface = interface;
  return s;
}

}  // namespace

// The seam's exchanges run as device loops over node rows.
TYPED_TEST(DeviceBackend, AgreesWithTheCpuAcrossAPeriodicSeam) {
  Scene s = periodic_incline(1.0, 1000.0, 2e6, InterfaceKind::Frictional);
  s.base.shear_strength = 500.0;
  const Difference d = largest_difference_from_the_cpu<TypeParam>(s, 300);
  std::printf("largest CPU-device difference, periodic, after 300 steps: %.3g\n", d.largest);
  EXPECT_LE(d.largest, 1e-6);
}

// The clay's band along a no-slip base (clay_band) on a periodic layer of
// softening clay steep enough to slide: the band's strength gathered at
// the nodes, their slip, and the softening it spreads back.
TYPED_TEST(DeviceBackend, AgreesWithTheCpuOnTheClayBand) {
  Scene s = periodic_incline(2.0, 600.0, 5e6, InterfaceKind::NoSlip);
  s.base.clay_band = true;
  fixtures::make_softening_clay(s.materials[0], 1500.0, 5.0, 5.0, 0.05);
  const Difference d = largest_difference_from_the_cpu<TypeParam>(s, 300);
  std::printf("largest CPU-device difference, clay band, after 300 steps: %.3g (xi up to %.3g)\n",
              d.largest, d.xi_max);
  EXPECT_GT(d.xi_max, 0.0);  // the band slipped and softened
  EXPECT_LE(d.largest, 1e-6);
}
