#pragma once
// `runout check SCENE --budget SECONDS`: measures this machine's throughput
// on the scene itself at a coarse cell size (MPM and the depth-averaged
// model, a fraction of a second each), estimates the finest cell size whose
// whole run fits the budget for each method and backend, and says which
// method it would pick and why (docs/study.md).
#include <chrono>

#include "runout/scene/scene.hpp"

namespace runout {

// Wall seconds per step of `model` on this machine: one step that warms the
// caches and sizes the grid, then steps at the CFL dt for `seconds` of wall
// time (at least one). Throws what a step throws.
template <class Model>
double seconds_per_step(Model& model, double seconds) {
  using Clock = std::chrono::steady_clock;
  model.step(model.stable_dt());
  const auto start = Clock::now();
  long steps = 0;
  double wall = 0;
  while (steps == 0 || wall < seconds) {
    model.step(model.stable_dt());
    ++steps;
    wall = std::chrono::duration<double>(Clock::now() - start).count();
  }
  return wall / steps;
}

int budget_check(const Scene& scene, double budget_seconds);

}  // namespace runout
