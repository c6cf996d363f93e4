#include "runout/measure/diagnostics.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace runout {

ParticleTotals particle_totals(const Particles& P) {
  const int n = P.size();
  constexpr int kChunk = 4096;
  const int chunks = (n + kChunk - 1) / kChunk;
  std::vector<ParticleTotals> part(chunks);
#pragma omp parallel for if (chunks > 1)
  for (int k = 0; k < chunks; ++k) {
    ParticleTotals t;
    for (int p = k * kChunk; p < std::min(n, (k + 1) * kChunk); ++p) {
      const double m = P.mass[p], vx = P.vx[p], vy = P.vy[p];
      const double v2 = vx * vx + vy * vy;
      t.mass += m;
      t.momentum_x += m * vx;
      t.momentum_y += m * vy;
      t.kinetic_energy += 0.5 * m * v2;
      t.max_speed = std::max(t.max_speed, std::sqrt(v2));
    }
    part[k] = t;
  }
  ParticleTotals total;
  for (const auto& t : part) {
    total.mass += t.mass;
    total.momentum_x += t.momentum_x;
    total.momentum_y += t.momentum_y;
    total.kinetic_energy += t.kinetic_energy;
    total.max_speed = std::max(total.max_speed, t.max_speed);
  }
  return total;
}

}  // namespace runout
