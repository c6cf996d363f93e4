#pragma once
// From a scene's material (host) to the plain parameter records the solvers
// use, in one place for the MPM and the depth-averaged method.
#include "runout/material.hpp"
#include "runout/scene.hpp"

namespace runout {

// The strength law of a Tresca material (d_rem = 1 / St) with xi95 as the
// scene gives it; for an elastic one a law without softening or rate effect.
StrengthParams strength_params(const MaterialSpec& m);

// The xi95 of an MPM run at cell size h: with xi95_reference_cell set,
// scaled so that the plastic displacement across a shear band at 95 %
// remoulding is the same at every cell size (docs/strength.md,
// "Mesh-adjusted softening"); otherwise xi95 itself.
double mesh_adjusted_xi95(const MaterialSpec& m, double cell_size);

// The MPM's parameters of a material on a grid of cell size h.
MaterialParams material_params(const MaterialSpec& m, double cell_size);

}  // namespace runout
