#pragma once
// A point or vector of a run's 2D frame (x, y), for the analysis
// algorithms.

namespace runout::analysis {

struct Vec2 {
  double x = 0, y = 0;
};

}  // namespace runout::analysis
