#pragma once
// The base a particle frame carries, read as the engine wrote it: the field
// data base_points (docs/output.md), whoever read the frame.
#include <optional>
#include <vector>

#include "runout/mpm/base.hpp"

namespace runout::analysis {

// The base from the tuples of base_points (`components` per tuple, x and y
// first): two points at one height are its planar base (s = x, as the engine
// measures it), more points its polyline. nullopt with fewer than two
// points or two components, with x not strictly increasing (a repeated
// point would make a segment without a direction), with a segment too short
// for its length to be computed, or with a coordinate that is not finite.
std::optional<Base> base_from_points(const std::vector<double>& values, int components);

// The x axis (s = x, d = y): the base the band and block searches measure
// against in a frame without base_points.
Base x_axis_base();

}  // namespace runout::analysis
