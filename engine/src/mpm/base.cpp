#include "runout/mpm/base.hpp"

namespace runout {

// Each segment's length once, for both its tangent and the arc length.
Base::Base(const BaseSpec& spec, double grid_min_y) : kind_(spec.kind), y0_(grid_min_y) {
  double s = 0.0;
  for (std::size_t k = 0; k < spec.points.size(); ++k) {
    if (k > 0) {
      const Eigen::Vector2d e = spec.points[k] - spec.points[k - 1];
      const double len = e.norm();
      seg_.push_back(BaseSegment{e.x() / len, e.y() / len, len});
      s += len;
    }
    px_.push_back(spec.points[k].x());
    py_.push_back(spec.points[k].y());
    ps_.push_back(s);
  }
}

BaseView Base::view() const {
  BaseView v;
  v.kind = kind_;
  v.y0 = y0_;
  v.n = static_cast<int>(px_.size());
  v.px = px_.data();
  v.py = py_.data();
  v.ps = ps_.data();
  v.seg = seg_.data();
  return v;
}

}  // namespace runout
