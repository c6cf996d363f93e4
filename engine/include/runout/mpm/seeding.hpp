#pragma once
#include <optional>

#include "runout/run/memory_estimate.hpp"
#include "runout/mpm/particles.hpp"
#include "runout/scene/scene.hpp"

namespace runout {

// Fills every body's polygon with ppc x ppc particles per grid cell, on the
// lattice of sub-cell centres of the scene's grid (so a fully covered cell
// holds exactly ppc^2 particles), a sub-cell centre inside the polygon
// becoming a particle of volume v = (h/ppc)^2 and mass density * v, scaled
// per body by A / (n v) so that its n particles carry the mass of its
// area A (seeding.cpp: mass_scale).
// Stress starts at zero; x0/y0 = position; ids run 0..n-1 in body order.
// Throws SceneError, before allocating, for a scene whose particles would
// not fit in memory or overflow int (require_memory), and for a body that
// holds no particle. `checked`: the scene's MPM memory estimate where
// require_memory has passed it already (a run's one estimate), so that it
// is not made and checked again.
Particles seed_particles(const Scene& scene,
                         const std::optional<MemoryEstimate>& checked = std::nullopt);

}  // namespace runout
