#include "runout/analysis/plastic_strain.hpp"

#include <algorithm>
#include <cmath>

namespace runout::analysis {

StrainById strain_by_id(const std::vector<std::int64_t>& ids, const std::vector<double>& xi) {
  StrainById by_id;
  by_id.reserve(ids.size());
  for (size_t i = 0; i < ids.size(); ++i) by_id[ids[i]] = xi[i];
  return by_id;
}

std::vector<double> strain_increment(const std::vector<std::int64_t>& ids,
                                     const std::vector<double>& xi, const StrainById* previous) {
  std::vector<double> increment(xi.size(), 0.0);
  if (!previous) return increment;
  for (size_t i = 0; i < xi.size(); ++i) {
    const auto before = previous->find(ids[i]);
    if (before != previous->end()) increment[i] = xi[i] - before->second;
  }
  return increment;
}

std::vector<double> normalised_strain(const std::vector<double>& xi, double xi95) {
  const double scale =
      xi95 > 0 ? xi95 : (xi.empty() ? 0.0 : *std::max_element(xi.begin(), xi.end()));
  std::vector<double> normalised(xi.size(), 0.0);
  if (scale > 0)
    std::transform(xi.begin(), xi.end(), normalised.begin(), [scale](double v) { return v / scale; });
  return normalised;
}

GridSpec grid_covering(const std::vector<Vec2>& points, double spacing) {
  if (points.empty()) return {{0, 0}, spacing, 0, 0};
  Vec2 lo = points[0], hi = points[0];
  for (const Vec2& p : points) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  const Vec2 origin{std::floor(lo.x / spacing) * spacing, std::floor(lo.y / spacing) * spacing};
  return {origin, spacing, static_cast<int>(std::ceil((hi.x - origin.x) / spacing)) + 1,
          static_cast<int>(std::ceil((hi.y - origin.y) / spacing)) + 1};
}

GridProjection project_to_grid(const std::vector<Vec2>& points,
                               const std::vector<const std::vector<double>*>& fields,
                               const GridSpec& grid, double radius) {
  const size_t nodes = static_cast<size_t>(grid.nx) * grid.ny;
  std::vector<double> weight(nodes, 0.0);
  GridProjection out{std::vector<std::vector<double>>(fields.size(), std::vector<double>(nodes, 0.0)),
                     std::vector<unsigned char>(nodes, 0)};
  // Scatter: each particle adds to the nodes within the radius, O(n) for a
  // radius of a few grid spacings.
  const int reach = static_cast<int>(std::ceil(radius / grid.spacing));
  for (size_t p = 0; p < points.size(); ++p) {
    const int ci = static_cast<int>(std::lround((points[p].x - grid.origin.x) / grid.spacing));
    const int cj = static_cast<int>(std::lround((points[p].y - grid.origin.y) / grid.spacing));
    for (int j = std::max(0, cj - reach); j <= std::min(grid.ny - 1, cj + reach); ++j)
      for (int i = std::max(0, ci - reach); i <= std::min(grid.nx - 1, ci + reach); ++i) {
        const double dx = grid.origin.x + i * grid.spacing - points[p].x;
        const double dy = grid.origin.y + j * grid.spacing - points[p].y;
        const double q2 = (dx * dx + dy * dy) / (radius * radius);
        if (q2 >= 1) continue;
        const size_t node = i + static_cast<size_t>(grid.nx) * j;
        weight[node] += 1 - q2;
        for (size_t f = 0; f < fields.size(); ++f) out.fields[f][node] += (1 - q2) * (*fields[f])[p];
      }
  }
  for (size_t node = 0; node < nodes; ++node) {
    if (weight[node] <= 0) continue;
    out.coverage[node] = 1;
    for (auto& field : out.fields) field[node] /= weight[node];
  }
  return out;
}

}  // namespace runout::analysis
