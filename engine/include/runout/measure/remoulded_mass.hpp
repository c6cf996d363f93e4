#pragma once
// How much of a sensitive clay the slide has remoulded: whether it moves as
// blocks or flows out as debris. The remoulded zone round each of its bands
// is as wide as the band the grid makes (a particle softens only where it
// yields), so this mass, unlike a band's displacement, still moves with the
// cell (docs/validation.md, "Sensitive clay, regularised").
#include <vector>

#include "runout/mpm/material.hpp"
#include "runout/mpm/particles.hpp"

namespace runout {

// The mass [kg/m] of the particles whose own plastic shear has taken 95 %
// of the strength remoulding can take (xi >= xi95, where S(xi) - 1/St =
// e^-3 (1 - 1/St)) in a Tresca material with St > 1. The basal band's
// remoulding (band_xi) is the band's, t_s thick under the particles that
// carry it, and does not count. `materials` by the particles' material
// index.
double remoulded_mass(const Particles& particles, const std::vector<MaterialParams>& materials);

}  // namespace runout
