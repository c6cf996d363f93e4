#pragma once
// The OpenMP thread counts the CPU backend asks for (backend_openmp.hpp),
// one thread where the build has no OpenMP.
#ifdef _OPENMP
#include <omp.h>
#endif

namespace runout::openmp {

inline int max_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}
inline int this_thread() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}
inline int team_threads() {  // in the parallel region that calls it
#ifdef _OPENMP
  return omp_get_num_threads();
#else
  return 1;
#endif
}

}  // namespace runout::openmp
