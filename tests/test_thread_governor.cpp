// ThreadGovernor (thread_governor.hpp) driven by a model machine: the wall
// time of a step on c threads is the machine's, so what it picks and what
// its probes cost can be checked against the best count exactly.
#include <gtest/gtest.h>

#include <functional>
#include <map>

#include "runout/run/thread_governor.hpp"

namespace {

using runout::GovernorWindow;
using runout::ThreadGovernor;

// Steps on the model machine seconds(step, threads); the steps taken on
// each count.
std::map<int, long> run(ThreadGovernor& g, long from, long to,
                        const std::function<double(long, int)>& seconds) {
  std::map<int, long> on;
  for (long k = from; k < to; ++k) {
    const int t = g.threads();
    ++on[t];
    g.took(seconds(k, t));
  }
  return on;
}

constexpr GovernorWindow kWindow{20, 0.0};
constexpr long kProbeBound = 100000 / ThreadGovernor::kMaxHold + 5 * kWindow.steps;

// A 2-vCPU machine: idle, two threads 1.8 times one; beside a busy
// process, two threads slower than one (docs/performance.md, "Threads"
// and "Runs under load").
double idle(int threads) { return threads == 2 ? 1.0 / 1.8 : 1.0; }
double loaded(int threads) { return threads == 2 ? 1.1 : 1.0; }

TEST(ThreadGovernor, StaysOnTwoThreadsOfAnIdleMachineButForRareProbes) {
  ThreadGovernor g(2, kWindow);
  const auto on = run(g, 0, 100000, [](long, int t) { return idle(t); });
  EXPECT_EQ(g.chosen(), 2);
  // A probe window each kMaxHold held ones, and the probes after the first
  // holds (kFirstHold, doubling to kMaxHold: five).
  EXPECT_LT(on.at(1), kProbeBound);
}

TEST(ThreadGovernor, MovesToOneThreadBesideABusyProcess) {
  ThreadGovernor g(2, kWindow);
  const auto on = run(g, 0, 100000, [](long, int t) { return loaded(t); });
  EXPECT_EQ(g.chosen(), 1);
  EXPECT_LT(on.at(2), kProbeBound + kWindow.steps);  // and the first window
}

TEST(ThreadGovernor, FollowsTheLoadAsItComesAndGoes) {
  ThreadGovernor g(2, kWindow);
  const auto machine = [](long k, int t) { return k >= 50000 && k < 100000 ? loaded(t) : idle(t); };
  run(g, 0, 50000, machine);
  EXPECT_EQ(g.chosen(), 2);
  // Load arriving is seen in the first window of the hold that runs slow.
  const auto loaded_on = run(g, 50000, 50200, machine);
  EXPECT_EQ(g.chosen(), 1);
  EXPECT_LT(loaded_on.at(2), 100);
  run(g, 50200, 100000, machine);
  // Load going away is seen at the next probe, kMaxHold windows at most.
  const auto after = run(g, 100000, 100000 + 2 * kWindow.steps * (ThreadGovernor::kMaxHold + 2),
                         machine);
  EXPECT_EQ(g.chosen(), 2);
  EXPECT_GT(after.at(2), after.at(1));
}

TEST(ThreadGovernor, WalksTheHalvingLadderToTheFastestCount) {
  // 16 cores of which the machine's load leaves 4 worth having: the step
  // time is least on 4 threads.
  const auto machine = [](long, int t) {
    const std::map<int, double> time{{16, 1.0}, {8, 0.6}, {4, 0.4}, {2, 0.5}, {1, 0.9}};
    return time.at(t);
  };
  ThreadGovernor g(16, kWindow);
  run(g, 0, 20000, machine);
  EXPECT_EQ(g.chosen(), 4);
}

TEST(ThreadGovernor, OneThreadIsNeverProbed) {
  ThreadGovernor g(1, kWindow);
  const auto on = run(g, 0, 1000, [](long, int) { return 1.0; });
  EXPECT_EQ(on.size(), 1u);
  EXPECT_EQ(on.begin()->first, 1);
}

TEST(ThreadGovernor, AWindowNeedsItsSecondsAsWellAsItsSteps) {
  // Steps of 1 ms with windows of 0.1 s: no probe before 100 steps.
  ThreadGovernor g(2, GovernorWindow{20, 0.1});
  const auto on = run(g, 0, 99, [](long, int) { return 1e-3; });
  EXPECT_EQ(on.count(1), 0u);
}

}  // namespace
