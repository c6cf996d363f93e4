#include "runout/analysis/horst_graben.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "runout/measure/morphology.hpp"
#include "runout/mpm/particles.hpp"

namespace runout::analysis {

namespace {

constexpr double kDegree = 3.14159265358979323846 / 180;

// Per along-base bin of width `width` from s0: the highest d of the
// particles in it (-infinity in an empty bin).
struct BinnedHeights {
  double s0 = 0, width = 1;
  std::vector<double> hi;

  BinnedHeights(double s0_, double width_, double s_max) : s0(s0_), width(width_) {
    const size_t bins = static_cast<size_t>((s_max - s0) / width) + 1;
    hi.assign(bins, -std::numeric_limits<double>::infinity());
  }
  size_t bin(double s) const {
    return std::min(hi.size() - 1, static_cast<size_t>(std::max(0.0, (s - s0) / width)));
  }
  void add(double s, double d) {
    double& b = hi[bin(s)];
    b = std::max(b, d);
  }
};

// A band that bounds blocks, as a straight line in base coordinates through
// its centroid at its dip: s(d) = s_c + (d_c - d) cot(dip).
struct BoundaryBand {
  int band;
  double surface_s;  // where it meets the upper surface
  double dip;
  double s_c, d_c, cot;

  double s_at(double d) const { return s_c + (d_c - d) * cot; }
};

bool dips(double dip, double tolerance) {
  return std::abs(dip) >= tolerance && std::abs(dip) <= 90 - tolerance;
}

BlockType classify(const BoundaryBand* left, const BoundaryBand* right, double tolerance) {
  if (!left || !right || !dips(left->dip, tolerance) || !dips(right->dip, tolerance))
    return BlockType::Block;
  if (left->dip < 0 && right->dip > 0) return BlockType::Horst;
  if (left->dip > 0 && right->dip < 0) return BlockType::Graben;
  return BlockType::Block;
}

// The bands that reach the upper surface and cross the slide, ordered by
// where they meet the surface.
std::vector<BoundaryBand> boundary_bands(const std::vector<ShearBand>& bands,
                                         const std::vector<runout::BasePoint>& at,
                                         const BinnedHeights& surface, const runout::BaseView& base,
                                         const BlockParameters& p) {
  std::vector<BoundaryBand> boundaries;
  for (size_t k = 0; k < bands.size(); ++k) {
    const ShearBand& band = bands[k];
    // (dip 0 even with no tolerance: a band along the base has no line across it)
    if (band.dip == 0 || std::abs(band.dip) < p.dip_tolerance) continue;
    double gap = std::numeric_limits<double>::infinity(), surface_s = 0;
    for (const int i : band.particles) {
      const double below = surface.hi[surface.bin(at[i].s)] - at[i].d;
      if (below < gap) {
        gap = below;
        surface_s = at[i].s;
      }
    }
    if (gap > p.surface_gap * p.spacing) continue;
    const runout::BasePoint c = runout::locate_on_base(base, band.centroid.x, band.centroid.y);
    boundaries.push_back({static_cast<int>(k), surface_s, band.dip, c.s, c.d,
                          std::cos(band.dip * kDegree) / std::sin(band.dip * kDegree)});
  }
  std::stable_sort(boundaries.begin(), boundaries.end(),
                   [](const BoundaryBand& a, const BoundaryBand& b) { return a.surface_s < b.surface_s; });
  return boundaries;
}

// Block of a particle: j when it lies right of (at larger s than) the first
// j boundary lines and left of the others; -1 when the lines are not in that
// order at its height (under the point where two of them cross).
int block_of(const runout::BasePoint& at, const std::vector<BoundaryBand>& boundaries) {
  const int m = static_cast<int>(boundaries.size());
  int j = 0;
  while (j < m && boundaries[j].s_at(at.d) <= at.s) ++j;
  for (int k = j + 1; k < m; ++k)
    if (boundaries[k].s_at(at.d) <= at.s) return -1;
  return j;
}

// The slide's upper surface as a polyline d = T(s) over its outer edges
// [rear, front]: the vertices are the bin centres of the thickness profile of
// Runout Morphology (runout::slide_profile, bins of outline_bin spacings,
// troughs between particle columns closed), the ends at the outer edges at
// the thickness of the end bins. A gap wider than the closing has T = 0.
struct Surface {
  std::vector<Vec2> vertices;  // (s, d), s increasing

  double at(double s) const {
    const auto after = std::upper_bound(vertices.begin(), vertices.end(), s,
                                        [](double v, const Vec2& q) { return v < q.x; });
    if (after == vertices.begin()) return vertices.front().y;
    if (after == vertices.end()) return vertices.back().y;
    const Vec2 a = *(after - 1), b = *after;
    return a.y + (b.y - a.y) * (s - a.x) / (b.x - a.x);
  }
};

Surface upper_surface(const std::vector<Vec2>& points, const runout::BaseView& base, double rear,
                      double front, const BlockParameters& p) {
  runout::Particles particles;
  particles.resize(static_cast<int>(points.size()));
  for (size_t i = 0; i < points.size(); ++i) {
    particles.x[i] = points[i].x;
    particles.y[i] = points[i].y;
    particles.mass[i] = 1;
  }
  const runout::Profile profile =
      runout::slide_profile(particles, base, p.outline_bin * p.spacing, p.spacing);
  Surface surface;
  surface.vertices.push_back({rear, profile.bins.front().thickness});
  for (const runout::ProfileBin& bin : profile.bins)
    if (bin.s > rear && bin.s < front) surface.vertices.push_back({bin.s, bin.thickness});
  surface.vertices.push_back({front, profile.bins.back().thickness});
  return surface;
}

// A boundary line in base coordinates: f(s, d) = s - s_c + (d - d_c) cot,
// zero on the line, positive on its front (+s) side; r = s + d cot on it.
double side_of(const BoundaryBand& line, double s, double d) {
  return s - line.s_c + (d - line.d_c) * line.cot;
}

// Every s where the outline of a block may bend: the surface's vertices and
// where a boundary line crosses the surface, the base (d = 0) or another
// line. Between two of them every bound of a block's column is linear.
std::vector<double> outline_breaks(const Surface& surface,
                                   const std::vector<BoundaryBand>& boundaries) {
  std::vector<double> breaks;
  for (const Vec2& q : surface.vertices) breaks.push_back(q.x);
  for (size_t k = 0; k < boundaries.size(); ++k) {
    const BoundaryBand& line = boundaries[k];
    breaks.push_back(line.s_at(0));
    for (size_t i = 0; i + 1 < surface.vertices.size(); ++i) {
      const Vec2 a = surface.vertices[i], b = surface.vertices[i + 1];
      const double fa = side_of(line, a.x, a.y), fb = side_of(line, b.x, b.y);
      if ((fa < 0) != (fb < 0)) breaks.push_back(a.x + (b.x - a.x) * fa / (fa - fb));
    }
    for (size_t l = k + 1; l < boundaries.size(); ++l) {
      const BoundaryBand& other = boundaries[l];
      if (line.cot == other.cot) continue;
      // s + d cot = s_c + d_c cot on each line
      const double r = line.s_c + line.d_c * line.cot, r2 = other.s_c + other.d_c * other.cot;
      const double d = (r - r2) / (line.cot - other.cot);
      breaks.push_back(r - d * line.cot);
    }
  }
  const double rear = surface.vertices.front().x, front = surface.vertices.back().x;
  breaks.erase(std::remove_if(breaks.begin(), breaks.end(),
                              [&](double s) { return !(s >= rear && s <= front); }),
               breaks.end());
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  return breaks;
}

// The column of block j at s: the heights d in [0, T(s)] in front of the
// first j boundary lines and behind the others (block_of's rule); lo > hi
// where it is empty.
struct Column {
  double lo, hi;
};

Column block_column(double s, const Surface& surface, const std::vector<BoundaryBand>& boundaries,
                    size_t j) {
  Column c{0, surface.at(s)};
  const double tiny = 1e-12;
  for (size_t k = 0; k < boundaries.size(); ++k) {
    // in front of line k (k < j): A d + B >= 0, with A = cot, B = f(s, 0);
    // behind it the reverse
    const double sign = k < j ? 1 : -1;
    const double a = sign * boundaries[k].cot, b = sign * side_of(boundaries[k], s, 0);
    if (a > tiny) {
      c.lo = std::max(c.lo, -b / a);
    } else if (a < -tiny) {
      c.hi = std::min(c.hi, -b / a);
    } else if (b < 0) {
      c.lo = std::numeric_limits<double>::infinity();  // a vertical line, on its other side
    }
  }
  return c;
}

// Drops repeated points and points in the middle of a straight edge.
std::vector<Vec2> corners_of(const std::vector<Vec2>& ring, double scale) {
  std::vector<Vec2> corners;
  const double eps = 1e-9 * scale;
  const auto straight = [eps](Vec2 a, Vec2 b, Vec2 q) {
    const double cross = (b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x);
    const double along = (b.x - a.x) * (q.x - b.x) + (b.y - a.y) * (q.y - b.y);
    return std::abs(cross) <= eps * std::hypot(q.x - a.x, q.y - a.y) && along >= 0;
  };
  for (const Vec2& q : ring) {
    if (!corners.empty() && std::hypot(q.x - corners.back().x, q.y - corners.back().y) <= eps)
      continue;
    if (corners.size() >= 2 && straight(corners[corners.size() - 2], corners.back(), q))
      corners.pop_back();
    corners.push_back(q);
  }
  while (corners.size() > 3 && std::hypot(corners.front().x - corners.back().x,
                                          corners.front().y - corners.back().y) <= eps)
    corners.pop_back();
  return corners;
}

// Closed outline of block j: the region between the base and the slide's
// upper surface in front of its rear boundary line and behind its front one,
// counter-clockwise: its bottom (the base, or a line where it meets the
// base inside the slide) from rear to front, then its top (the surface, or
// a line) from front to rear. Where the surface dips below the region (a
// trough at a band's top), the outline runs along the surface.
// A block whose region has no area (its particles below the base) gets the
// rectangle of its particles' extent and top, from the base.
std::vector<Vec2> block_outline(const Surface& surface, const std::vector<double>& breaks,
                                const std::vector<BoundaryBand>& boundaries, size_t j,
                                const SlideBlock& fallback, const runout::BaseView& base,
                                const BlockParameters& p) {
  const double eps = 1e-9 * p.spacing;
  std::vector<Vec2> bottom, top;  // (s, d)
  std::vector<Vec2> pending_bottom, pending_top;  // empty columns after the last full one
  for (const double s : breaks) {
    const Column c = block_column(s, surface, boundaries, j);
    const double lo = std::min(c.lo, c.hi);
    if (c.lo <= c.hi + eps) {
      bottom.insert(bottom.end(), pending_bottom.begin(), pending_bottom.end());
      top.insert(top.end(), pending_top.begin(), pending_top.end());
      pending_bottom.clear();
      pending_top.clear();
      bottom.push_back({s, lo});
      top.push_back({s, c.hi});
    } else if (!bottom.empty()) {
      pending_bottom.push_back({s, lo});
      pending_top.push_back({s, lo});
    }
  }
  std::vector<Vec2> ring = bottom;
  ring.insert(ring.end(), top.rbegin(), top.rend());
  std::vector<Vec2> corners = corners_of(ring, p.spacing);
  if (corners.size() < 3) corners = {{fallback.start_s, 0}, {fallback.end_s, 0},
                                     {fallback.end_s, fallback.top}, {fallback.start_s, fallback.top}};
  for (Vec2& q : corners) {
    const runout::BaseFrame f = runout::base_frame_at(base, q.x);
    q = {f.x + q.y * f.nx, f.y + q.y * f.ny};
  }
  return corners;
}

SlideBlock measure_block(const std::vector<int>& members, const std::vector<runout::BasePoint>& at,
                         const std::vector<double>& displacement, const BlockParameters& p) {
  const double half = 0.5 * p.spacing;
  SlideBlock block;
  block.particles = static_cast<int>(members.size());
  block.start_s = std::numeric_limits<double>::infinity();
  block.end_s = block.top = -std::numeric_limits<double>::infinity();
  for (const int i : members) {
    block.start_s = std::min(block.start_s, at[i].s - half);
    block.end_s = std::max(block.end_s, at[i].s + half);
    block.top = std::max(block.top, at[i].d + half);
    block.displacement += displacement[i];
  }
  block.displacement /= block.particles;
  block.width = block.end_s - block.start_s;
  return block;
}

}  // namespace

const char* block_type_name(BlockType type) {
  switch (type) {
    case BlockType::Horst:
      return "horst";
    case BlockType::Graben:
      return "graben";
    case BlockType::Block:
      break;
  }
  return "block";
}

std::vector<SlideBlock> find_blocks(const std::vector<Vec2>& points,
                                    const std::vector<double>& displacement,
                                    const std::vector<ShearBand>& bands, const runout::BaseView& base,
                                    const BlockParameters& parameters) {
  if (points.empty() || bands.empty() || parameters.spacing <= 0) return {};
  std::vector<runout::BasePoint> at(points.size());
  double s_min = std::numeric_limits<double>::infinity(), s_max = -s_min;
  for (size_t i = 0; i < points.size(); ++i) {
    at[i] = runout::locate_on_base(base, points[i].x, points[i].y);
    s_min = std::min(s_min, at[i].s);
    s_max = std::max(s_max, at[i].s);
  }
  BinnedHeights heights(s_min, parameters.outline_bin * parameters.spacing, s_max);
  for (const runout::BasePoint& c : at) heights.add(c.s, c.d);

  const std::vector<BoundaryBand> boundaries = boundary_bands(bands, at, heights, base, parameters);
  if (boundaries.empty()) return {};
  const double half = 0.5 * parameters.spacing;
  const Surface surface = upper_surface(points, base, s_min - half, s_max + half, parameters);
  const std::vector<double> breaks = outline_breaks(surface, boundaries);
  std::vector<std::vector<int>> members(boundaries.size() + 1);
  for (size_t i = 0; i < points.size(); ++i) {
    const int j = block_of(at[i], boundaries);
    if (j >= 0) members[j].push_back(static_cast<int>(i));
  }

  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<SlideBlock> blocks;
  for (size_t j = 0; j < members.size(); ++j) {
    if (members[j].empty()) continue;  // two boundary lines that cross above the slide
    SlideBlock block = measure_block(members[j], at, displacement, parameters);
    block.outline = block_outline(surface, breaks, boundaries, j, block, base, parameters);
    const BoundaryBand* left = j > 0 ? &boundaries[j - 1] : nullptr;
    const BoundaryBand* right = j < boundaries.size() ? &boundaries[j] : nullptr;
    block.type = classify(left, right, parameters.dip_tolerance);
    block.left_band = left ? left->band : -1;
    block.right_band = right ? right->band : -1;
    block.left_dip = left ? left->dip : nan;
    block.right_dip = right ? right->dip : nan;
    blocks.push_back(std::move(block));
  }
  for (size_t j = 0; j < blocks.size(); ++j) {
    double sum = 0;
    int neighbours = 0;
    if (j > 0) sum += blocks[j - 1].top, ++neighbours;
    if (j + 1 < blocks.size()) sum += blocks[j + 1].top, ++neighbours;
    blocks[j].relief = neighbours > 0 ? blocks[j].top - sum / neighbours : nan;
  }
  return blocks;
}

}  // namespace runout::analysis
