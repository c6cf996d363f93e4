#include "runout/analysis/frame_base.hpp"

namespace runout::analysis {

std::optional<Base> base_from_points(const std::vector<double>& values, int components) {
  if (components < 2 || values.size() < 2 * static_cast<std::size_t>(components))
    return std::nullopt;
  BaseSpec spec;
  spec.kind = BaseKind::Polyline;
  for (std::size_t k = 0; k + components <= values.size(); k += components) {
    const Eigen::Vector2d p(values[k], values[k + 1]);
    if (!p.allFinite()) return std::nullopt;
    if (!spec.points.empty() && !(p.x() > spec.points.back().x())) return std::nullopt;
    spec.points.push_back(p);
  }
  if (spec.points.size() == 2 && spec.points[0].y() == spec.points[1].y())
    spec.kind = BaseKind::Planar;
  return Base(spec, spec.points[0].y());
}

Base x_axis_base() {
  BaseSpec x_axis;
  x_axis.kind = BaseKind::Planar;
  return Base(x_axis, 0.0);
}

}  // namespace runout::analysis
