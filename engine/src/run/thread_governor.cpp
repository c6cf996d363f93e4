#include "runout/run/thread_governor.hpp"

#include <algorithm>

namespace runout {

ThreadGovernor::ThreadGovernor(int most, GovernorWindow window) : window_(window) {
  for (int c = std::max(most, 1);; c /= 2) {
    counts_.push_back(c);
    if (c == 1) break;
  }
}

void ThreadGovernor::took(double seconds) {
  if (counts_.size() < 2) return;
  ++steps_;
  seconds_ += seconds;
  if (steps_ < window_.steps || seconds_ < window_.seconds) return;
  const double per_step = seconds_ / steps_;
  steps_ = 0;
  seconds_ = 0;
  end_window(per_step);
}

void ThreadGovernor::start(Phase phase) {
  phase_ = phase;
  if (phase != Phase::Probe) return;
  // The neighbour on the side probe_down_ says, or the other where the
  // ladder ends.
  const int last = static_cast<int>(counts_.size()) - 1;
  if (probe_down_ ? at_ == last : at_ == 0) probe_down_ = !probe_down_;
  probe_ = probe_down_ ? at_ + 1 : at_ - 1;
}

void ThreadGovernor::end_window(double per_step) {
  switch (phase_) {
    case Phase::Measure:
      chosen_ = per_step;
      start(Phase::Probe);
      return;
    case Phase::Probe:
      if (per_step < kBetter * chosen_) {
        at_ = probe_;  // and the next probe goes on the same way
        chosen_ = per_step;
        hold_ = 1;
      } else {
        probe_down_ = !probe_down_;
        hold_ = std::min(2 * hold_, kMaxHold);
      }
      held_ = 0;
      start(Phase::Hold);
      return;
    case Phase::Hold:
      // The hold's last window measures the count for the probe after it.
      if (per_step > kSlower * chosen_) hold_ = 1;  // the machine changed
      if (++held_ < hold_) return;
      chosen_ = per_step;
      start(Phase::Probe);
      return;
  }
}

}  // namespace runout
