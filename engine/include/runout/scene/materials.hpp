#pragma once
// From a scene's material (host) to the plain parameter records the solvers
// use, in one place for the MPM and the depth-averaged method.
#include <vector>

#include "runout/mpm/material.hpp"
#include "runout/scene/scene.hpp"

namespace runout {

// The strength law of a Tresca material (d_rem = 1 / St); for an elastic one
// a law without softening or rate effect.
StrengthParams strength_params(const MaterialSpec& m);
MaterialParams material_params(const MaterialSpec& m);
// Every material of the scene, in its order.
std::vector<MaterialParams> make_materials(const Scene& scene);

}  // namespace runout
