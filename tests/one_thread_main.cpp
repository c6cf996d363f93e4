// The tests' main. ctest runs the test processes side by side, one per
// core (scripts/test: ctest -j$(nproc)), so each takes one OpenMP thread
// unless OMP_NUM_THREADS says otherwise; a test about threads sets its
// own. Two processes of two threads on two cores wait for each other at
// every barrier: in CI the two longest tests ran over three times slower
// than alone and timed out.
#include <gtest/gtest.h>

#include <cstdlib>
#ifdef _OPENMP
#include <omp.h>
#endif

int main(int argc, char** argv) {
#ifdef _OPENMP
  if (!std::getenv("OMP_NUM_THREADS")) omp_set_num_threads(1);
#endif
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
