#include "runout/mpm/nonlocal.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace runout {
namespace {

// As the MPM driver: below this a parallel region costs more than it saves.
constexpr int kParallelMin = 4096;

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

}  // namespace

// The lattice's spacing along y is l / kLatticePerLength; along a
// periodic x it is the period over a whole number of nodes no wider.
NonlocalAverage::NonlocalAverage(std::vector<Regularisation> materials, double period, double x0,
                                 BaseView mirror)
    : materials_(std::move(materials)), period_(period), x0_(x0), mirror_(mirror) {
  for (const auto& m : materials_) {
    active_ = active_ || m.length > 0.0;
    Taps t;
    if (m.length > 0.0) {
      t.spacing_y = m.length / kLatticePerLength;
      t.wrap = period_ > 0.0 ? std::max(1, static_cast<int>(std::ceil(period_ / t.spacing_y))) : 0;
      t.spacing_x = t.wrap > 0 ? period_ / t.wrap : t.spacing_y;
      t.y = gaussian_taps(t.spacing_y, m.length);
      t.x = t.wrap > 0 ? gaussian_taps(t.spacing_x, m.length) : t.y;
    }
    taps_.push_back(std::move(t));
  }
}

std::vector<double> NonlocalAverage::lengths() const {
  std::vector<double> out;
  for (const auto& m : materials_) out.push_back(m.length);
  return out;
}

// sum_j N_j(s) sum_i w((j - i) d) N_i(s) with d = spacing / l: the centre
// value of a thin band through s after spreading, convolving and taking back.
double NonlocalAverage::band_peak(double spacing_over_length, double s) {
  const LatticeSpline sp = lattice_spline(s);
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
void NonlocalAverage::convolve(std::vector<double>& field, const LatticeAxis& ax,
                               const LatticeAxis& ay) {
  const int nx = ax.count, ny = ay.count;
  const int rx = ax.reach, ry = ay.reach;
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
NonlocalLattice NonlocalAverage::lattice(int m, double xmin, double xmax, double ymin,
                                 double ymax) const {
  const Taps& t = taps_[m];
  NonlocalLattice g;
  g.x0 = x0_;
  g.ay.spacing = t.spacing_y;
  g.ay.reach = static_cast<int>(t.y.size()) - 1;
  g.ay.taps = t.y.data();
  const int reach = g.ay.reach;
  g.ay.first = static_cast<int>(std::floor(ymin / g.ay.spacing + 0.5)) - 1 - reach;
  g.ay.count = static_cast<int>(std::floor(ymax / g.ay.spacing + 0.5)) + 2 + reach - g.ay.first;
  g.ax.reach = static_cast<int>(t.x.size()) - 1;
  g.ax.taps = t.x.data();
  g.ax.spacing = t.spacing_x;
  if (t.wrap > 0) {
    g.ax.wrap = t.wrap;
    g.ax.count = t.wrap;
  } else {
    g.ax.first = static_cast<int>(std::floor(xmin / g.ax.spacing + 0.5)) - 1 - reach;
    g.ax.count = static_cast<int>(std::floor(xmax / g.ax.spacing + 0.5)) + 2 + reach - g.ax.first;
  }
  if (static_cast<double>(g.ax.count) * g.ay.count > std::numeric_limits<int>::max())
    throw std::runtime_error("the nonlocal average's lattice would have more than 2^31 nodes");
  return g;
}

// Taken back: sum w V dxi / sum w V is the normalised average; a thin
// band along x carrying delta gives delta K_x peak / (K_x K_y) there (K
// the kernel's line integral along each axis, peak the lattice's own
// factor for a thin band), so K_y / (t_s peak) turns it into delta / t_s.
double NonlocalAverage::band_scale(int m) const {
  const Regularisation& reg = materials_[m];
  const Taps& t = taps_[m];
  return line_integral(t.spacing_y, t.y) /
         (reg.band_thickness * band_peak(t.spacing_y / reg.length, 0.0));
}

// The particles of one chunk (kSpreadChunk of them by index, the last
// fewer) that are of the material, and their images, onto the chunk's own
// box of nodes.
void NonlocalAverage::spread_chunk(const NonlocalPoints& P, const double* in, int material,
                                   double reach, const NonlocalLattice& g, int c) {
  const Chunk& ch = chunks_[c];
  double* increments = chunk_sums_.data() + ch.at;
  double* volumes = increments + static_cast<std::size_t>(ch.ni) * ch.nj;
  std::fill(increments, volumes + static_cast<std::size_t>(ch.ni) * ch.nj, 0.0);
  // f(index in the box, weight) for the 3 x 3 nodes of (x, y).
  const auto for_nodes = [&](double x, double y, auto&& f) {
    const LatticeSpline sx = g.spline_x(x), sy = g.spline_y(y);
    for (int b = 0; b < 3; ++b) {
      const std::size_t row = static_cast<std::size_t>(sy.base - 1 + b - ch.j0) * ch.ni;
      for (int a = 0; a < 3; ++a) f(row + (sx.base - 1 + a - ch.i0), sy.w[b] * sx.w[a]);
    }
  };
  const int first = c * kSpreadChunk, end = std::min(P.n, first + kSpreadChunk);
  for (int p = first; p < end; ++p) {
    if (P.material[p] != material) continue;
    const double v = P.vol[p], va = P.vol[p] * in[p];
    if (va > 0.0)
      for_nodes(P.x[p], P.y[p], [&](std::size_t k, double w) {
        increments[k] += w * va;
        volumes[k] += w * v;
      });
    else  // most particles, which do not yield
      for_nodes(P.x[p], P.y[p], [&](std::size_t k, double w) { volumes[k] += w * v; });
  }
  if (mirror_.kind == BaseKind::None) return;
  for (int p = first; p < end; ++p) {
    double mx, my;
    if (P.material[p] == material && base_image(mirror_, P.x[p], P.y[p], reach, mx, my))
      for_nodes(mx, my, [&](std::size_t k, double w) { volumes[k] += w * P.vol[p]; });
  }
}

// V a and V spread chunk by chunk of the particles, on the threads, and
// added into the lattice in chunk order: the sums, and so the result, are
// the same on any number of threads.
void NonlocalAverage::spread(const NonlocalPoints& P, const double* in, int material, double reach,
                             double pad, const NonlocalLattice& g) {
  // A point's 3 x 3 nodes lie in the box made of the nearest nodes of the
  // box's extremes, less and plus one (the nearest node grows with the
  // coordinate); an image lies within pad of its particle.
  std::size_t total = 0;
  for (Chunk& ch : chunks_) {
    if (!(ch.xmin <= ch.xmax)) continue;
    ch.i0 = g.spline_x(ch.xmin - pad).base - 1;
    ch.j0 = g.spline_y(ch.ymin - pad).base - 1;
    ch.ni = g.spline_x(ch.xmax + pad).base + 2 - ch.i0;
    ch.nj = g.spline_y(ch.ymax + pad).base + 2 - ch.j0;
    ch.at = total;
    total += 2 * static_cast<std::size_t>(ch.ni) * ch.nj;
  }
  chunk_sums_.resize(total);
  const int chunks = static_cast<int>(chunks_.size());
#pragma omp parallel for schedule(dynamic) if (P.n > kParallelMin)
  for (int c = 0; c < chunks; ++c)
    if (chunks_[c].ni > 0) spread_chunk(P, in, material, reach, g, c);

  increments_.assign(g.size(), 0.0);
  volumes_.assign(g.size(), 0.0);
  const int rows = g.ay.count;
#pragma omp parallel for schedule(static) if (P.n > kParallelMin)
  for (int r = 0; r < rows; ++r) {
    const int j = g.ay.first + r;
    double* inc = increments_.data() + static_cast<std::size_t>(r) * g.ax.count;
    double* vol = volumes_.data() + static_cast<std::size_t>(r) * g.ax.count;
    for (const Chunk& ch : chunks_) {
      if (ch.ni == 0 || j < ch.j0 || j >= ch.j0 + ch.nj) continue;
      const std::size_t area = static_cast<std::size_t>(ch.ni) * ch.nj;
      const double* from = chunk_sums_.data() + ch.at + static_cast<std::size_t>(j - ch.j0) * ch.ni;
      for (int i = 0; i < ch.ni; ++i) {
        const int k = g.ax.node(ch.i0 + i);
        inc[k] += from[i];
        vol[k] += from[area + i];
      }
    }
  }
}

void NonlocalAverage::average_material(const NonlocalPoints& P, const double* in, double* out,
                                       int material) {
  const double reach = image_reach(material);
  // Each chunk's box of the material's particles, and the whole box from
  // them (min and max give the same bits in any order), widened where the
  // particles have images by how far an image can lie from its particle:
  // twice the reach. The images are found as they are spread: finding them
  // here as well took longer than the empty nodes this adds.
  const double pad = mirror_.kind != BaseKind::None ? 2.0 * reach : 0.0;
  const double inf = std::numeric_limits<double>::infinity();
  chunks_.resize((P.n + kSpreadChunk - 1) / kSpreadChunk);
  const int chunks = static_cast<int>(chunks_.size());
#pragma omp parallel for schedule(static) if (P.n > kParallelMin)
  for (int c = 0; c < chunks; ++c) {
    const int first = c * kSpreadChunk, end = std::min(P.n, first + kSpreadChunk);
    double x0 = inf, x1 = -inf, y0 = inf, y1 = -inf;
    for (int p = first; p < end; ++p) {
      if (P.material[p] != material) continue;
      x0 = std::min(x0, P.x[p]);
      x1 = std::max(x1, P.x[p]);
      y0 = std::min(y0, P.y[p]);
      y1 = std::max(y1, P.y[p]);
    }
    chunks_[c] = Chunk{x0, x1, y0, y1};
  }
  double xmin = inf, ymin = inf, xmax = -inf, ymax = -inf;
  for (const Chunk& ch : chunks_) {
    xmin = std::min(xmin, ch.xmin);
    xmax = std::max(xmax, ch.xmax);
    ymin = std::min(ymin, ch.ymin);
    ymax = std::max(ymax, ch.ymax);
  }
  if (!(xmin <= xmax)) return;
  const NonlocalLattice g = lattice(material, xmin - pad, xmax + pad, ymin - pad, ymax + pad);
  spread(P, in, material, reach, pad, g);
  convolve(increments_, g.ax, g.ay);
  convolve(volumes_, g.ax, g.ay);

  const Regularisation& reg = materials_[material];
  const GatherBand gather{g,      increments_.data(), volumes_.data(), P.x,
                          P.y,    P.material,         in,              out,
                          material, band_scale(material), reg.band_thickness, reg.length};
#pragma omp parallel for schedule(static) if (P.n > kParallelMin)
  for (int p = 0; p < P.n; ++p) gather(p);
}

void NonlocalAverage::apply(const NonlocalPoints& P, const double* in, double* out) {
  std::copy_n(in, P.n, out);
  for (int m = 0; m < static_cast<int>(materials_.size()); ++m)
    if (materials_[m].length > 0.0) average_material(P, in, out, m);
}

}  // namespace runout
