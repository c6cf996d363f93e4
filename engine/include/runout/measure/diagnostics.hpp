#pragma once
#include "runout/mpm/particles.hpp"

namespace runout {

// Sums over the particles, taken in fixed chunks so that they come out the
// same run after run whatever the number of threads.
struct ParticleTotals {
  double mass = 0;
  double momentum_x = 0, momentum_y = 0;
  double kinetic_energy = 0;
  double max_speed = 0;
};

ParticleTotals particle_totals(const Particles& particles);

}  // namespace runout
