#pragma once
// How well the particles fill the layer of cells along the base: a check
// on a run, not a property of the slide. The base resists the slide through
// the stress of the particles in that layer (the internal force on the base
// nodes is the sum of V_p sigma_p grad N over them), so a layer whose
// particles cover a fraction f of it passes about f times its clay's
// strength to the base. Crowded (f > 1) or thinned (f < 1), the runout then
// moves with the particles per cell (docs/strength.md, "What is not
// converged").
#include "runout/mpm/base.hpp"
#include "runout/mpm/particles.hpp"

namespace runout {

// Bins of the base one cell h wide count where the slide stands this many
// cells thick (its particles' volume over the bin's length), and so do
// both bins beside them: the front, the rear and thin tongues, whose basal
// layer is not full, are left out.
constexpr double kBasalFillMinCells = 3.0;

// The particles' volume within one cell h of the base (d < h, d from
// locate_on_base; a particle inside the base counts) over the area h * h of
// each counted bin, summed over those bins: 1 where the particles tile the
// basal layer. NaN where no bin counts. h > 0.
double basal_fill(const Particles& particles, const BaseView& base, double h);

}  // namespace runout
