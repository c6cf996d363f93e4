#pragma once
// How many OpenMP threads a run uses when the user does not say
// (--threads or OMP_NUM_THREADS).

namespace runout::cli {

// Particles per thread of the default: a step of fewer particles than about
// this on each thread costs more in the parallel regions' wake-ups (the
// then passive wait policy, openmp_wait.hpp) than a thread saves; two
// threads win from about 15 000 particles, where rounding gives two
// (docs/performance.md, "Threads"). A run then times its steps and moves
// to fewer threads where they are faster (thread_governor.hpp).
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
