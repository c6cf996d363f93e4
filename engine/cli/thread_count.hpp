#pragma once
// How many OpenMP threads a run uses when the user does not say
// (--threads or OMP_NUM_THREADS).

namespace runout::cli {

// Particles per thread of the default: a step of fewer particles than about
// this on each thread costs more in the parallel regions' wake-ups (the
// passive wait policy, openmp_wait.hpp) than a thread saves. Measured
// with whole runs of the default scene refined to 5 000, 10 267, 20 000
// and 40 624 particles to 1 s, two rounds on the 2-vCPU host (README,
// "Performance"): one thread against two took 0.47 against 0.84 s, 1.53
// against 1.66 s, 3.69 against 4.09 s and 12.4 against 11.5 s.
constexpr double kParticlesPerThread = 25000;

// particles / kParticlesPerThread rounded, at least one, at most cores.
int default_thread_count(double particles, int cores);

// Sets OpenMP's thread count for a run of about `particles` particles (or
// elements) to default_thread_count over the cores OpenMP would use,
// unless OMP_NUM_THREADS is set: then OpenMP's own reading of it stands.
void use_default_threads(double particles);

// The most threads a CPU run may move between (RunOptions::adapt_threads,
// thread_governor.hpp): OpenMP's count, or 0 where OMP_NUM_THREADS fixes
// it.
int adaptable_threads();

}  // namespace runout::cli
