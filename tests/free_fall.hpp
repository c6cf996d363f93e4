#pragma once
// The free-fall problem, shared by the CPU test and the GPU one: a block
// thrown at v0 under a gravity with both components lands at
// x0 + v0 t + g t^2 / 2 with velocity v0 + g t, to 1e-10 relative.
#include <gtest/gtest.h>

#include <cmath>

#include "runout/mpm/particles.hpp"
#include "scene_builders.hpp"

namespace runout::fixtures {

inline constexpr double kFreeFallTime = 1.7;

inline Scene free_fall_scene(ShapeKind shape) {
  Scene s = block_scene({10.0, 30.0}, {12.0, 32.0}, {0.0, 0.0}, {40.0, 40.0}, 0.5, 2, 1000.0,
                        1e5, 0.3);
  s.grid.shape = shape;
  s.gravity.vector = {1.2, -9.81};
  s.bodies[0].velocity = {1.5, 2.0};
  return s;
}

inline void expect_on_the_parabola(const Particles& P, const Scene& s, double t) {
  const Eigen::Vector2d v0 = s.bodies[0].velocity, g = s.gravity.vector;
  const Eigen::Vector2d v = v0 + g * t;
  for (int p = 0; p < P.size(); ++p) {
    const Eigen::Vector2d exact = Eigen::Vector2d(P.x0[p], P.y0[p]) + v0 * t + 0.5 * g * t * t;
    EXPECT_LE(std::fabs(P.x[p] - exact.x()), 1e-10 * std::fabs(exact.x())) << "particle " << p;
    EXPECT_LE(std::fabs(P.y[p] - exact.y()), 1e-10 * std::fabs(exact.y())) << "particle " << p;
    EXPECT_NEAR(P.vx[p], v.x(), 1e-10 * std::fabs(v.x()));
    EXPECT_NEAR(P.vy[p], v.y(), 1e-10 * std::fabs(v.y()));
  }
}

}  // namespace runout::fixtures
