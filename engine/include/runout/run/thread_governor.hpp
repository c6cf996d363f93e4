#pragma once
// How many threads a CPU run steps on, chosen by timing its own steps.
// Results are the same on any number of threads (docs/engine.md, "Parallel
// scatter without races"), so a run may change the count between any two
// steps without changing a bit of what it writes. Beside one busy process
// on a 2-vCPU machine, two threads in lockstep waited at every barrier for
// the one that shared its core and ran 8 to 12 % slower than one thread
// (case 3 at 0.25 m cells, passive wait policy, 2026-12-05), where on the
// idle machine they ran 1.2 times as fast: no fixed count is right for
// both, and the load can come and go within a run.
//
// The counts tried are most, most / 2, ..., 1. The governor times a window
// of steps on the current count, then one on a neighbouring count (the
// next lower, or the next higher, in turn), and moves there if it ran
// faster by more than the windows' noise; then it holds the count for a
// number of windows that doubles each time the count stays (up to
// kMaxHold), so that on an idle machine the slower probes cost about
// 1 / kMaxHold of the run. A window on the held count that runs much
// slower than the count did when chosen (load arriving) ends the hold.
#include <vector>

namespace runout {

// A window of ThreadGovernor: at least `steps` steps and `seconds` of
// stepping, so that the step-to-step spread (XPIC steps, reorders)
// averages out.
struct GovernorWindow {
  int steps = 20;
  double seconds = 0.1;
};

class ThreadGovernor {
 public:
  static constexpr int kFirstHold = 4, kMaxHold = 64;  // windows
  // A neighbour must run this much faster to be taken, and a held count's
  // window this much slower than when chosen to end the hold.
  static constexpr double kBetter = 0.97, kSlower = 1.25;

  explicit ThreadGovernor(int most, GovernorWindow window = {});

  int threads() const { return counts_[phase_ == Phase::Probe ? probe_ : at_]; }
  int chosen() const { return counts_[at_]; }  // what threads() is between probes
  // The wall time of the step just taken on threads().
  void took(double seconds);

 private:
  enum class Phase { Measure, Probe, Hold };
  void start(Phase phase);
  void end_window(double per_step);

  std::vector<int> counts_;  // most, most / 2, ..., 1
  GovernorWindow window_;
  int at_ = 0, probe_ = 0;
  bool probe_down_ = true;  // which neighbour the next probe tries
  Phase phase_ = Phase::Measure;
  int steps_ = 0;  // in the window
  double seconds_ = 0;
  double chosen_ = 0;  // seconds a step on counts_[at_] when measured
  int hold_ = kFirstHold, held_ = 0;  // windows to hold, and held so far
};

}  // namespace runout
