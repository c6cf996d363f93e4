#pragma once
// Quantities a scene implies that several parts of the engine use (the
// seeding, the step configuration, the estimates): one place each, so they
// agree.
#include <cmath>
#include <cstddef>
#include <vector>

#include "runout/mpm/material.hpp"
#include "runout/scene/scene.hpp"

namespace runout {

// Spacing of the particle lattice, h / ppc: a particle starts with volume
// spacing^2.
inline double particle_spacing(const Scene& s) { return s.grid.cell_size / s.grid.ppc; }

// P-wave speed sqrt(M / rho) of a material at its initial density.
inline double p_wave_speed(const MaterialParams& m) {
  return std::sqrt(p_wave_modulus(m) / m.density);
}

// The fastest P-wave of the materials and the first material that has it;
// speed 0 and material -1 when none is above 0.
struct FastestWave {
  double speed = 0;
  int material = -1;
};
inline FastestWave fastest_p_wave(const std::vector<MaterialParams>& materials) {
  FastestWave w;
  for (std::size_t k = 0; k < materials.size(); ++k) {
    const double speed = p_wave_speed(materials[k]);
    if (speed > w.speed) {
      w.speed = speed;
      w.material = static_cast<int>(k);
    }
  }
  return w;
}

}  // namespace runout
