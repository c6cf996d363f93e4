// A body in free fall with an initial velocity lands where kinematics puts
// it, x0 + v0 t + g t^2 / 2, to 1e-10 relative, with GIMP and with linear
// shape functions; the half-step error of x += dt v_new would be
// g t dt / 2, about 1e-3 here.
#include <gtest/gtest.h>

#include <cmath>

#include "runout/mpm/simulation.hpp"
#include "free_fall.hpp"

using namespace runout;

namespace {

void check_free_fall(ShapeKind shape, TransferKind transfer, double flip = 1.0) {
  Scene s = fixtures::free_fall_scene(shape);
  s.solver.transfer = transfer;
  s.solver.flip = flip;
  Simulation sim(s);
  const double t = fixtures::kFreeFallTime;
  sim.advance_to(t);
  ASSERT_GT(sim.steps(), 20);
  EXPECT_EQ(sim.time(), t);
  const Particles& P = sim.particles();
  fixtures::expect_on_the_parabola(P, s, t);
  double max_stress = 0;
  for (int p = 0; p < P.size(); ++p)
    max_stress = std::max({max_stress, std::fabs(P.sxx[p]), std::fabs(P.syy[p]),
                           std::fabs(P.sxy[p])});
  // Uniform motion strains nothing: only round-off stress.
  EXPECT_LT(max_stress, 1e-12 * 1e5);
}

}  // namespace

TEST(FreeFall, GimpFlipLandsOnTheParabola) { check_free_fall(ShapeKind::Gimp, TransferKind::Flip); }
TEST(FreeFall, GimpBlendLandsOnTheParabola) {
  check_free_fall(ShapeKind::Gimp, TransferKind::PicFlip, 0.99);
}
TEST(FreeFall, GimpPicLandsOnTheParabola) {
  check_free_fall(ShapeKind::Gimp, TransferKind::PicFlip, 0.0);
}
TEST(FreeFall, GimpApicLandsOnTheParabola) { check_free_fall(ShapeKind::Gimp, TransferKind::Apic); }
TEST(FreeFall, LinearLandsOnTheParabola) { check_free_fall(ShapeKind::Linear, TransferKind::Flip); }
TEST(FreeFall, LinearApicLandsOnTheParabola) {
  check_free_fall(ShapeKind::Linear, TransferKind::Apic);
}
