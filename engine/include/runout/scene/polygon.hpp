#pragma once
#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace runout {

using Polygon = std::vector<Eigen::Vector2d>;

double signed_area(const Polygon& polygon);  // > 0 when counter-clockwise
bool is_simple(const Polygon& polygon);      // no two non-adjacent edges meet
// Why the outline is not a simple polygon of positive area, naming the
// vertices or edges at fault; "" when it is one.
std::string outline_defect(const Polygon& polygon);
// The first pair of edges i < j (edge i runs from vertex i to i + 1) that
// share no vertex and still meet, touching included, in the order of i then
// j; (n, n) when there is none. Near-linear for outlines of short edges.
std::pair<std::size_t, std::size_t> first_meeting_edges(const Polygon& polygon);
bool contains(const Polygon& polygon, const Eigen::Vector2d& point);  // even-odd rule

}  // namespace runout
