#pragma once
// Plastic shear strain per particle and on a regular grid, on plain arrays:
// the algorithms behind vtkRunoutPlasticStrain (docs/filters.md, "Plastic
// strain"). xi is the particles' cumulative plastic shear strain.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "runout/analysis/vec2.hpp"

namespace runout::analysis {

// xi of one frame by particle id.
using StrainById = std::unordered_map<std::int64_t, double>;

StrainById strain_by_id(const std::vector<std::int64_t>& ids, const std::vector<double>& xi);

// xi minus xi of the same particle in `previous`; 0 for a particle that
// `previous` does not hold, and for every particle without a previous frame
// (previous == nullptr).
std::vector<double> strain_increment(const std::vector<std::int64_t>& ids,
                                     const std::vector<double>& xi, const StrainById* previous);

// xi / xi95 when xi95 > 0, else xi / (largest xi); all 0 when that is 0.
std::vector<double> normalised_strain(const std::vector<double>& xi, double xi95);

// A regular 2D grid of nx x ny nodes, node (i, j) at origin + spacing (i, j).
struct GridSpec {
  Vec2 origin;
  double spacing = 0;
  int nx = 0, ny = 0;
};

// The grid of the given spacing whose nodes cover the points' bounding box,
// its origin on a multiple of the spacing (so frames of a series share
// nodes). No points: an empty grid.
GridSpec grid_covering(const std::vector<Vec2>& points, double spacing);

struct GridProjection {
  std::vector<std::vector<double>> fields;  // one per input field, node i + nx j
  std::vector<unsigned char> coverage;      // 1 where a particle is within the radius
};

// Kernel-weighted projection of particle fields onto the grid nodes:
// value(node) = sum_p w_p f_p / sum_p w_p with w_p = 1 - (r_p / radius)^2
// for the particles p within `radius` of the node. The weights are
// normalised, so a uniform field projects exactly onto every covered node.
// A node with no particle within the radius gets 0 and coverage 0.
GridProjection project_to_grid(const std::vector<Vec2>& points,
                               const std::vector<const std::vector<double>*>& fields,
                               const GridSpec& grid, double radius);

}  // namespace runout::analysis
