#pragma once
// `runout check SCENE --budget SECONDS`: measures this machine's throughput
// on the scene itself at a coarse cell size (MPM and the depth-averaged
// model, a fraction of a second each), estimates the finest cell size whose
// whole run fits the budget for each method and backend, and says which
// method it would pick and why (docs/study.md).
#include "runout/scene.hpp"

namespace runout {

int budget_check(const Scene& scene, double budget_seconds);

}  // namespace runout
