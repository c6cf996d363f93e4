#pragma once
// How the CLI's OpenMP threads wait at a barrier (docs/performance.md,
// "Runs under load").

namespace runout::cli {

// The turns of libgomp's busy-wait loop before a waiting thread sleeps
// (GOMP_SPINCOUNT), unless the user set OMP_WAIT_POLICY or GOMP_SPINCOUNT.
// libgomp's default, 300,000, let a thread
// beside another busy process hold the core the thread it waited for
// needed, and two threads ran several times slower than one. Not spinning
// at all (the passive policy alone) cost 7 to 8 % of an idle two-thread
// run: a step's parallel regions follow each other closer than a sleeping
// thread wakes. 1000 gave that back (case 3 at 0.25 m cells to 1 s, two
// threads: 6.05 to 6.23 s against 6.68 to 6.91 s passive), where 300 gave
// nothing and 2000 no more; beside a busy process 1000 left two threads
// under the thread governor as fast as one (2026-12-05).
inline constexpr const char* kSpinCount = "1000";

// Sets the passive policy with kSpinCount spins, unless the user chose
// either. libgomp reads both once, when it is loaded, before main, so the
// process sets them and executes itself again (argv unchanged); if that
// fails it goes on with libgomp's defaults.
void use_short_openmp_wait(char** argv);

}  // namespace runout::cli
