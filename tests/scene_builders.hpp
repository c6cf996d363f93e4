#pragma once
// Scenes built in code for the physics tests, so that they do not depend on
// the scene parser.
#include "runout/scene.hpp"

namespace runout::fixtures {

inline Scene block_scene(Eigen::Vector2d body_min, Eigen::Vector2d body_max,
                         Eigen::Vector2d domain_min, Eigen::Vector2d domain_max, double h,
                         int ppc, double density, double youngs, double poisson) {
  Scene s;
  s.name = "test";
  s.grid.cell_size = h;
  s.grid.min = domain_min;
  s.grid.max = domain_max;
  s.grid.ppc = ppc;
  s.boundary = {BoundaryKind::Free, BoundaryKind::Free, BoundaryKind::Free, BoundaryKind::Free};
  s.gravity.vector = {0.0, 0.0};
  MaterialSpec m;
  m.name = "m";
  m.density = density;
  m.youngs_modulus = youngs;
  m.poisson_ratio = poisson;
  s.materials.push_back(m);
  BodySpec b;
  b.name = "block";
  b.polygon = {{body_min.x(), body_min.y()}, {body_max.x(), body_min.y()},
               {body_max.x(), body_max.y()}, {body_min.x(), body_max.y()}};
  s.bodies.push_back(b);
  return s;
}

}  // namespace runout::fixtures
