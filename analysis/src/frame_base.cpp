#include "runout/analysis/frame_base.hpp"

#include <cmath>

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
  Base base(spec, spec.points[0].y());
  // A segment's direction is its difference over its length: a length
  // whose square underflows to 0 (subnormal coordinates) or overflows
  // gives none.
  const BaseView view = base.view();
  for (int k = 0; k + 1 < view.n; ++k)
    if (!(view.seg[k].len > 0 && std::isfinite(view.seg[k].len))) return std::nullopt;
  return base;
}

Base x_axis_base() {
  BaseSpec x_axis;
  x_axis.kind = BaseKind::Planar;
  return Base(x_axis, 0.0);
}

}  // namespace runout::analysis
