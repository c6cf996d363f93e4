#include "runout/measure/morphology.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "runout/output/atomic_file.hpp"

namespace runout {

namespace {

void require_positive(double value, const char* what) {
  if (!(value > 0.0)) throw std::invalid_argument(std::string(what) + " must be > 0");
}

// A particle in base coordinates, with its velocity along the base.
struct Located {
  double s, d, v_s;
};

std::vector<Located> locate_particles(const Particles& P, const BaseView& base) {
  std::vector<Located> out(P.size());
  for (int p = 0; p < P.size(); ++p) {
    const BasePoint b = locate_on_base(base, P.x[p], P.y[p]);
    // The tangent is the outward normal turned -90 degrees: (ny, -nx).
    out[p] = Located{b.s, b.d, P.vx[p] * b.ny - P.vy[p] * b.nx};
  }
  return out;
}

// Bins of equal width along s, the first centred on the rear-most particle:
// particles on a lattice of the bin width then sit at bin centres, not on
// the edges where rounding would decide their bin.
struct Binning {
  double origin = 0, width = 1;
  int count = 0;

  int index(double s) const { return static_cast<int>(std::floor((s - origin) / width)); }
  double centre(int k) const { return origin + (k + 0.5) * width; }
};

Binning binning_over(const std::vector<Located>& located, double width) {
  Binning b;
  b.width = width;
  if (located.empty()) return b;
  const auto [lo, hi] = std::minmax_element(
      located.begin(), located.end(),
      [](const Located& a, const Located& c) { return a.s < c.s; });
  b.origin = lo->s - 0.5 * width;
  b.count = b.index(hi->s) + 1;  // the same expression that bins the front-most particle
  return b;
}

struct BinTotals {
  int particles = 0;
  double mass = 0;
  double momentum_s = 0;  // sum of m v_s
  double max_d = -std::numeric_limits<double>::infinity();
};

std::vector<BinTotals> bin_totals(const Particles& P, const std::vector<Located>& located,
                                  const Binning& binning) {
  std::vector<BinTotals> bins(binning.count);
  for (int p = 0; p < P.size(); ++p) {
    BinTotals& b = bins[binning.index(located[p].s)];
    b.particles += 1;
    b.mass += P.mass[p];
    b.momentum_s += P.mass[p] * located[p].v_s;
    b.max_d = std::max(b.max_d, located[p].d);
  }
  return bins;
}

struct BinRange {
  int first = 0, last = -1;
  bool contains(int k) const { return first <= k && k <= last; }
};

// The runs of occupied bins, rear to front, each bridging up to gap_bins
// empty bins: the main body and any blocks that have broken away.
std::vector<BinRange> occupied_runs(const std::vector<BinTotals>& bins, int gap_bins) {
  std::vector<BinRange> runs;
  for (int k = 0; k < static_cast<int>(bins.size()); ++k) {
    if (bins[k].particles == 0) continue;
    if (runs.empty() || k - runs.back().last - 1 > gap_bins) runs.push_back(BinRange{k, k});
    runs.back().last = k;
  }
  return runs;
}

// The heaviest run; the first (rear-most) of equally heavy runs.
BinRange heaviest_run(const std::vector<BinTotals>& bins, const std::vector<BinRange>& runs) {
  BinRange best;
  double best_mass = -1.0;
  for (const BinRange& run : runs) {
    double mass = 0.0;
    for (int k = run.first; k <= run.last; ++k) mass += bins[k].mass;
    if (mass > best_mass) {
      best = run;
      best_mass = mass;
    }
  }
  return best;
}

// sqrt(sum over the runs of (their momentum along s)^2 / their mass, over
// the whole mass).
double block_speed(const std::vector<BinTotals>& bins, const std::vector<BinRange>& runs) {
  double energy = 0.0, mass = 0.0;
  for (const BinRange& run : runs) {
    double run_mass = 0.0, run_momentum = 0.0;
    for (int k = run.first; k <= run.last; ++k) {
      run_mass += bins[k].mass;
      run_momentum += bins[k].momentum_s;
      mass += bins[k].mass;
    }
    energy += run_momentum * run_momentum / run_mass;
  }
  return mass > 0.0 ? std::sqrt(energy / mass) : 0.0;
}

// Running sums over the main body; divided by its mass at the end.
struct MainBodySums {
  int particles = 0;
  double mass = 0, mx = 0, my = 0, ms = 0, mvx = 0, mvy = 0;
  double front_s = -std::numeric_limits<double>::infinity();
  double rear_s = std::numeric_limits<double>::infinity();
  double max_d = -std::numeric_limits<double>::infinity();

  void add(const Particles& P, int p, const Located& l) {
    const double m = P.mass[p];
    particles += 1;
    mass += m;
    mx += m * P.x[p];
    my += m * P.y[p];
    ms += m * l.s;
    mvx += m * P.vx[p];
    mvy += m * P.vy[p];
    front_s = std::max(front_s, l.s);
    rear_s = std::min(rear_s, l.s);
    max_d = std::max(max_d, l.d);
  }
};

// The mass-weighted along-base velocity of the main-body particles whose
// centre is within the toe window.
double toe_velocity(const Particles& P, const std::vector<Located>& located,
                    const std::vector<bool>& in_main, double window_start) {
  double mass = 0.0, momentum = 0.0;
  for (int p = 0; p < P.size(); ++p) {
    if (!in_main[p] || located[p].s < window_start) continue;
    mass += P.mass[p];
    momentum += P.mass[p] * located[p].v_s;
  }
  return momentum / mass;
}

// The s at which the mass, summed from the rear in order of s (ties in
// particle order, so any run gives the same), first reaches `fraction` of
// the whole.
double mass_quantile_s(const Particles& P, const std::vector<Located>& located,
                       double fraction) {
  std::vector<int> order(P.size());
  for (int p = 0; p < P.size(); ++p) order[p] = p;
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return located[a].s < located[b].s; });
  double total = 0.0;
  for (int p = 0; p < P.size(); ++p) total += P.mass[p];
  double behind = 0.0;
  for (const int p : order) {
    behind += P.mass[p];
    if (behind >= fraction * total) return located[p].s;
  }
  return located[order.back()].s;  // rounding: the front-most particle
}

void append_number(std::string& out, double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  out += buf;
}

}  // namespace

BaseFrame base_frame_at(const BaseView& base, double s) {
  if (base.kind != BaseKind::Polyline) return BaseFrame{s, base.y0, 1.0, 0.0, 0.0, 1.0};
  // The segment whose arc-length range holds s; the end segments take
  // everything beyond the polyline's ends.
  const int after = static_cast<int>(std::upper_bound(base.ps, base.ps + base.n, s) - base.ps);
  const int k = std::clamp(after - 1, 0, base.n - 2);
  const double tx = base.seg[k].tx, ty = base.seg[k].ty;
  const double t = s - base.ps[k];
  return BaseFrame{base.px[k] + t * tx, base.py[k] + t * ty, tx, ty, -ty, tx};
}

SlideMorphology measure_slide(const Particles& P, const BaseView& base, double spacing) {
  require_positive(spacing, "particle spacing");
  SlideMorphology out;
  if (P.size() == 0) return out;

  const std::vector<Located> located = locate_particles(P, base);
  const Binning binning = binning_over(located, kMainBodyBinSpacings * spacing);
  const std::vector<BinTotals> bins = bin_totals(P, located, binning);
  const std::vector<BinRange> runs = occupied_runs(bins, kMainBodyGapBins);
  const BinRange main = heaviest_run(bins, runs);
  out.block_speed = block_speed(bins, runs);

  MainBodySums sums;
  std::vector<bool> in_main(P.size());
  for (int p = 0; p < P.size(); ++p) {
    in_main[p] = main.contains(binning.index(located[p].s));
    if (in_main[p]) {
      sums.add(P, p, located[p]);
    } else {
      out.outside_mass += P.mass[p];
    }
    const double v2 = P.vx[p] * P.vx[p] + P.vy[p] * P.vy[p];
    out.kinetic_energy += 0.5 * P.mass[p] * v2;
    out.max_speed = std::max(out.max_speed, std::sqrt(v2));
  }

  const double half = 0.5 * spacing;
  out.particles = sums.particles;
  out.toe_s = sums.front_s + half;
  out.rear_s = sums.rear_s - half;
  out.length = out.toe_s - out.rear_s;
  out.centroid_x = sums.mx / sums.mass;
  out.centroid_y = sums.my / sums.mass;
  out.centroid_s = sums.ms / sums.mass;
  out.centroid_vx = sums.mvx / sums.mass;
  out.centroid_vy = sums.mvy / sums.mass;
  const BaseFrame at_centroid = base_frame_at(base, out.centroid_s);
  out.centroid_velocity_s = out.centroid_vx * at_centroid.tx + out.centroid_vy * at_centroid.ty;
  out.toe_velocity =
      toe_velocity(P, located, in_main, out.toe_s - kToeWindowSpacings * spacing);
  out.max_thickness = sums.max_d + half;
  out.mass_front_s = mass_quantile_s(P, located, kMassFrontFraction);
  return out;
}

double runout_distance(const SlideMorphology& now, double initial_toe_s) {
  return now.toe_s - initial_toe_s;
}

// Morphological closing (a running max, then a running min, over 2 r + 1
// bins) of a profile that is 0 outside the slide: fills troughs narrower
// than about 2 r bins and leaves wider ones, the ends of the slide and
// every convex stretch of surface as they were.
std::vector<double> closed(const std::vector<double>& v, int r) {
  const int pad = 2 * r;  // zeros beyond the ends, so that they stay ends
  std::vector<double> in(v.size() + 2 * pad, 0.0);
  std::copy(v.begin(), v.end(), in.begin() + pad);
  const int n = static_cast<int>(in.size());
  const auto sweep = [n, r](const std::vector<double>& a, bool take_max) {
    std::vector<double> out(n);
    for (int i = 0; i < n; ++i) {
      double m = a[i];
      for (int j = std::max(0, i - r); j <= std::min(n - 1, i + r); ++j)
        m = take_max ? std::max(m, a[j]) : std::min(m, a[j]);
      out[i] = m;
    }
    return out;
  };
  const std::vector<double> c = sweep(sweep(in, true), false);
  return std::vector<double>(c.begin() + pad, c.end() - pad);
}

Profile slide_profile(const Particles& P, const BaseView& base, double bin_width,
                      double spacing) {
  require_positive(bin_width, "profile bin width");
  require_positive(spacing, "particle spacing");
  const std::vector<Located> located = locate_particles(P, base);
  const Binning binning = binning_over(located, bin_width);
  const std::vector<BinTotals> totals = bin_totals(P, located, binning);

  std::vector<double> top(totals.size(), 0.0);
  for (int k = 0; k < binning.count; ++k)
    if (totals[k].particles > 0) top[k] = totals[k].max_d + 0.5 * spacing;
  // A slide stretched to several times its length leaves its particle
  // columns further apart than a bin, and the bins between hold only lower
  // particles or none: a sawtooth that is not the surface.
  top = closed(top, kProfileClosingBins);

  Profile profile;
  profile.bin_width = bin_width;
  profile.bins.resize(totals.size());
  for (int k = 0; k < binning.count; ++k) {
    const BinTotals& t = totals[k];
    ProfileBin& bin = profile.bins[k];
    bin.s = binning.centre(k);
    bin.particles = t.particles;
    bin.thickness = top[k];
    if (t.particles > 0) bin.velocity_s = t.momentum_s / t.mass;
    const BaseFrame f = base_frame_at(base, bin.s);
    bin.x_surface = f.x + bin.thickness * f.nx;
    bin.y_surface = f.y + bin.thickness * f.ny;
  }
  return profile;
}

void write_profile_csv(const std::string& path, double time, const Profile& profile) {
  std::string text = "# time = ";
  append_number(text, time);
  text += "\ns,x_surface,y_surface,thickness,particles,velocity_s\n";
  for (const ProfileBin& b : profile.bins) {
    for (const double v : {b.s, b.x_surface, b.y_surface, b.thickness}) {
      append_number(text, v);
      text += ',';
    }
    text += std::to_string(b.particles) + ',';
    append_number(text, b.velocity_s);
    text += '\n';
  }
  write_file_atomically(path, text);
}

}  // namespace runout
