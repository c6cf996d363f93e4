#include "openmp_wait.hpp"

#include <unistd.h>

#include <cstdlib>

namespace runout::cli {

void use_passive_openmp_wait(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY")) return;  // the user's, or set before this exec
  if (setenv("OMP_WAIT_POLICY", "PASSIVE", 1) != 0) return;
  execv("/proc/self/exe", argv);
}

}  // namespace runout::cli
