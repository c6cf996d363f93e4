#pragma once
// A request to stop a run, set from a signal handler (the CLI's SIGINT,
// SIGTERM and SIGHUP) and honoured by the run schedule at the next step
// boundary, where the state is whole and can be checkpointed. Lock-free
// atomics are the only shared state a handler may touch.
#include <atomic>

namespace runout {

namespace run_control_detail {
inline std::atomic<int> requested{0};  // the signal asked to stop by, 0: none
inline std::atomic<int> honoured{0};   // the signal a run stopped for
static_assert(std::atomic<int>::is_always_lock_free, "touched from a signal handler");
}  // namespace run_control_detail

// Async-signal-safe.
inline void request_stop(int signal) noexcept {
  run_control_detail::requested.store(signal, std::memory_order_relaxed);
}
inline int stop_requested() noexcept {
  return run_control_detail::requested.load(std::memory_order_relaxed);
}
// The run schedule says that it stopped early for the request (a request
// that came after the last step stops nothing).
inline void mark_stopped(int signal) noexcept {
  run_control_detail::honoured.store(signal, std::memory_order_relaxed);
}
inline int stopped_by() noexcept {
  return run_control_detail::honoured.load(std::memory_order_relaxed);
}

}  // namespace runout
