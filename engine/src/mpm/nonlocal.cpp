#include "runout/mpm/nonlocal.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace runout {
namespace {

// As the MPM driver: below this a parallel region costs more than it saves.
constexpr int kParallelMin = 4096;
constexpr double kPi = 3.14159265358979323846;

// Quadratic B-spline weights of the nodes base - 1, base, base + 1 for a
// point at u lattice spacings from node 0, base the nearest node (de Boor;
// the weights sum to 1 and reproduce the point's first and second moments).
struct Spline {
  int base;
  double w[3];
};
Spline spline(double u) {
  const int base = static_cast<int>(std::floor(u + 0.5));
  const double t = u - base;  // in [-1/2, 1/2)
  return {base, {0.5 * (0.5 - t) * (0.5 - t), 0.75 - t * t, 0.5 * (0.5 + t) * (0.5 + t)}};
}

std::vector<double> gaussian_taps(double spacing, double length) {
  const int reach = static_cast<int>(std::ceil(kNonlocalCutoff * length / spacing));
  std::vector<double> taps(reach + 1);
  for (int k = 0; k <= reach; ++k) {
    const double r = k * spacing / length;
    taps[k] = std::exp(-r * r);
  }
  return taps;
}

// K_line of the lattice along one axis: spacing times the sum of the taps.
double line_integral(double spacing, const std::vector<double>& taps) {
  double sum = taps[0];
  for (std::size_t k = 1; k < taps.size(); ++k) sum += 2.0 * taps[k];
  return spacing * sum;
}

// The increment of a particle whose own increment is a and whose band
// carries delta / t_s = band: b = delta / a is the width of the zone that
// yields around it, measured. A band (b up to half the averaging width
// sqrt(pi) l) remoulds by delta / t_s; a zone as wide as the average or
// wider is diffuse yield, which no band concentrates, and remoulds by its
// own strain a; between the two, a linear blend.
double localised_increment(double a, double band, double t_s, double l) {
  if (a <= 0.0) return 0.0;
  const double x = band * t_s / (a * std::sqrt(kPi) * l);  // b / (sqrt(pi) l)
  const double phi = std::clamp(2.0 * (1.0 - x), 0.0, 1.0);
  return phi * band + (1.0 - phi) * a;
}

}  // namespace

NonlocalAverage::NonlocalAverage(std::vector<Regularisation> materials, double period, double x0,
                                 BaseView mirror)
    : materials_(std::move(materials)), period_(period), x0_(x0), mirror_(mirror) {
  for (const auto& m : materials_) active_ = active_ || m.length > 0.0;
}

std::vector<double> NonlocalAverage::lengths() const {
  std::vector<double> out;
  for (const auto& m : materials_) out.push_back(m.length);
  return out;
}

// sum_j N_j(s) sum_i w((j - i) d) N_i(s) with d = spacing / l: the centre
// value of a thin band through s after spreading, convolving and taking back.
double NonlocalAverage::band_peak(double spacing_over_length, double s) {
  const Spline sp = spline(s);
  double peak = 0;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const double r = (a - b) * spacing_over_length;
      peak += sp.w[a] * sp.w[b] * std::exp(-r * r);
    }
  return peak;
}

// field (ay.count rows of ax.count) convolved with the taps along x into
// pass_, then along y back into field, both as sums over the taps of whole
// shifted rows (contiguous, so they vectorise). Each row is worked only
// over the span where it is not zero, widened by the taps along x: a long
// or diagonal slide fills a small part of each row of its bounding box,
// and rows that are zero are skipped whole. Adding the zeros left out
// changed no sum, and each output is summed in the same order whatever the
// threads, which split the rows.
void NonlocalAverage::convolve(std::vector<double>& field, const Axis& ax, const Axis& ay) {
  const int nx = ax.count, ny = ay.count;
  const int rx = static_cast<int>(ax.taps.size()) - 1, ry = static_cast<int>(ay.taps.size()) - 1;
  pass_.assign(field.size(), 0.0);
  spans_.assign(ny, Span{});
#pragma omp parallel for schedule(static) if (nx * ny > kParallelMin)
  for (int j = 0; j < ny; ++j) {
    const double* in = field.data() + static_cast<std::size_t>(j) * nx;
    double* out = pass_.data() + static_cast<std::size_t>(j) * nx;
    int lo = 0;
    while (lo < nx && in[lo] == 0.0) ++lo;
    if (lo == nx) continue;
    int hi = nx;
    while (in[hi - 1] == 0.0) --hi;
    // in is zero outside [lo, hi); out is not outside [lo - rx, hi + rx),
    // the whole row where it wraps.
    spans_[j] = ax.wrap > 0 ? Span{0, nx} : Span{std::max(0, lo - rx), std::min(nx, hi + rx)};
    for (int k = -rx; k <= rx; ++k) {
      const double w = ax.taps[std::abs(k)];
      if (ax.wrap > 0) {
        for (int i = 0; i < nx; ++i) out[i] += w * in[((i + k) % nx + nx) % nx];
      } else {
        // out[i] += w in[i + k] for lo <= i + k < hi
        const int first = std::max(0, lo - k), last = std::min(nx, hi - k);
        for (int i = first; i < last; ++i) out[i] += w * in[i + k];
      }
    }
  }
#pragma omp parallel for schedule(static) if (nx * ny > kParallelMin)
  for (int j = 0; j < ny; ++j) {
    double* out = field.data() + static_cast<std::size_t>(j) * nx;
    std::fill(out, out + nx, 0.0);
    for (int k = std::max(-ry, -j); k <= std::min(ry, ny - 1 - j); ++k) {
      const Span span = spans_[j + k];
      if (span.first == span.last) continue;
      const double w = ay.taps[std::abs(k)];
      const double* in = pass_.data() + static_cast<std::size_t>(j + k) * nx;
      for (int i = span.first; i < span.last; ++i) out[i] += w * in[i];
    }
  }
}

// The lattice over the points' box and the kernel's reach; along x the
// period where the scene is periodic (a whole number of spacings, so the
// lattice closes on itself).
void NonlocalAverage::fit_lattice(double l, double xmin, double xmax, double ymin, double ymax) {
  ay_ = Axis{};
  ay_.spacing = l / kLatticePerLength;
  ay_.taps = gaussian_taps(ay_.spacing, l);
  const int reach = static_cast<int>(ay_.taps.size()) - 1;
  ay_.first = static_cast<int>(std::floor(ymin / ay_.spacing + 0.5)) - 1 - reach;
  ay_.count = static_cast<int>(std::floor(ymax / ay_.spacing + 0.5)) + 2 + reach - ay_.first;
  ax_ = Axis{};
  if (period_ > 0.0) {
    ax_.wrap = std::max(1, static_cast<int>(std::ceil(period_ / ay_.spacing)));
    ax_.spacing = period_ / ax_.wrap;
    ax_.count = ax_.wrap;
    ax_.taps = gaussian_taps(ax_.spacing, l);
  } else {
    ax_.spacing = ay_.spacing;
    ax_.taps = ay_.taps;
    ax_.first = static_cast<int>(std::floor(xmin / ax_.spacing + 0.5)) - 1 - reach;
    ax_.count = static_cast<int>(std::floor(xmax / ax_.spacing + 0.5)) + 2 + reach - ax_.first;
  }
  const std::size_t size = static_cast<std::size_t>(ax_.count) * ay_.count;
  increments_.assign(size, 0.0);
  volumes_.assign(size, 0.0);
}

template <class F>
void NonlocalAverage::for_nodes(double x, double y, F&& f) const {
  const Spline sx = spline((x - (period_ > 0.0 ? x0_ : 0.0)) / ax_.spacing);
  const Spline sy = spline(y / ay_.spacing);
  for (int b = 0; b < 3; ++b) {
    const std::size_t row = static_cast<std::size_t>(ay_.node(sy.base - 1 + b)) * ax_.count;
    for (int a = 0; a < 3; ++a) f(row + ax_.node(sx.base - 1 + a), sy.w[b] * sx.w[a]);
  }
}

// Where p's image across a no-slip base lies, if within the kernel's
// reach: a band along such a base keeps the whole kernel across it (the
// images' volume, not their increments, enters the weights).
bool NonlocalAverage::mirror_point(double x, double y, double reach, double& mx,
                                   double& my) const {
  if (mirror_.kind == BaseKind::None) return false;
  const BasePoint b = locate_on_base(mirror_, x, y);
  if (b.d < 0.0 || b.d > reach) return false;
  mx = x - 2.0 * b.d * b.nx;
  my = y - 2.0 * b.d * b.ny;
  return true;
}

void NonlocalAverage::average_material(const NonlocalPoints& P, const double* in, double* out,
                                       int material) {
  const Regularisation& reg = materials_[material];
  const double l = reg.length, reach = kNonlocalCutoff * l;
  // The box of the material's particles and their images, split over the
  // threads (min and max reduce in any order to the same bits); each
  // particle's image is kept at its own index (vol 0: none; no array
  // without a no-slip base to mirror in), so the images are spread in
  // particle order whatever the threads.
  double xmin = std::numeric_limits<double>::infinity(), ymin = xmin, xmax = -xmin, ymax = -xmin;
  const bool mirrored = mirror_.kind != BaseKind::None;
  images_.assign(mirrored ? P.n : 0, Image{0.0, 0.0, 0.0});
#pragma omp parallel for schedule(static) reduction(min : xmin, ymin) reduction(max : xmax, ymax) \
    if (P.n > kParallelMin)
  for (int p = 0; p < P.n; ++p) {
    if (P.material[p] != material) continue;
    xmin = std::min(xmin, P.x[p]);
    xmax = std::max(xmax, P.x[p]);
    ymin = std::min(ymin, P.y[p]);
    ymax = std::max(ymax, P.y[p]);
    if (!mirrored) continue;
    Image& image = images_[p];
    if (mirror_point(P.x[p], P.y[p], reach, image.x, image.y)) {
      image.vol = P.vol[p];
      xmin = std::min(xmin, image.x);
      xmax = std::max(xmax, image.x);
      ymin = std::min(ymin, image.y);
      ymax = std::max(ymax, image.y);
    }
  }
  if (!(xmin <= xmax)) return;
  fit_lattice(l, xmin, xmax, ymin, ymax);

  // Spread V dxi and V (with the images' V), in particle order.
  for (int p = 0; p < P.n; ++p) {
    if (P.material[p] != material) continue;
    const double v = P.vol[p], va = P.vol[p] * in[p];
    if (va > 0.0)
      for_nodes(P.x[p], P.y[p], [&](std::size_t k, double w) {
        increments_[k] += w * va;
        volumes_[k] += w * v;
      });
    else
      for_nodes(P.x[p], P.y[p], [&](std::size_t k, double w) { volumes_[k] += w * v; });
  }
  for (const Image& image : images_)
    if (image.vol > 0.0)
      for_nodes(image.x, image.y, [&](std::size_t k, double w) { volumes_[k] += w * image.vol; });
  convolve(increments_, ax_, ay_);
  convolve(volumes_, ax_, ay_);

  // Taken back: sum w V dxi / sum w V is the normalised average, times the
  // weight a point deep inside the body has, K_x K_y, is the integral of
  // the kernel over the increments as if the body went on all round; over
  // t_s K_line, and the lattice's own factor for a thin band, it is
  // delta / t_s.
  const double kx = line_integral(ax_.spacing, ax_.taps), ky = line_integral(ay_.spacing, ay_.taps);
  const double scale = kx * ky / (reg.band_thickness * kx * band_peak(ay_.spacing / l, 0.0));
#pragma omp parallel for schedule(static) if (P.n > kParallelMin)
  for (int p = 0; p < P.n; ++p) {
    if (P.material[p] != material) continue;
    if (in[p] <= 0.0) {  // a particle that does not yield does not soften
      out[p] = 0.0;
      continue;
    }
    double sum = 0, weight = 0;
    for_nodes(P.x[p], P.y[p], [&](std::size_t k, double w) {
      sum += w * increments_[k];
      weight += w * volumes_[k];
    });
    const double band = weight > 0.0 ? scale * sum / weight : 0.0;
    out[p] = localised_increment(in[p], band, reg.band_thickness, l);
  }
}

void NonlocalAverage::apply(const NonlocalPoints& P, const double* in, double* out) {
  std::copy_n(in, P.n, out);
  for (int m = 0; m < static_cast<int>(materials_.size()); ++m)
    if (materials_[m].length > 0.0) average_material(P, in, out, m);
}

}  // namespace runout
