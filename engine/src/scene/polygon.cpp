#include "runout/scene/polygon.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace runout {
namespace {

// > 0 when a, b, c turn counter-clockwise, 0 when collinear.
double turn(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
            const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

int sign(double v) { return (v > 0.0) - (v < 0.0); }

// p is known to be collinear with segment ab.
bool within_box(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                const Eigen::Vector2d& b) {
  return p.x() >= std::min(a.x(), b.x()) && p.x() <= std::max(a.x(), b.x()) &&
         p.y() >= std::min(a.y(), b.y()) && p.y() <= std::max(a.y(), b.y());
}

bool on_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                const Eigen::Vector2d& b) {
  return turn(a, b, p) == 0.0 && within_box(p, a, b);
}

// Closed segments, so touching counts as meeting.
bool segments_meet(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                   const Eigen::Vector2d& c, const Eigen::Vector2d& d) {
  const int abc = sign(turn(a, b, c)), abd = sign(turn(a, b, d));
  const int cda = sign(turn(c, d, a)), cdb = sign(turn(c, d, b));
  if (abc * abd < 0 && cda * cdb < 0) return true;
  return on_segment(c, a, b) || on_segment(d, a, b) || on_segment(a, c, d) ||
         on_segment(b, c, d);
}

// Edges (a, s) and (s, b) share s; they may touch nowhere else, so the
// outline must not fold back along itself (which also rejects a repeated
// vertex, i.e. a zero-length edge).
bool folds_back(const Eigen::Vector2d& a, const Eigen::Vector2d& s,
                const Eigen::Vector2d& b) {
  return on_segment(a, s, b) || on_segment(b, s, a);
}

// The outline's edges binned into a uniform grid of about n cells over its
// bounding box, each edge into every cell its bounding box covers. Two
// edges that meet share the cell of a point where they meet (both boxes
// hold it, and the cell of a coordinate is monotone in it), so only edges
// of one cell need testing against each other: about n tests for an
// outline of short edges, instead of the n^2 / 2 of testing all pairs
// (1e5 vertices took 136 s that way).
class EdgeGrid {
 public:
  explicit EdgeGrid(const Polygon& polygon) : polygon_(polygon) {
    const std::size_t n = polygon.size();
    boxes_.reserve(n);
    for (std::size_t e = 0; e < n; ++e) {
      const Eigen::Vector2d& a = polygon[e];
      const Eigen::Vector2d& b = polygon[(e + 1) % n];
      boxes_.push_back({a.cwiseMin(b), a.cwiseMax(b)});
    }
    lo_ = hi_ = polygon[0];
    for (const auto& p : polygon) {
      lo_ = lo_.cwiseMin(p);
      hi_ = hi_.cwiseMax(p);
    }
    // Long edges cover many cells: a coarser grid keeps the entries (and
    // the memory) within a few per edge.
    for (side_ = std::max<long>(1, std::lround(std::sqrt(double(n))));; side_ /= 2) {
      std::size_t entries = 0;
      for_each_cell_of_edges([&](long, std::size_t) { ++entries; });
      if (side_ == 1 || entries <= kEntriesPerEdge * n) break;
    }
    // Counting sort of (cell, edge) entries: one pass to count, one to fill.
    start_.assign(side_ * side_ + 1, 0);
    for_each_cell_of_edges([&](long cell, std::size_t) { ++start_[cell + 1]; });
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    edges_.resize(start_.back());
    std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
    for_each_cell_of_edges([&](long cell, std::size_t e) {
      edges_[fill[cell]++] = static_cast<std::uint32_t>(e);
    });
    for (std::size_t c = 0; c + 1 < start_.size(); ++c)
      std::sort(edges_.begin() + start_[c], edges_.begin() + start_[c + 1],
                [&](std::uint32_t a, std::uint32_t b) { return box(a).min.x() < box(b).min.x(); });
  }

  // The first pair (i < j, in the order of i then j) of edges that share no
  // vertex and meet; (n, n) when there is none. Within a cell the edges
  // are sorted by their left end, so that only pairs whose boxes overlap
  // are tested: many long parallel edges in one cell (a comb's teeth) cost
  // a sort, not every pair.
  std::pair<std::size_t, std::size_t> first_meeting() const {
    const std::size_t n = polygon_.size();
    std::pair<std::size_t, std::size_t> first{n, n};
    for (std::size_t c = 0; c + 1 < start_.size(); ++c)
      for (std::size_t a = start_[c]; a < start_[c + 1]; ++a)
        for (std::size_t b = a + 1; b < start_[c + 1] && box(edges_[b]).min.x() <= box(edges_[a]).max.x();
             ++b) {
          const std::size_t i = std::min(edges_[a], edges_[b]);
          const std::size_t j = std::max(edges_[a], edges_[b]);
          if (j == i + 1 || (i == 0 && j == n - 1) || std::make_pair(i, j) >= first) continue;
          if (box(i).min.y() > box(j).max.y() || box(j).min.y() > box(i).max.y()) continue;
          if (segments_meet(polygon_[i], polygon_[(i + 1) % n], polygon_[j], polygon_[(j + 1) % n]))
            first = {i, j};
        }
    return first;
  }

 private:
  long cell_of(double v, double lo, double hi) const {
    if (hi <= lo) return 0;
    return std::clamp(static_cast<long>((v - lo) / (hi - lo) * side_), 0L, side_ - 1);
  }
  struct Box {
    Eigen::Vector2d min, max;
  };
  const Box& box(std::size_t edge) const { return boxes_[edge]; }

  template <class Visit>
  void for_each_cell_of_edges(Visit visit) const {
    for (std::size_t e = 0; e < boxes_.size(); ++e) {
      const Box& b = boxes_[e];
      const long x0 = cell_of(b.min.x(), lo_.x(), hi_.x());
      const long x1 = cell_of(b.max.x(), lo_.x(), hi_.x());
      const long y0 = cell_of(b.min.y(), lo_.y(), hi_.y());
      const long y1 = cell_of(b.max.y(), lo_.y(), hi_.y());
      for (long y = y0; y <= y1; ++y)
        for (long x = x0; x <= x1; ++x) visit(y * side_ + x, e);
    }
  }

  static constexpr std::size_t kEntriesPerEdge = 8;
  const Polygon& polygon_;
  Eigen::Vector2d lo_, hi_;
  long side_ = 1;
  std::vector<std::size_t> start_;
  std::vector<Box> boxes_;            // of each edge
  std::vector<std::uint32_t> edges_;  // the scene parser caps vertices far below 2^32
};

}  // namespace

std::pair<std::size_t, std::size_t> first_meeting_edges(const Polygon& polygon) {
  return EdgeGrid(polygon).first_meeting();
}

double signed_area(const Polygon& polygon) {
  double twice = 0.0;
  for (std::size_t i = 0, n = polygon.size(); i < n; ++i) {
    const Eigen::Vector2d& p = polygon[i];
    const Eigen::Vector2d& q = polygon[(i + 1) % n];
    twice += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * twice;
}

std::string outline_defect(const Polygon& polygon) {
  const std::size_t n = polygon.size();
  if (n < 3) return "fewer than 3 vertices";
  auto vertex = [&](std::size_t i) -> const Eigen::Vector2d& {
    return polygon[i % n];
  };
  // Checked first: a collinear outline also folds back, and "zero area"
  // says better what is wrong with it.
  std::size_t other = 1;  // a vertex apart from vertex 0, for the line through both
  while (other < n && vertex(other) == vertex(0)) ++other;
  bool collinear = true;
  for (std::size_t i = 1; i < n && other < n && collinear; ++i)
    collinear = turn(vertex(0), vertex(other), vertex(i)) == 0.0;
  if (collinear) return "zero area: every vertex lies on one line";
  for (std::size_t i = 0; i < n; ++i)
    if (vertex(i + 1) == vertex(i))
      return "vertices " + std::to_string(i) + " and " + std::to_string((i + 1) % n) +
             " coincide (a zero-length edge)";
  for (std::size_t i = 0; i < n; ++i)
    if (folds_back(vertex(i), vertex(i + 1), vertex(i + 2)))
      return "the outline folds back on itself at vertex " + std::to_string((i + 1) % n);
  const auto [i, j] = first_meeting_edges(polygon);
  if (i == n) return "";
  return "self-intersecting polygon: edge " + std::to_string(i) + " (vertices " +
         std::to_string(i) + ", " + std::to_string((i + 1) % n) + ") meets edge " +
         std::to_string(j) + " (vertices " + std::to_string(j) + ", " +
         std::to_string((j + 1) % n) + ")";
}

bool is_simple(const Polygon& polygon) { return outline_defect(polygon).empty(); }

bool contains(const Polygon& polygon, const Eigen::Vector2d& point) {
  bool inside = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[j];
    if ((a.y() > point.y()) == (b.y() > point.y())) continue;
    const double crossing_x =
        a.x() + (point.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
    if (point.x() < crossing_x) inside = !inside;
  }
  return inside;
}

}  // namespace runout
