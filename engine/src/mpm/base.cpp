#include "runout/mpm/base.hpp"

namespace runout {

Base::Base(const BaseSpec& spec, double grid_min_y) : kind_(spec.kind), y0_(grid_min_y) {
  double s = 0.0;
  for (std::size_t k = 0; k < spec.points.size(); ++k) {
    if (k > 0) s += (spec.points[k] - spec.points[k - 1]).norm();
    px_.push_back(spec.points[k].x());
    py_.push_back(spec.points[k].y());
    ps_.push_back(s);
  }
  for (std::size_t k = 0; k + 1 < px_.size(); ++k)
    seg_.push_back(base_segment(px_[k], py_[k], px_[k + 1], py_[k + 1]));
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
