#include "runout/analysis/horst_graben.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "runout/morphology.hpp"

namespace runout::analysis {

namespace {

constexpr double kDegree = 3.14159265358979323846 / 180;

// Per along-base bin of width `width` from s0: the lowest and highest d of
// the particles in it (an empty bin has lo > hi).
struct BinnedHeights {
  double s0 = 0, width = 1;
  std::vector<double> lo, hi;

  BinnedHeights(double s0_, double width_, double s_max) : s0(s0_), width(width_) {
    const size_t bins = static_cast<size_t>((s_max - s0) / width) + 1;
    lo.assign(bins, std::numeric_limits<double>::infinity());
    hi.assign(bins, -std::numeric_limits<double>::infinity());
  }
  size_t bin(double s) const {
    return std::min(lo.size() - 1, static_cast<size_t>(std::max(0.0, (s - s0) / width)));
  }
  void add(double s, double d) {
    const size_t b = bin(s);
    lo[b] = std::min(lo[b], d);
    hi[b] = std::max(hi[b], d);
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

// Closed outline of a block: in along-base bins, the bottom of its particles
// from rear to front, then their top from front to rear, each bin a flat
// step between its edges (half a spacing beyond the particle centres).
std::vector<Vec2> block_outline(const std::vector<int>& members,
                                const std::vector<runout::BasePoint>& at, const SlideBlock& block,
                                const runout::BaseView& base, const BlockParameters& p) {
  const double half = 0.5 * p.spacing;
  BinnedHeights heights(block.start_s, p.outline_bin * p.spacing, block.end_s);
  for (const int i : members) heights.add(at[i].s, at[i].d);
  std::vector<Vec2> ring, top;  // (s, d)
  for (size_t b = 0; b < heights.lo.size(); ++b) {
    if (heights.lo[b] > heights.hi[b]) continue;
    const double s_lo = heights.s0 + b * heights.width;
    const double s_hi = std::min(block.end_s, s_lo + heights.width);
    ring.push_back({s_lo, heights.lo[b] - half});
    ring.push_back({s_hi, heights.lo[b] - half});
    top.push_back({s_lo, heights.hi[b] + half});
    top.push_back({s_hi, heights.hi[b] + half});
  }
  ring.insert(ring.end(), top.rbegin(), top.rend());

  // Neighbouring bins at one height repeat a point or put one in the middle
  // of a straight edge: keep the corners only, which polygon triangulation
  // needs.
  std::vector<Vec2> corners;
  for (const Vec2& q : ring) {
    if (!corners.empty() && q.x == corners.back().x && q.y == corners.back().y) continue;
    if (corners.size() >= 2) {
      const Vec2 a = corners[corners.size() - 2], b = corners.back();
      if ((a.x == b.x && b.x == q.x) || (a.y == b.y && b.y == q.y)) corners.pop_back();
    }
    corners.push_back(q);
  }
  for (Vec2& q : corners) {
    const runout::BaseFrame f = runout::base_frame_at(base, q.x);
    q = {f.x + q.y * f.nx, f.y + q.y * f.ny};
  }
  return corners;
}

SlideBlock measure_block(const std::vector<int>& members, const std::vector<runout::BasePoint>& at,
                         const std::vector<double>& displacement, const runout::BaseView& base,
                         const BlockParameters& p) {
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
  block.outline = block_outline(members, at, block, base, p);
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
  BinnedHeights surface(s_min, parameters.outline_bin * parameters.spacing, s_max);
  for (const runout::BasePoint& c : at) surface.add(c.s, c.d);

  const std::vector<BoundaryBand> boundaries = boundary_bands(bands, at, surface, base, parameters);
  if (boundaries.empty()) return {};
  std::vector<std::vector<int>> members(boundaries.size() + 1);
  for (size_t i = 0; i < points.size(); ++i) {
    const int j = block_of(at[i], boundaries);
    if (j >= 0) members[j].push_back(static_cast<int>(i));
  }

  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<SlideBlock> blocks;
  for (size_t j = 0; j < members.size(); ++j) {
    if (members[j].empty()) continue;  // two boundary lines that cross above the slide
    SlideBlock block = measure_block(members[j], at, displacement, base, parameters);
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
