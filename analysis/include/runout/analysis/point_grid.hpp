#pragma once
// A uniform-grid hash of 2D points for fixed-radius neighbour queries: each
// point goes into the square cell of side `cell` that holds it, so the
// points within r of a position are among those of the cells within
// ceil(r / cell) cells of its own. Building is O(n), a query O(1) at bounded
// density, and the order in which a query visits points depends only on the
// input, so the algorithms built on it give the same result run after run.
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "runout/analysis/vec2.hpp"

namespace runout::analysis {

class PointGrid {
 public:
  // Hashes points[i] for every i in `subset`; cell > 0.
  PointGrid(const std::vector<Vec2>& points, const std::vector<int>& subset, double cell)
      : points_(points), cell_(cell), next_(points.size(), -1) {
    head_.reserve(subset.size());
    for (const int i : subset) {
      auto [slot, inserted] = head_.try_emplace(key(cell_of(points[i].x), cell_of(points[i].y)), i);
      if (!inserted) {
        next_[i] = slot->second;
        slot->second = i;
      }
    }
  }

  // Calls visit(j) for every hashed point j with |points[j] - p| <= radius.
  template <class Visit>
  void for_each_within(Vec2 p, double radius, Visit&& visit) const {
    const long reach = static_cast<long>(std::ceil(radius / cell_));
    const long ci = cell_of(p.x), cj = cell_of(p.y);
    const double r2 = radius * radius;
    for (long i = ci - reach; i <= ci + reach; ++i)
      for (long j = cj - reach; j <= cj + reach; ++j) {
        const auto slot = head_.find(key(i, j));
        if (slot == head_.end()) continue;
        for (int k = slot->second; k >= 0; k = next_[k]) {
          const double dx = points_[k].x - p.x, dy = points_[k].y - p.y;
          if (dx * dx + dy * dy <= r2) visit(k);
        }
      }
  }

 private:
  long cell_of(double v) const { return static_cast<long>(std::floor(v / cell_)); }
  // Cell indices fit in 32 bits for any slide measured in metres.
  static std::int64_t key(long i, long j) {
    return static_cast<std::int64_t>(static_cast<std::uint64_t>(i) << 32) ^
           static_cast<std::int64_t>(static_cast<std::uint32_t>(j));
  }

  const std::vector<Vec2>& points_;
  double cell_;
  std::unordered_map<std::int64_t, int> head_;  // cell -> its first point
  std::vector<int> next_;                       // point -> next point of its cell, -1 at the end
};

}  // namespace runout::analysis
