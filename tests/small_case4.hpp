#pragma once
// The small case-4 slide of the regularisation and basal-band tests:
// scenes/case4_spreading.toml (its clay, t_s and 1 kPa interface on the
// 2-degree slope) with a trapezoid 24 m long and 5 m high with 30-degree
// faces, nu = 0.3 for a longer time step, and the grid ending at x_max.
// On a held base with FLIP (the solver's defaults) and l three cells, as
// the tests were made: each sets the base and l it is about.
#include <cmath>
#include <string>

#include "runout/scene/scene_parser.hpp"

namespace runout::fixtures {

inline Scene small_case4_scene(double x_max) {
  Scene s = load_scene_file(std::string(RUNOUT_SOURCE_DIR) + "/scenes/case4_spreading.toml");
  s.grid.max.x() = x_max;
  s.solver = SolverSpec{};
  s.base.clay_band = false;
  s.materials[0].nonlocal_length = 0.0;
  s.materials[0].poisson_ratio = 0.3;
  const double top = 5.0 / std::tan(30.0 * M_PI / 180.0);
  s.bodies[0].polygon = {{0.0, 0.0}, {24.0, 0.0}, {24.0 - top, 5.0}, {top, 5.0}};
  return s;
}

}  // namespace runout::fixtures
