#pragma once
// The rigid base: where a point is relative to it. A planar base is the
// grid's bottom line (planar slopes run in the slope frame); a polyline is
// a bathymetry in the run's frame, points ordered by increasing x, the slide
// on its upper (left) side. The first and last segments extend to infinity
// so that the base has no ends.
#include <cmath>
#include <vector>

#include "runout/mpm/host_device.hpp"
#include "runout/scene/kinds.hpp"
#include "runout/scene/scene.hpp"

namespace runout {

// A polyline segment's unit tangent and length, computed once: a point is
// located against every segment for every particle, several times a step.
struct BaseSegment {
  double tx, ty, len;
};

struct BaseView {
  BaseKind kind = BaseKind::None;
  double y0 = 0;                 // Planar: the base line y = y0
  int n = 0;                     // Polyline: number of points
  const double *px = nullptr, *py = nullptr;
  const double* ps = nullptr;    // arc length at each point, ps[0] = 0
  const BaseSegment* seg = nullptr;  // n - 1 segments, seg[k] from point k to k + 1
};

struct BasePoint {
  double s;       // along-base coordinate: arc length of the closest base point
  double d;       // signed distance, > 0 above the base, < 0 inside it
  double nx, ny;  // outward unit normal of the base there
};

RUNOUT_HD inline BasePoint locate_on_base(const BaseView& b, double x, double y) {
  if (b.kind != BaseKind::Polyline) return BasePoint{x, y - b.y0, 0.0, 1.0};
  // The nearest segment by the squared distance; the root once, for it
  // (the nonlocal average locates most particles of a slide every step).
  int best = 0;
  double best_t = 0.0, best_dist2 = -1.0;
  for (int k = 0; k + 1 < b.n; ++k) {
    const double tx = b.seg[k].tx, ty = b.seg[k].ty, len = b.seg[k].len;
    double t = (x - b.px[k]) * tx + (y - b.py[k]) * ty;  // along the segment
    if (k > 0 && t < 0.0) t = 0.0;
    if (k + 2 < b.n && t > len) t = len;
    const double cx = b.px[k] + t * tx, cy = b.py[k] + t * ty;
    const double dist2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
    if (best_dist2 < 0.0 || dist2 < best_dist2) {
      best_dist2 = dist2;
      best = k;
      best_t = t;
    }
  }
  if (best_dist2 < 0.0) return BasePoint{0.0, 0.0, 0.0, 1.0};  // no segment
  const double tx = b.seg[best].tx, ty = b.seg[best].ty;
  const double cx = b.px[best] + best_t * tx, cy = b.py[best] + best_t * ty;
  const double nx = -ty, ny = tx;  // left normal: up for increasing x
  const double side = (x - cx) * nx + (y - cy) * ny;
  const double d = std::sqrt(best_dist2);
  return BasePoint{b.ps[best] + best_t, side < 0.0 ? -d : d, nx, ny};
}

// Owns the polyline arrays behind a BaseView.
class Base {
 public:
  explicit Base(const BaseSpec& spec, double grid_min_y);
  BaseView view() const;
  BaseKind kind() const { return kind_; }

 private:
  BaseKind kind_;
  double y0_;
  std::vector<double> px_, py_, ps_;
  std::vector<BaseSegment> seg_;
};

}  // namespace runout
