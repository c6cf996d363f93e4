#pragma once
#include <Eigen/Core>
#include <string>
#include <vector>

namespace runout {

using Polygon = std::vector<Eigen::Vector2d>;

double signed_area(const Polygon& polygon);  // > 0 when counter-clockwise
bool is_simple(const Polygon& polygon);      // no two non-adjacent edges meet
// Why the outline is not a simple polygon of positive area, naming the
// vertices or edges at fault; "" when it is one.
std::string outline_defect(const Polygon& polygon);
bool contains(const Polygon& polygon, const Eigen::Vector2d& point);  // even-odd rule

}  // namespace runout
