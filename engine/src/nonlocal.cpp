#include "runout/nonlocal.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace runout {
namespace {

// As the MPM driver: below this a parallel region costs more than it saves
// (on a machine shared with other jobs, far more).
constexpr int kParallelMin = 4096;

// Distance from v to the interval [lo, lo + width] (0 inside).
double gap(double v, double lo, double width) {
  return std::max({lo - v, v - (lo + width), 0.0});
}

}  // namespace

NonlocalAverage::NonlocalAverage(std::vector<double> lengths) : lengths_(std::move(lengths)) {
  for (double l : lengths_) active_ = active_ || l > 0.0;
}

// Bins of side l / kNonlocalBinsPerLength over the material's particles;
// but never so small that there are more bins than particles (a length far
// below the particle spacing would otherwise ask for bins by the billion):
// bin^2 >= area / n and bin >= extent / n. Sums in particle order.
void NonlocalAverage::aggregate(const NonlocalPoints& P, const double* in, int material) {
  double xmin = std::numeric_limits<double>::infinity(), ymin = xmin;
  double xmax = -xmin, ymax = -xmin;
  int n = 0;
  for (int p = 0; p < P.n; ++p) {
    if (P.material[p] != material) continue;
    xmin = std::min(xmin, P.x[p]);
    xmax = std::max(xmax, P.x[p]);
    ymin = std::min(ymin, P.y[p]);
    ymax = std::max(ymax, P.y[p]);
    ++n;
  }
  if (n == 0) return;
  const double width = xmax - xmin, height = ymax - ymin;
  bin_ = std::max({lengths_[material] / kNonlocalBinsPerLength, std::sqrt(width * height / n),
                   std::max(width, height) / n});
  x0_ = xmin;
  y0_ = ymin;
  bins_x_ = static_cast<int>(width / bin_) + 1;
  bins_y_ = static_cast<int>(height / bin_) + 1;
  bins_.assign(static_cast<std::size_t>(bins_x_) * bins_y_, Bin{});
  // Moments about the bin's corner, where they are well conditioned.
  for (int p = 0; p < P.n; ++p) {
    if (P.material[p] != material) continue;
    const int k = bin_index(P.x[p], P.y[p]);
    const double u = P.x[p] - (x0_ + (k % bins_x_) * bin_);
    const double v = P.y[p] - (y0_ + (k / bins_x_) * bin_);
    bins_[k].vol.add(P.vol[p], u, v);
    bins_[k].sum.add(P.vol[p] * in[p], u, v);
  }
  for (int k = 0; k < static_cast<int>(bins_.size()); ++k) {
    const double cx = x0_ + (k % bins_x_) * bin_, cy = y0_ + (k / bins_x_) * bin_;
    bins_[k].vol.centre(cx, cy);
    bins_[k].sum.centre(cx, cy);
  }
}

void NonlocalAverage::Moments::add(double m, double u, double v) {
  mass += m;
  x += m * u;
  y += m * v;
  xx += m * u * u;
  xy += m * u * v;
  yy += m * v * v;
}

// From sums about the corner (cx, cy) to the centroid and the central
// second moments.
void NonlocalAverage::Moments::centre(double cx, double cy) {
  if (mass <= 0.0) return;
  const double u = x / mass, v = y / mass;
  xx -= mass * u * u;
  xy -= mass * u * v;
  yy -= mass * v * v;
  x = cx + u;
  y = cy + v;
}

// sum over the bin's points of m_q w(x_q - (x, y)), by the Taylor expansion
// of w about the centroid c to second order: with d = c - (x, y) and M the
// central second moments, the Hessian of w = exp(-|d|^2 / l^2) is
// w (4 d d^T / l^4 - 2 I / l^2), so the sum is
//   w(d) (m + 2 d.M.d / l^4 - tr M / l^2) + O(bin^3 / l^3).
// The first-order term vanishes about the centroid.
double NonlocalAverage::Moments::weighted(double px, double py, double inv_l2) const {
  const double dx = x - px, dy = y - py;
  const double w = std::exp(-(dx * dx + dy * dy) * inv_l2);
  const double dMd = dx * dx * xx + 2.0 * dx * dy * xy + dy * dy * yy;
  return w * (mass + 2.0 * dMd * inv_l2 * inv_l2 - (xx + yy) * inv_l2);
}

int NonlocalAverage::bin_index(double x, double y) const {
  const int i = std::min(static_cast<int>((x - x0_) / bin_), bins_x_ - 1);
  const int j = std::min(static_cast<int>((y - y0_) / bin_), bins_y_ - 1);
  return j * bins_x_ + i;
}

double NonlocalAverage::average_at(double x, double y, double l, double own_value) const {
  const double cutoff = kNonlocalCutoff * l;
  const double cutoff2 = cutoff * cutoff, inv_l2 = 1.0 / (l * l);
  const int reach = static_cast<int>(std::ceil(cutoff / bin_));
  const int own = bin_index(x, y);
  const int bi = own % bins_x_, bj = own / bins_x_;
  double sum = 0, weight_sum = 0;
  for (int j = std::max(bj - reach, 0); j <= std::min(bj + reach, bins_y_ - 1); ++j) {
    const double gy = gap(y, y0_ + j * bin_, bin_);
    for (int i = std::max(bi - reach, 0); i <= std::min(bi + reach, bins_x_ - 1); ++i) {
      const double gx = gap(x, x0_ + i * bin_, bin_);
      if (gx * gx + gy * gy > cutoff2) continue;  // the whole bin is beyond the cut-off
      const Bin& b = bins_[j * bins_x_ + i];
      if (b.vol.mass == 0.0) continue;
      // A bin is in or out as a whole, by its volume centroid, so that a
      // uniform field, whose two centroids differ by rounding, stays uniform.
      const double dx = b.vol.x - x, dy = b.vol.y - y;
      if (dx * dx + dy * dy > cutoff2) continue;
      weight_sum += b.vol.weighted(x, y, inv_l2);
      if (b.sum.mass > 0.0) sum += b.sum.weighted(x, y, inv_l2);
    }
  }
  // The own bin's centroid is within reach unless the bins had to be made
  // larger than the cut-off (a length far below the particle spacing):
  // then there is nothing to average with.
  return weight_sum > 0.0 ? sum / weight_sum : own_value;
}

void NonlocalAverage::apply(const NonlocalPoints& P, const double* in, double* out) {
  std::copy_n(in, P.n, out);
  for (int m = 0; m < static_cast<int>(lengths_.size()); ++m) {
    const double l = lengths_[m];
    if (l <= 0.0) continue;
    aggregate(P, in, m);
#pragma omp parallel for schedule(dynamic, 64) if (P.n > kParallelMin)
    for (int p = 0; p < P.n; ++p)
      if (P.material[p] == m) out[p] = average_at(P.x[p], P.y[p], l, in[p]);
  }
}

}  // namespace runout
