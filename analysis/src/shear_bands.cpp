#include "runout/analysis/shear_bands.hpp"

#include <algorithm>
#include <cmath>

#include "runout/analysis/point_grid.hpp"

namespace runout::analysis {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180;
// A neighbourhood whose minor principal variance exceeds this fraction of
// its major one has no clear direction (where bands meet or cross, the apex
// of a V): its particle takes no side in the orientation test.
constexpr double kOrientedVarianceRatio = 0.5;

// Second moments of points given as offsets from a fixed centre (offsets
// keep the sums accurate far from the origin).
struct Moments {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;

  void add(double dx, double dy) {
    n += 1;
    sx += dx;
    sy += dy;
    sxx += dx * dx;
    sxy += dx * dy;
    syy += dy * dy;
  }
  // The major principal axis: its angle to x in (-pi/2, pi/2] (NaN when the
  // covariance is isotropic) and the ratio of the minor principal variance
  // to the major one (1 when isotropic).
  struct Axis {
    double angle;
    double variance_ratio;
  };
  Axis principal_axis() const {
    const double cxx = sxx / n - (sx / n) * (sx / n);
    const double cyy = syy / n - (sy / n) * (sy / n);
    const double cxy = sxy / n - (sx / n) * (sy / n);
    const double mean = 0.5 * (cxx + cyy), radius = std::hypot(0.5 * (cxx - cyy), cxy);
    if (radius == 0) return {std::nan(""), 1.0};
    return {0.5 * std::atan2(2 * cxy, cxx - cyy), (mean - radius) / (mean + radius)};
  }
};

// Difference of two axis angles (radians; an axis and its opposite are one).
double axis_difference(double a, double b) {
  const double d = std::fmod(std::abs(a - b), kPi);
  return std::min(d, kPi - d);
}

// Local orientation of each selected particle: the principal axis of the
// selected particles within `radius`. NaN with fewer than 3 of them or
// without a clear direction.
std::vector<double> local_orientations(const std::vector<Vec2>& points,
                                       const std::vector<int>& selected, const PointGrid& grid,
                                       double radius) {
  std::vector<double> angle(points.size(), std::nan(""));
  for (const int i : selected) {
    Moments m;
    grid.for_each_within(points[i], radius, [&](int j) {
      m.add(points[j].x - points[i].x, points[j].y - points[i].y);
    });
    if (m.n < 3) continue;
    const Moments::Axis axis = m.principal_axis();
    if (axis.variance_ratio <= kOrientedVarianceRatio) angle[i] = axis.angle;
  }
  return angle;
}

// A growing band's mean orientation: the mean of its members' axes as
// doubled angles, which treats an axis and its opposite alike.
class MeanAxis {
 public:
  void add(double angle) {
    if (std::isnan(angle)) return;
    c_ += std::cos(2 * angle);
    s_ += std::sin(2 * angle);
  }
  // A particle without an orientation, or a band without one yet, accepts.
  bool accepts(double angle, double max_angle) const {
    if (std::isnan(angle) || (c_ == 0 && s_ == 0)) return true;
    return axis_difference(angle, 0.5 * std::atan2(s_, c_)) <= max_angle;
  }

 private:
  double c_ = 0, s_ = 0;
};

// Band label of every particle (-1: in none), labels in order of the seeds.
std::vector<int> cluster_bands(const std::vector<Vec2>& points, const std::vector<double>& xi,
                               const std::vector<int>& selected, const BandParameters& p) {
  const double link = p.linking_factor * p.spacing;
  const PointGrid grid(points, selected, link);
  const bool use_orientation = p.max_angle < 90;
  const std::vector<double> orientation =
      use_orientation ? local_orientations(points, selected, grid, p.orientation_radius * p.spacing)
                      : std::vector<double>(points.size(), std::nan(""));
  const double max_angle = p.max_angle * kDegree;

  // Seeds from the highest xi: a band grows from its core outwards, so its
  // mean orientation is set by its best-defined part.
  std::vector<int> seeds = selected;
  std::stable_sort(seeds.begin(), seeds.end(), [&](int a, int b) { return xi[a] > xi[b]; });

  std::vector<int> label(points.size(), -1);
  std::vector<int> members;
  int bands = 0;
  for (const int seed : seeds) {
    if (label[seed] >= 0) continue;
    members.assign(1, seed);
    label[seed] = bands;
    MeanAxis axis;
    axis.add(orientation[seed]);
    for (size_t next = 0; next < members.size(); ++next) {
      grid.for_each_within(points[members[next]], link, [&](int j) {
        if (label[j] >= 0 || !axis.accepts(orientation[j], max_angle)) return;
        label[j] = bands;
        axis.add(orientation[j]);
        members.push_back(j);
      });
    }
    if (static_cast<int>(members.size()) >= p.min_particles) {
      ++bands;
    } else {
      // Too small to be a band: its particles stay free for a later band
      // (a few particles of a junction can seed a stub of their own).
      for (const int i : members) label[i] = -1;
    }
  }
  return label;
}

ShearBand measure_band(const std::vector<Vec2>& points, const std::vector<double>& xi,
                       std::vector<int> members, const runout::BaseView& base,
                       const BandParameters& p) {
  ShearBand band;
  band.particles = std::move(members);
  const double count = static_cast<double>(band.particles.size());
  for (const int i : band.particles) {
    band.centroid.x += points[i].x;
    band.centroid.y += points[i].y;
    band.mean_strain += xi[i];
    band.peak_strain = std::max(band.peak_strain, xi[i]);
  }
  band.centroid = {band.centroid.x / count, band.centroid.y / count};
  band.mean_strain /= count;
  Moments m;
  for (const int i : band.particles)
    m.add(points[i].x - band.centroid.x, points[i].y - band.centroid.y);
  const double angle = m.principal_axis().angle;
  Vec2 a = std::isnan(angle) ? Vec2{1, 0} : Vec2{std::cos(angle), std::sin(angle)};

  const runout::BasePoint at = runout::locate_on_base(base, band.centroid.x, band.centroid.y);
  band.centroid_s = at.s;
  const Vec2 n{at.nx, at.ny}, t{n.y, -n.x};  // the normal is the tangent turned +90 degrees
  double along = a.x * t.x + a.y * t.y, across = a.x * n.x + a.y * n.y;
  if (along < 0 || (along == 0 && across > 0)) {
    a = {-a.x, -a.y};
    along = -along;
    across = -across;
  }
  band.axis = a;
  band.dip = std::atan2(-across, along) / kDegree;

  std::vector<double> u(band.particles.size());
  for (size_t k = 0; k < u.size(); ++k) {
    const Vec2 q = points[band.particles[k]];
    u[k] = (q.x - band.centroid.x) * a.x + (q.y - band.centroid.y) * a.y;
  }
  const auto [lo, hi] = std::minmax_element(u.begin(), u.end());
  const double extent = *hi - *lo;
  band.length = extent + p.spacing;
  band.thickness = count * p.spacing * p.spacing / band.length;

  // Skeleton: at least two bins, so that a band gives a line, not a point.
  const int bins = std::max(2, static_cast<int>(std::ceil(extent / (p.skeleton_bin * p.spacing))));
  std::vector<Moments> bin(bins);
  for (size_t k = 0; k < u.size(); ++k) {
    const int b = extent > 0 ? std::min(bins - 1, static_cast<int>((u[k] - *lo) / extent * bins)) : 0;
    const Vec2 q = points[band.particles[k]];
    bin[b].add(q.x, q.y);
  }
  for (const Moments& b : bin)
    if (b.n > 0) band.skeleton.push_back({b.sx / b.n, b.sy / b.n});
  return band;
}

}  // namespace

double threshold_value(const std::vector<double>& xi, const StrainThreshold& threshold) {
  switch (threshold.mode) {
    case ThresholdMode::Absolute:
      return threshold.absolute;
    case ThresholdMode::RelativeToReference:
      return threshold.relative * threshold.reference;
    case ThresholdMode::Percentile:
      break;
  }
  if (xi.empty()) return 0;
  std::vector<double> sorted = xi;
  const double rank = std::ceil(threshold.percentile / 100 * static_cast<double>(sorted.size()));
  const size_t k = static_cast<size_t>(std::clamp(rank, 1.0, static_cast<double>(sorted.size()))) - 1;
  std::nth_element(sorted.begin(), sorted.begin() + k, sorted.end());
  return sorted[k];
}

std::vector<ShearBand> find_shear_bands(const std::vector<Vec2>& points,
                                        const std::vector<double>& xi,
                                        const runout::BaseView& base,
                                        const BandParameters& parameters) {
  if (points.empty() || !(parameters.spacing * parameters.linking_factor > 0)) return {};
  const double cut = threshold_value(xi, parameters.threshold);
  std::vector<int> selected;
  for (size_t i = 0; i < xi.size(); ++i)
    if (xi[i] > cut) selected.push_back(static_cast<int>(i));

  const std::vector<int> label = cluster_bands(points, xi, selected, parameters);
  std::vector<std::vector<int>> members;
  for (const int i : selected) {
    if (label[i] < 0) continue;
    if (label[i] >= static_cast<int>(members.size())) members.resize(label[i] + 1);
    members[label[i]].push_back(i);
  }
  std::vector<ShearBand> bands;
  for (auto& m : members) bands.push_back(measure_band(points, xi, std::move(m), base, parameters));
  std::stable_sort(bands.begin(), bands.end(),
                   [](const ShearBand& a, const ShearBand& b) { return a.centroid_s < b.centroid_s; });
  return bands;
}

}  // namespace runout::analysis
