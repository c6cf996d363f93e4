#pragma once
// OpenMP's wait policy for the CLI's runs (docs/performance.md, "Under
// load").

namespace runout::cli {

// Makes OpenMP threads sleep, not spin, while they wait at a barrier,
// unless the user set OMP_WAIT_POLICY: libgomp's default spins for a while
// (about 300,000 iterations) at every barrier, and on a machine where
// another process is busy a spinning thread holds the core the thread it
// waits for needs, so two threads ran several times slower than one.
// libgomp reads the policy once, when it is loaded, before main, so the
// process sets it and executes itself again (argv unchanged); if that
// fails it goes on with the default policy.
void use_passive_openmp_wait(char** argv);

}  // namespace runout::cli
