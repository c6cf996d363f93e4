#include "runout/polygon.hpp"

#include <algorithm>
#include <cstddef>
#include <string>

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

}  // namespace

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
  for (std::size_t i = 0; i < n; ++i) {
    if (folds_back(vertex(i), vertex(i + 1), vertex(i + 2)))
      return "the outline folds back on itself at vertex " + std::to_string((i + 1) % n);
    // Edge i against every later edge that shares no vertex with it.
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;
      if (segments_meet(vertex(i), vertex(i + 1), vertex(j), vertex(j + 1)))
        return "self-intersecting polygon: edge " + std::to_string(i) + " (vertices " +
               std::to_string(i) + ", " + std::to_string((i + 1) % n) + ") meets edge " +
               std::to_string(j) + " (vertices " + std::to_string(j) + ", " +
               std::to_string((j + 1) % n) + ")";
    }
  }
  return "";
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
