#include "openmp_wait.hpp"

#include <unistd.h>

#include <cstdlib>

namespace runout::cli {

void use_short_openmp_wait(char** argv) {
  // The user's, or set before this exec.
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  if (setenv("OMP_WAIT_POLICY", "PASSIVE", 1) != 0 || setenv("GOMP_SPINCOUNT", kSpinCount, 1) != 0)
    return;
  execv("/proc/self/exe", argv);
}

}  // namespace runout::cli
