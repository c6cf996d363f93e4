#include "thread_count.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace runout::cli {

int default_thread_count(double particles, int cores) {
  const double wanted = std::round(particles / kParticlesPerThread);
  return static_cast<int>(std::clamp(wanted, 1.0, static_cast<double>(std::max(cores, 1))));
}

void use_default_threads(double particles) {
  if (std::getenv("OMP_NUM_THREADS")) return;
  omp_set_num_threads(default_thread_count(particles, omp_get_max_threads()));
}

int adaptable_threads() { return std::getenv("OMP_NUM_THREADS") ? 0 : omp_get_max_threads(); }

}  // namespace runout::cli
