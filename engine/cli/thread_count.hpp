#pragma once
// How many OpenMP threads a run uses when the user does not say
// (--threads or OMP_NUM_THREADS).

namespace runout::cli {

// Particles per thread of the default: a step of fewer particles than about
// this on each thread costs more in the parallel regions' wake-ups (the
// then passive wait policy, openmp_wait.hpp) than a thread saves. Measured
// with whole runs of the default scene refined to 9 914, 20 000 and
// 40 135 particles to 1 s, two rounds on the 2-vCPU host, 2026-12-05 with
// 52d5c9a (README, "Performance"): one thread against two took 1.42 and
// 1.43 s against 1.56 and 1.60 s, 4.04 and 4.02 s against 3.77 and
// 3.84 s, 11.4 and 11.3 s against 8.1 and 8.2 s; two threads win from
// about 15 000, where rounding gives two. (It was 25 000 when each step
// woke the threads more often: 10 267 particles took 1.53 s against 1.66,
// 20 000 3.69 s against 4.09.) A run then times its steps and moves to
// fewer threads where they are faster (thread_governor.hpp).
constexpr double kParticlesPerThread = 10000;

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
