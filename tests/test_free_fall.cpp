// A body in free fall with an initial velocity lands where kinematics puts
// it, x0 + v0 t + g t^2 / 2, to 1e-10 relative, with GIMP and with linear
// shape functions; the half-step error of x += dt v_new would be
// g t dt / 2, about 1e-3 here.
#include <gtest/gtest.h>

#include <cmath>

#include "runout/simulation.hpp"
#include "scene_builders.hpp"

using namespace runout;

namespace {

void check_free_fall(ShapeKind shape, double flip) {
  Scene s = fixtures::block_scene({10.0, 30.0}, {12.0, 32.0}, {0.0, 0.0}, {40.0, 40.0}, 0.5, 2,
                                 1000.0, 1e5, 0.3);
  s.grid.shape = shape;
  s.solver.flip = flip;
  s.gravity.vector = {1.2, -9.81};
  const Eigen::Vector2d v0(1.5, 2.0), g = s.gravity.vector;
  s.bodies[0].velocity = v0;
  Simulation sim(s);
  const double t = 1.7;
  sim.advance_to(t);
  ASSERT_GT(sim.steps(), 20);
  EXPECT_EQ(sim.time(), t);
  const Particles& P = sim.particles();
  double max_stress = 0;
  for (int p = 0; p < P.size(); ++p) {
    const Eigen::Vector2d x0(P.x0[p], P.y0[p]);
    const Eigen::Vector2d exact = x0 + v0 * t + 0.5 * g * t * t;
    EXPECT_LE(std::fabs(P.x[p] - exact.x()), 1e-10 * std::fabs(exact.x())) << "particle " << p;
    EXPECT_LE(std::fabs(P.y[p] - exact.y()), 1e-10 * std::fabs(exact.y())) << "particle " << p;
    EXPECT_NEAR(P.vx[p], v0.x() + g.x() * t, 1e-10 * std::fabs(v0.x() + g.x() * t));
    EXPECT_NEAR(P.vy[p], v0.y() + g.y() * t, 1e-10 * std::fabs(v0.y() + g.y() * t));
    max_stress = std::max({max_stress, std::fabs(P.sxx[p]), std::fabs(P.syy[p]),
                           std::fabs(P.sxy[p])});
  }
  // Uniform motion strains nothing: only round-off stress.
  EXPECT_LT(max_stress, 1e-12 * 1e5);
}

}  // namespace

TEST(FreeFall, GimpFlipLandsOnTheParabola) { check_free_fall(ShapeKind::Gimp, 0.99); }
TEST(FreeFall, GimpPicLandsOnTheParabola) { check_free_fall(ShapeKind::Gimp, 0.0); }
TEST(FreeFall, LinearLandsOnTheParabola) { check_free_fall(ShapeKind::Linear, 1.0); }
