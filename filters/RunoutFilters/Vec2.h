#pragma once
// A point or vector of a run's 2D frame (x, y), for the filters' plain
// algorithms.

namespace runout::filters {

struct Vec2 {
  double x = 0, y = 0;
};

}  // namespace runout::filters
