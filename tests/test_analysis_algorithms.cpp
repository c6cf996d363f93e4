// The analysis' algorithms (runout_analysis, no VTK): plastic strain, shear
// bands and horsts and grabens on synthetic particle lattices whose answers
// are known, the morphology rule on plain profiles and slabs, the frame
// checks, and the columns the filters and `runout analyse` share. The VTK
// classes that wrap them are tested in test_strain_filters.cpp and
// test_morphology_filter.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "csv_table.hpp"
#include "lattice_fixtures.hpp"
#include "runout/analysis/frame_base.hpp"
#include "runout/analysis/frame_checks.hpp"
#include "runout/analysis/horst_graben.hpp"
#include "runout/analysis/morphology_rules.hpp"
#include "runout/analysis/plastic_strain.hpp"
#include "runout/analysis/result_columns.hpp"
#include "runout/analysis/shear_bands.hpp"
#include "runout/scene/polygon.hpp"

using namespace runout::analysis;
using namespace runout::lattice_fixtures;

namespace {

// Turned by `angle` degrees about the origin.
std::vector<Vec2> rotated(const std::vector<Vec2>& points, double angle) {
  const double c = std::cos(angle * kPi / 180), s = std::sin(angle * kPi / 180);
  std::vector<Vec2> out;
  for (const Vec2& p : points) out.push_back({c * p.x - s * p.y, s * p.x + c * p.y});
  return out;
}

runout::Base x_axis() { return x_axis_base(); }

BandParameters band_parameters(double h) {
  BandParameters p;
  p.spacing = h;
  return p;
}

std::vector<ShearBand> bands_of(const Lattice& lattice, const BandParameters& p,
                                const runout::Base& base = x_axis()) {
  return find_shear_bands(lattice.points, lattice.xi, base.view(), p);
}

}  // namespace

// ---------------------------------------------------------------- plastic strain

TEST(StrainAlgorithms, IncrementMatchesParticlesById) {
  const StrainById previous = strain_by_id({7, 3, 5}, {1.0, 2.0, 0.5});
  const std::vector<double> increment =
      strain_increment({5, 7, 3, 9}, {0.75, 1.5, 2.0, 4.0}, &previous);
  EXPECT_EQ(increment, (std::vector<double>{0.25, 0.5, 0.0, 0.0}));  // id 9 is new: 0
  EXPECT_EQ(strain_increment({1, 2}, {3.0, 4.0}, nullptr), (std::vector<double>{0.0, 0.0}));
}

TEST(StrainAlgorithms, NormalisedByXi95ElseByLargest) {
  EXPECT_EQ(normalised_strain({1.0, 2.5}, 5.0), (std::vector<double>{0.2, 0.5}));
  EXPECT_EQ(normalised_strain({1.0, 4.0}, 0.0), (std::vector<double>{0.25, 1.0}));
  EXPECT_EQ(normalised_strain({0.0, 0.0}, 0.0), (std::vector<double>{0.0, 0.0}));
  EXPECT_TRUE(normalised_strain({}, 0.0).empty());
}

TEST(StrainAlgorithms, GridCoversPointsOnMultiplesOfItsSpacing) {
  const GridSpec grid = grid_covering({{0.3, -0.7}, {2.1, 1.2}}, 0.5);
  EXPECT_DOUBLE_EQ(grid.origin.x, 0.0);
  EXPECT_DOUBLE_EQ(grid.origin.y, -1.0);
  EXPECT_EQ(grid.nx, 6);  // 0 .. 2.5
  EXPECT_EQ(grid.ny, 6);  // -1 .. 1.5
  EXPECT_EQ(grid_covering({}, 0.5).nx, 0);
}

TEST(StrainAlgorithms, UniformFieldProjectsExactly) {
  Slab slab;
  slab.length = 4;
  slab.height = 2;
  const Lattice lattice = make_lattice(slab);
  const std::vector<double> field(lattice.points.size(), 0.7);
  std::vector<double> ramp;
  for (const Vec2& p : lattice.points) ramp.push_back(3 * p.x - p.y);
  GridSpec grid = grid_covering(lattice.points, 0.2);
  grid.nx += 10;  // nodes beyond the slab's reach
  const GridProjection out = project_to_grid(lattice.points, {&field, &ramp}, grid, 0.4);
  int covered = 0;
  for (int j = 0; j < grid.ny; ++j)
    for (int i = 0; i < grid.nx; ++i) {
      const size_t node = i + static_cast<size_t>(grid.nx) * j;
      const double x = grid.origin.x + i * grid.spacing, y = grid.origin.y + j * grid.spacing;
      if (!out.coverage[node]) {
        EXPECT_GT(x, slab.length) << "an inner node without particles";
        EXPECT_EQ(out.fields[0][node], 0.0);
        continue;
      }
      ++covered;
      EXPECT_NEAR(out.fields[0][node], 0.7, 1e-12);
      // A symmetric kernel reproduces a linear field where it is whole.
      if (x > 0.5 && x < slab.length - 0.5 && y > 0.5 && y < slab.height - 0.5) {
        EXPECT_NEAR(out.fields[1][node], 3 * x - y, 1e-9);
      }
    }
  EXPECT_GT(covered, 200);
}

// ---------------------------------------------------------------- shear bands

TEST(ShearBands, OneBandAtKnownDipAndWidth) {
  for (const double dip : {45.0, -45.0, 60.0}) {
    Slab slab;
    slab.bands = {{10.0, dip, 0.5}};
    const Lattice lattice = make_lattice(slab);
    const std::vector<ShearBand> bands = bands_of(lattice, band_parameters(slab.h));
    ASSERT_EQ(bands.size(), 1u) << dip;
    const ShearBand& band = bands[0];
    EXPECT_NEAR(band.dip, dip, 2.0);
    EXPECT_NEAR(band.thickness, 0.5, slab.h) << dip;
    // Through the slab's height, plus the band's slanted ends.
    const double through = slab.height / std::sin(std::abs(dip) * kPi / 180) +
                           0.5 / std::tan(std::abs(dip) * kPi / 180);
    EXPECT_NEAR(band.length, through, 0.2) << dip;
    const double mid_x = 10.0 + 0.5 * slab.height / std::tan(dip * kPi / 180);
    EXPECT_NEAR(band.centroid.x, mid_x, 0.1);
    EXPECT_NEAR(band.centroid.y, 2.5, 0.1);
    EXPECT_NEAR(band.centroid_s, band.centroid.x, 1e-12);
    EXPECT_DOUBLE_EQ(band.mean_strain, 10.0);
    EXPECT_DOUBLE_EQ(band.peak_strain, 10.0);
    // The skeleton runs along the band's middle, rear to front; its end
    // bins hold the corners of the band's slanted ends.
    ASSERT_GE(band.skeleton.size(), 10u);
    for (size_t k = 0; k < band.skeleton.size(); ++k) {
      const bool end = k < 2 || k + 2 >= band.skeleton.size();
      EXPECT_LT(distance_to(slab.bands[0], slab.height, band.skeleton[k]), end ? 0.25 : 0.05);
    }
    EXPECT_LT(band.skeleton.front().x, band.skeleton.back().x);
  }
}

TEST(ShearBands, DipIsMeasuredAgainstTheBase) {
  // The whole slab on a base turned 10 degrees down: same band, same dip.
  Slab slab;
  slab.bands = {{10.0, 45.0, 0.5}};
  Lattice lattice = make_lattice(slab);
  lattice.points = rotated(lattice.points, -10.0);
  runout::BaseSpec spec;
  spec.kind = runout::BaseKind::Polyline;
  const std::vector<Vec2> ends = rotated({{0, 0}, {40, 0}}, -10.0);
  for (const Vec2& e : ends) spec.points.emplace_back(e.x, e.y);
  const std::vector<ShearBand> bands =
      bands_of(lattice, band_parameters(slab.h), runout::Base(spec, 0.0));
  ASSERT_EQ(bands.size(), 1u);
  EXPECT_NEAR(bands[0].dip, 45.0, 2.0);
  EXPECT_NEAR(bands[0].centroid_s, 12.5, 0.1);
}

TEST(ShearBands, ThresholdModes) {
  Slab slab;
  slab.bands = {{10.0, 45.0, 0.5}};
  const Lattice lattice = make_lattice(slab);
  BandParameters p = band_parameters(slab.h);
  p.threshold.mode = ThresholdMode::Absolute;
  p.threshold.absolute = 1.0;
  EXPECT_EQ(bands_of(lattice, p).size(), 1u);
  p.threshold.absolute = 10.0;  // strictly above: the band's own value is not enough
  EXPECT_EQ(bands_of(lattice, p).size(), 0u);
  p.threshold.mode = ThresholdMode::RelativeToReference;
  p.threshold.relative = 0.5;
  p.threshold.reference = 5.0;
  EXPECT_DOUBLE_EQ(threshold_value(lattice.xi, p.threshold), 2.5);
  EXPECT_EQ(bands_of(lattice, p).size(), 1u);
  p.threshold.relative = 3.0;
  EXPECT_EQ(bands_of(lattice, p).size(), 0u);
  p.threshold.mode = ThresholdMode::Percentile;
  p.threshold.percentile = 50;
  EXPECT_DOUBLE_EQ(threshold_value(lattice.xi, p.threshold), 0.05);
  EXPECT_EQ(threshold_value({4.0, 1.0, 3.0, 2.0}, p.threshold), 2.0);  // nearest rank
  EXPECT_EQ(bands_of(lattice, p).size(), 1u);
}

TEST(ShearBands, NoPlasticStrainNoBands) {
  Slab slab;
  slab.background_xi = 0.0;
  const Lattice lattice = make_lattice(slab);  // no band lines: all zero
  EXPECT_TRUE(bands_of(lattice, band_parameters(slab.h)).empty());
  EXPECT_TRUE(find_shear_bands({}, {}, x_axis().view(), band_parameters(0.1)).empty());
  EXPECT_TRUE(find_shear_bands({{1, 1}}, {3.0}, x_axis().view(), band_parameters(0.1)).empty());
}

TEST(ShearBands, SmallClustersAreDropped) {
  Slab slab;
  Lattice lattice = make_lattice(slab);
  for (size_t i = 0; i < lattice.points.size(); ++i)
    if (std::abs(lattice.points[i].x - 5) < 0.11 && std::abs(lattice.points[i].y - 2) < 0.11)
      lattice.xi[i] = 10;  // a 2 x 2 patch
  EXPECT_TRUE(bands_of(lattice, band_parameters(slab.h)).empty());
  BandParameters p = band_parameters(slab.h);
  p.min_particles = 4;
  EXPECT_EQ(bands_of(lattice, p).size(), 1u);
}

TEST(ShearBands, BandsThatMeetAreSeparated) {
  // A V (the flanks of a graben meeting at the base) and a band rooted in a
  // basal shear zone along the whole slab.
  Slab slab;
  slab.length = 30;
  slab.bands = {{5.0, 45.0, 0.4}, {15.0, -45.0, 0.4}, {25.0, 45.0, 0.4}};
  Lattice lattice = make_lattice(slab);
  for (size_t i = 0; i < lattice.points.size(); ++i)
    if (lattice.points[i].y < 0.3) lattice.xi[i] = 10;
  BandParameters p = band_parameters(slab.h);
  p.threshold.mode = ThresholdMode::Absolute;  // the bands hold more than a tenth
  const std::vector<ShearBand> bands = bands_of(lattice, p);
  ASSERT_EQ(bands.size(), 4u);
  std::vector<double> dips;
  for (const ShearBand& b : bands)
    if (std::abs(b.dip) > 10) dips.push_back(b.dip);
  ASSERT_EQ(dips.size(), 3u);
  EXPECT_NEAR(dips[0], 45, 3);
  EXPECT_NEAR(dips[1], -45, 3);
  EXPECT_NEAR(dips[2], 45, 3);
  const auto basal = std::find_if(bands.begin(), bands.end(),
                                  [](const ShearBand& b) { return std::abs(b.dip) < 2; });
  ASSERT_NE(basal, bands.end());
  EXPECT_GT(basal->length, 25.0);

  // On distance alone they are one cluster.
  p.max_angle = 90;
  EXPECT_EQ(bands_of(lattice, p).size(), 1u);
}

// ---------------------------------------------------------------- horsts and grabens

namespace {

BlockParameters block_parameters(double h) {
  BlockParameters p;
  p.spacing = h;
  return p;
}

std::vector<SlideBlock> blocks_of_lattice(const Lattice& lattice, double h) {
  const runout::Base base = x_axis();
  const std::vector<ShearBand> bands =
      find_shear_bands(lattice.points, lattice.xi, base.view(), band_parameters(h));
  const std::vector<double> displacement(lattice.points.size(), 1.5);
  return find_blocks(lattice.points, displacement, bands, base.view(), block_parameters(h));
}

// Sign changes of the vertical direction along a closed outline, going
// round once: 2 for an outline whose top and bottom each run one way.
int vertical_reversals(const std::vector<Vec2>& outline) {
  std::vector<int> signs;
  for (size_t k = 0; k < outline.size(); ++k) {
    const double dy = outline[(k + 1) % outline.size()].y - outline[k].y;
    if (std::abs(dy) > 1e-9) signs.push_back(dy > 0 ? 1 : -1);
  }
  int reversals = 0;
  for (size_t k = 0; k < signs.size(); ++k) reversals += signs[k] != signs[(k + 1) % signs.size()];
  return reversals;
}

double outline_length(const std::vector<Vec2>& outline) {
  double length = 0;
  for (size_t k = 0; k < outline.size(); ++k) {
    const Vec2 a = outline[k], b = outline[(k + 1) % outline.size()];
    length += std::hypot(b.x - a.x, b.y - a.y);
  }
  return length;
}

double outline_area(const std::vector<Vec2>& outline) {
  double area = 0;
  for (size_t k = 0; k < outline.size(); ++k) {
    const Vec2 a = outline[k], b = outline[(k + 1) % outline.size()];
    area += 0.5 * (a.x * b.y - b.x * a.y);
  }
  return area;
}

std::string outline_defect_of(const std::vector<Vec2>& outline) {
  runout::Polygon polygon;
  for (const Vec2& v : outline) polygon.emplace_back(v.x, v.y);
  return runout::outline_defect(polygon);
}

// The lattice without the particles for which `drop` is true.
Lattice without(const Lattice& full, const std::function<bool(Vec2)>& drop) {
  Lattice lattice;
  for (size_t i = 0; i < full.points.size(); ++i) {
    if (drop(full.points[i])) continue;
    lattice.points.push_back(full.points[i]);
    lattice.xi.push_back(full.xi[i]);
  }
  return lattice;
}

bool has_vertex_near(const std::vector<Vec2>& outline, Vec2 q, double tolerance) {
  return std::any_of(outline.begin(), outline.end(), [&](const Vec2& v) {
    return std::hypot(v.x - q.x, v.y - q.y) <= tolerance;
  });
}

std::vector<SlideBlock> blocks_of(const Slab& slab) { return blocks_of_lattice(make_lattice(slab), slab.h); }

// / and \: a wedge 4 m wide at the top, 14 m at the base, raised 0.5 m
// (narrowing on upwards between the flanks).
Slab horst_slab() {
  Slab slab;
  slab.length = 40;
  slab.bands = {{18.0, -45.0, 0.4}, {22.0, 45.0, 0.4}};
  slab.top = [](double x) { return x > 18.5 && x < 21.5 ? 5.5 : 5.0; };
  return slab;
}

}  // namespace

TEST(HorstGraben, HorstBetweenBandsDippingAway) {
  const Slab slab = horst_slab();
  const std::vector<SlideBlock> blocks = blocks_of(slab);
  ASSERT_EQ(blocks.size(), 3u);
  EXPECT_EQ(blocks[0].type, BlockType::Block);
  EXPECT_EQ(blocks[1].type, BlockType::Horst);
  EXPECT_EQ(blocks[2].type, BlockType::Block);
  const SlideBlock& horst = blocks[1];
  EXPECT_NEAR(horst.left_dip, -45, 2);
  EXPECT_NEAR(horst.right_dip, 45, 2);
  EXPECT_EQ(horst.left_band, 0);
  EXPECT_EQ(horst.right_band, 1);
  EXPECT_NEAR(horst.start_s, 13.0, 0.3);  // the flanks at the base
  EXPECT_NEAR(horst.end_s, 27.0, 0.3);
  EXPECT_NEAR(horst.width, 14.0, 0.5);
  EXPECT_NEAR(horst.top, 5.5, 1e-9);
  EXPECT_NEAR(horst.relief, 0.5, 1e-9);
  EXPECT_NEAR(horst.displacement, 1.5, 1e-12);
  EXPECT_NEAR(blocks[0].start_s, 0.0, 1e-9);
  EXPECT_NEAR(blocks[2].end_s, 40.0, 1e-9);
  EXPECT_TRUE(std::isnan(blocks[0].left_dip));
  EXPECT_NEAR(blocks[0].right_dip, -45, 2);
  EXPECT_NEAR(blocks[0].relief, -0.5, 1e-9);  // against the horst alone
  EXPECT_EQ(std::string(block_type_name(horst.type)), "horst");

  // The outline: a closed polygon around the horst's particles.
  ASSERT_GE(horst.outline.size(), 8u);
  const double area = outline_area(horst.outline);
  EXPECT_NEAR(area, horst.particles * slab.h * slab.h, 0.1 * area);  // counter-clockwise
}

TEST(HorstGraben, OutlinesFollowTheSurfaceNotTheGapsBetweenColumns) {
  // The horst's slab with its particle columns drawn apart as a spreading
  // slide leaves them: of every four columns, two have lost their top
  // 0.3 m. The outlines must follow the slide's surface (flat, with the
  // horst's raised top) and the bands, not comb down into the gaps.
  const Slab slab = horst_slab();
  const std::vector<SlideBlock> blocks =
      blocks_of_lattice(without(make_lattice(slab),
                                [&](Vec2 q) {
                                  const int column = static_cast<int>(q.x / slab.h);
                                  return (column / 2) % 2 == 1 && q.y > slab.top(q.x) - 3 * slab.h;
                                }),
                        slab.h);
  ASSERT_EQ(blocks.size(), 3u);
  ASSERT_EQ(blocks[1].type, BlockType::Horst);
  for (const SlideBlock& block : blocks) {
    ASSERT_GE(block.outline.size(), 4u);
    EXPECT_EQ(outline_defect_of(block.outline), "") << block.start_s;
    // The old outline stepped down and up at every other bin: dozens of
    // reversals, and longer than the box around the block.
    EXPECT_LE(vertical_reversals(block.outline), 2) << block.start_s;
    EXPECT_LT(outline_length(block.outline), 2 * (block.width + block.top)) << block.start_s;
    for (const Vec2& v : block.outline) {
      EXPECT_GE(v.y, -1e-9);
      EXPECT_LE(v.y, block.top + 1e-9);  // no higher than the surface over the block
    }
  }
  // The horst's flanks are its bands: from the base at 13 m and 27 m up to
  // where they meet the surface, 5 m high, at 18 m and 22 m; the blocks
  // beside it share those edges.
  const SlideBlock& horst = blocks[1];
  for (const Vec2 corner : {Vec2{13, 0}, Vec2{27, 0}, Vec2{18, 5}, Vec2{22, 5}}) {
    EXPECT_TRUE(has_vertex_near(horst.outline, corner, 0.3)) << corner.x << ", " << corner.y;
    for (const Vec2& v : horst.outline) {
      if (std::hypot(v.x - corner.x, v.y - corner.y) > 0.3) continue;
      EXPECT_TRUE(has_vertex_near(blocks[corner.x < 20 ? 0 : 2].outline, v, 1e-9))
          << v.x << ", " << v.y;
    }
  }
}

TEST(HorstGraben, OutlineAcrossAGapRunsAlongTheBase) {
  // The rear block of the horst's slab with its particles between 5 m and
  // 7 m gone (ten bins: wider than the surface's closing): one block whose
  // outline encloses its two parts and runs along the base between them.
  const Slab slab = horst_slab();
  const Lattice lattice = without(make_lattice(slab), [](Vec2 q) { return q.x > 5 && q.x < 7; });
  const std::vector<SlideBlock> blocks = blocks_of_lattice(lattice, slab.h);
  ASSERT_EQ(blocks.size(), 3u);
  const SlideBlock& rear = blocks[0];
  EXPECT_NEAR(outline_area(rear.outline), rear.particles * slab.h * slab.h,
              0.05 * outline_area(rear.outline));
  bool on_base_in_gap = false;
  for (const Vec2& v : rear.outline) {
    EXPECT_TRUE(std::isfinite(v.x) && std::isfinite(v.y));
    EXPECT_GE(v.y, -1e-9);
    if (v.x > 5.2 && v.x < 6.8) {
      EXPECT_NEAR(v.y, 0, 1e-9);
      on_base_in_gap = true;
    }
  }
  EXPECT_TRUE(on_base_in_gap || has_vertex_near(rear.outline, {5.0, 0.0}, 0.3));
}

TEST(HorstGraben, GrabenBetweenBandsConvergingDownwards) {
  // \ and /, meeting at the base: a V-shaped wedge dropped 0.5 m.
  Slab slab;
  slab.length = 40;
  slab.bands = {{15.0, 45.0, 0.4}, {25.0, -45.0, 0.4}};
  slab.top = [](double x) { return x > 15 && x < 25 ? 4.5 : 5.0; };
  const std::vector<SlideBlock> blocks = blocks_of(slab);
  ASSERT_EQ(blocks.size(), 3u);
  EXPECT_EQ(blocks[0].type, BlockType::Block);
  EXPECT_EQ(blocks[1].type, BlockType::Graben);
  EXPECT_EQ(blocks[2].type, BlockType::Block);
  const SlideBlock& graben = blocks[1];
  EXPECT_NEAR(graben.left_dip, 45, 2);
  EXPECT_NEAR(graben.right_dip, -45, 2);
  EXPECT_NEAR(graben.start_s, 15.5, 0.2);  // the flanks at its top, 4.5 m high
  EXPECT_NEAR(graben.end_s, 24.5, 0.2);
  EXPECT_NEAR(graben.top, 4.5, 1e-9);
  EXPECT_NEAR(graben.relief, -0.5, 1e-9);
  EXPECT_EQ(std::string(block_type_name(graben.type)), "graben");
}

TEST(HorstGraben, ParallelBandsAndSingleBandMakePlainBlocks) {
  Slab slab;
  slab.length = 40;
  slab.bands = {{15.0, 45.0, 0.4}, {25.0, 45.0, 0.4}};
  std::vector<SlideBlock> blocks = blocks_of(slab);
  ASSERT_EQ(blocks.size(), 3u);
  for (const SlideBlock& b : blocks) EXPECT_EQ(b.type, BlockType::Block);
  EXPECT_NEAR(blocks[1].relief, 0.0, 1e-9);

  slab.bands = {{20.0, 45.0, 0.4}};
  blocks = blocks_of(slab);
  ASSERT_EQ(blocks.size(), 2u);
  EXPECT_EQ(blocks[0].type, BlockType::Block);
  EXPECT_EQ(blocks[1].type, BlockType::Block);
  EXPECT_TRUE(std::isnan(blocks[1].right_dip));
}

TEST(HorstGraben, BandsThatDoNotCutTheSlideMakeNoBlocks) {
  Slab slab;
  slab.background_xi = 0;
  EXPECT_TRUE(blocks_of(slab).empty());  // no bands at all
  // A basal shear zone (parallel to the base) and a buried band.
  Lattice lattice = make_lattice(slab);
  for (size_t i = 0; i < lattice.points.size(); ++i) {
    const Vec2 p = lattice.points[i];
    if (p.y < 0.3 || (std::abs(p.x - 10 - (3 - p.y)) < 0.2 && p.y > 1 && p.y < 3)) lattice.xi[i] = 10;
  }
  const runout::Base base = x_axis();
  const std::vector<ShearBand> bands =
      find_shear_bands(lattice.points, lattice.xi, base.view(), band_parameters(slab.h));
  EXPECT_EQ(bands.size(), 2u);
  const std::vector<double> displacement(lattice.points.size(), 0.0);
  EXPECT_TRUE(
      find_blocks(lattice.points, displacement, bands, base.view(), block_parameters(slab.h)).empty());
  EXPECT_TRUE(find_blocks({}, {}, bands, base.view(), block_parameters(slab.h)).empty());
}

// ---------------------------------------------------------------- morphology

namespace {

constexpr double kRuleSpacing = 0.25;

// The arrays of a frame (as VTK stores them) of the slab [0, 40] x [0, 4] on
// the lattice of kRuleSpacing, seeded at rest and moved dx along the planar
// base at velocity vx.
struct SlabArrays {
  std::vector<double> xyz, velocity, mass, initial;
};

SlabArrays translated_slab(double dx, double vx) {
  SlabArrays a;
  for (int i = 0; i < 160; ++i)
    for (int j = 0; j < 16; ++j) {
      const double x0 = (i + 0.5) * kRuleSpacing, y0 = (j + 0.5) * kRuleSpacing;
      a.xyz.insert(a.xyz.end(), {x0 + dx, y0, 0.0});
      a.velocity.insert(a.velocity.end(), {vx, 0.0, 0.0});
      a.mass.push_back(600.0 * kRuleSpacing * kRuleSpacing);
      a.initial.insert(a.initial.end(), {x0, y0, 0.0});
    }
  return a;
}

runout::Particles particles_of(const SlabArrays& a) {
  return morphology_particles(a.xyz, a.velocity, 3, a.mass, 1, a.initial, 3);
}

// The planar base as the engine writes it (base_points), read back.
runout::Base planar_base() { return *base_from_points({-10.0, 0.0, 0.0, 200.0, 0.0, 0.0}, 3); }

}  // namespace

TEST(MorphologyRules, ClosingFillsNarrowTroughsOnly) {
  const std::vector<double> t = {4, 4, 1, 4, 4, 4, 1, 1, 1, 1, 4, 4};
  const std::vector<double> closed = runout::analysis::close_profile(t, 1);
  const std::vector<double> want = {4, 4, 4, 4, 4, 4, 1, 1, 1, 1, 4, 4};
  EXPECT_EQ(closed, want);
  EXPECT_EQ(runout::analysis::close_profile(t, 0), t);
  EXPECT_TRUE(runout::analysis::close_profile({}, 3).empty());
}

TEST(MorphologyRules, GrabensAreDeepTroughsBetweenHorsts) {
  using runout::analysis::count_grabens;
  // Two grabens between horsts of the initial height 4.
  EXPECT_EQ(count_grabens({1, 4, 4, 2, 2, 4, 4, 1.5, 4, 4, 1}, kRuleSpacing, 4.0), 2);
  // A flat or repeated bottom is one graben.
  EXPECT_EQ(count_grabens({4, 2, 2, 2, 4}, kRuleSpacing, 4.0), 1);
  EXPECT_EQ(count_grabens({4, 2, 2.1, 2, 4}, kRuleSpacing, 4.0), 1);
  // Shallower than 20 % of the lower flank, or than 2 spacings.
  EXPECT_EQ(count_grabens({4, 3.3, 4}, kRuleSpacing, 4.0), 0);
  EXPECT_EQ(count_grabens({1.0, 0.6, 1.0}, kRuleSpacing, 1.0), 0);
  // Flanks thinner than half the initial height: a thinned sheet, no horsts.
  EXPECT_EQ(count_grabens({1.9, 0.5, 1.9}, kRuleSpacing, 4.0), 0);
  // A step down to the front is no trough; nor is a taper.
  EXPECT_EQ(count_grabens({4, 4, 2, 2, 2}, kRuleSpacing, 4.0), 0);
  EXPECT_EQ(count_grabens({1, 2, 3, 4, 3, 2, 1}, kRuleSpacing, 4.0), 0);
  EXPECT_EQ(count_grabens({}, kRuleSpacing, 4.0), 0);
}

TEST(MorphologyRules, MechanismRuleInItsOrder) {
  using runout::analysis::classify_mechanism;
  using E = runout::analysis::MechanismEvidence;
  EXPECT_EQ(classify_mechanism(E{1.0, 1.0, 0.5, 0, 0}), Mechanism::BlockSliding);
  EXPECT_EQ(classify_mechanism(E{1.14, 0.81, 0.1, 0, 0}), Mechanism::BlockSliding);
  EXPECT_EQ(classify_mechanism(E{1.15, 0.9, 0.5, 0, 0}), Mechanism::Elongation);
  EXPECT_EQ(classify_mechanism(E{1.5, 0.6, 0.5, 0, 0}), Mechanism::Elongation);
  EXPECT_EQ(classify_mechanism(E{1.5, 0.9, 0.5, 1, 0}), Mechanism::Spreading);
  EXPECT_EQ(classify_mechanism(E{1.0, 1.0, 0.5, 2, 0}), Mechanism::Spreading);
  // Troughs the slide had from the start are not grabens that formed.
  EXPECT_EQ(classify_mechanism(E{1.0, 1.0, 0.5, 1, 1}), Mechanism::BlockSliding);
  // Not moved yet; thinned in place; no data.
  EXPECT_EQ(classify_mechanism(E{1.0, 1.0, 0.05, 0, 0}), Mechanism::Undetermined);
  EXPECT_EQ(classify_mechanism(E{1.1, 0.7, 0.5, 0, 0}), Mechanism::Undetermined);
  EXPECT_EQ(classify_mechanism(E{NAN, 1.0, 0.5, 0, 0}), Mechanism::Undetermined);
  EXPECT_STREQ(runout::analysis::mechanism_name(Mechanism::BlockSliding), "block sliding");
  EXPECT_STREQ(runout::analysis::mechanism_name(Mechanism::Undetermined), "undetermined");
}

// With the travel of its series the class reads how the slide moved after
// its start: a block whose faces slumped (L / L0 = 1.6, Hmax / H0 = 0.6,
// case 3's numbers) is block sliding, not elongation.
TEST(MorphologyRules, LateStretchDecidesBetweenBlockAndElongation) {
  using runout::analysis::classify_mechanism;
  using E = runout::analysis::MechanismEvidence;
  EXPECT_EQ(classify_mechanism(E{1.6, 0.6, 5.0, 0, 0, 0.02}), Mechanism::BlockSliding);
  EXPECT_EQ(classify_mechanism(E{1.6, 0.6, 5.0, 0, 0, 0.49}), Mechanism::BlockSliding);
  EXPECT_EQ(classify_mechanism(E{1.1, 0.9, 0.4, 0, 0, 0.5}), Mechanism::Elongation);
  EXPECT_EQ(classify_mechanism(E{1.1, 0.9, 0.4, 1, 0, 0.0}), Mechanism::Spreading);
  EXPECT_EQ(classify_mechanism(E{1.5, 0.6, 0.05, 0, 0, 1.0}), Mechanism::Undetermined);
}

TEST(MorphologyRules, LateStretchOverTheSecondHalfOfTheTravel) {
  using runout::analysis::late_stretch;
  // A block of 50 m that grew to 80 m over its first 20 m of travel, then
  // slid 80 m more at that length: none of the late travel stretched it.
  EXPECT_NEAR(late_stretch({{0, 50}, {20, 80}, {60, 80}, {100, 80}}), 0.0, 1e-12);
  // The rear held still while the toe ran 40 m: all of it.
  EXPECT_NEAR(late_stretch({{0, 50}, {10, 60}, {40, 90}}), 1.0, 1e-12);
  // Half the toe's speed at the rear: a half; L at R / 2 = 20 m
  // interpolated between the samples at 10 and 30 m (L = 55 and 65).
  EXPECT_NEAR(late_stretch({{0, 50}, {10, 55}, {30, 65}, {40, 70}}), 0.5, 1e-12);
  EXPECT_TRUE(std::isnan(late_stretch({{0, 50}})));
  EXPECT_TRUE(std::isnan(late_stretch({{0, 50}, {0, 50}})));
  EXPECT_TRUE(std::isnan(late_stretch({})));
}

// The recorded reference runs (docs/data, 0.1 m cells, 4 x 4 particles):
// case 2 is an elongation and case 3 block sliding by their histories'
// travel (measured: late stretch 1.00 and 0.020), though case 3 is 1.69
// times as long as it started. Their frames are not kept, so no grabens.
TEST(MorphologyRules, ReferenceRunsClassedByTheirTravel) {
  const auto evidence = [](const std::string& file) {
    const runout::csv_table::Table h = runout::csv_table::read_table(
        std::string(RUNOUT_SOURCE_DIR) + "/docs/data/" + file);
    std::vector<runout::analysis::TravelSample> travel;
    for (std::size_t k = 0; k < h.rows.size(); ++k)
      travel.push_back({h.number(k, "runout"), h.number(k, "length")});
    const std::size_t last = h.rows.size() - 1;
    runout::analysis::MechanismEvidence e;
    e.length_ratio = h.number(last, "length") / h.number(0, "length");
    e.thickness_ratio = h.number(last, "max_thickness") / h.number(0, "max_thickness");
    e.runout_ratio = h.number(last, "runout") / h.number(0, "length");
    e.late_stretch = runout::analysis::late_stretch(travel);
    std::printf("%s: L / L0 %.2f, Hmax / H0 %.2f, runout / L0 %.2f, late stretch %.3f\n",
                file.c_str(), e.length_ratio, e.thickness_ratio, e.runout_ratio, e.late_stretch);
    return e;
  };
  using runout::analysis::classify_mechanism;
  EXPECT_EQ(classify_mechanism(evidence("case2_0.1m_4x4_history.csv")), Mechanism::Elongation);
  EXPECT_EQ(classify_mechanism(evidence("case3_0.1m_4x4_cpu_history.csv")),
            Mechanism::BlockSliding);
}

TEST(MorphologyRules, TranslatedBlockFromItsArrays) {
  const runout::Particles p = particles_of(translated_slab(10.0, 2.0));
  ASSERT_EQ(p.size(), 160 * 16);
  const runout::Base base = planar_base();
  EXPECT_EQ(morphology_problem(p, base, kRuleSpacing, kProfileBinSpacings), "");
  const FrameMorphology m =
      measure_frame(p, base.view(), kRuleSpacing, kProfileBinSpacings * kRuleSpacing);
  EXPECT_DOUBLE_EQ(m.now.toe_s, 50.0);
  EXPECT_DOUBLE_EQ(m.initial.toe_s, 40.0);
  EXPECT_DOUBLE_EQ(m.runout, 10.0);
  EXPECT_DOUBLE_EQ(m.now.length, 40.0);
  EXPECT_NEAR(m.now.toe_velocity, 2.0, 1e-12);
  EXPECT_EQ(m.mechanism, Mechanism::BlockSliding);
  EXPECT_EQ(m.profile.bins.size(), 81u);  // bins of 2 spacings over 40 m, centred on the rear column
}

TEST(FrameChecks, MorphologyRefusesWhatItCannotMeasure) {
  const runout::Particles p = particles_of(translated_slab(10.0, 2.0));
  const std::optional<runout::Base> base = planar_base();
  auto problem = [&](const runout::Particles& q, const std::optional<runout::Base>& b,
                     double spacing) { return morphology_problem(q, b, spacing, 2.0, "mass"); };
  EXPECT_NE(problem(p, base, 0.0).find("\"particle_spacing\""), std::string::npos);
  EXPECT_NE(problem(p, base, std::nan("")).find("\"particle_spacing\""), std::string::npos);
  EXPECT_NE(problem(p, std::nullopt, kRuleSpacing).find("\"base_points\""), std::string::npos);
  runout::Particles massless = p;
  massless.mass[7] = 0.0;
  EXPECT_NE(problem(massless, base, kRuleSpacing).find("\"mass\""), std::string::npos);
  runout::Particles stray = p;
  stray.x[3] = 1e6;  // 4e6 bins of 0.5 m
  EXPECT_NE(problem(stray, base, kRuleSpacing).find("profile bins"), std::string::npos);
  runout::Particles far = p;
  far.x[3] = 1e9;  // beyond 2^30 spacings
  EXPECT_NE(problem(far, base, kRuleSpacing).find("2^30"), std::string::npos);
  runout::Particles far_initially = p;
  far_initially.x0[3] = 1e9;
  EXPECT_NE(problem(far_initially, base, kRuleSpacing).find("2^30"), std::string::npos);
  // A spacing of 1e300 m passes any reach in spacings; the reach in metres
  // still bounds the base geometry's arithmetic.
  const std::optional<runout::Base> far_base = base_from_points({-1e13, 0, 0, 1e13, 1, 0}, 3);
  ASSERT_TRUE(far_base);
  EXPECT_NE(problem(p, far_base, 1e300).find("10^12 m"), std::string::npos);
  runout::Particles far_out = p;
  far_out.x[3] = 2e12;
  EXPECT_NE(problem(far_out, base, 1e300).find("10^12 m"), std::string::npos);
  EXPECT_EQ(problem(runout::Particles(), base, kRuleSpacing), "");
}

TEST(FrameChecks, PointsAndPointArrays) {
  EXPECT_EQ(points_problem({0, 0, 0, 1, 1, 0}), "");
  EXPECT_EQ(points_problem({0, 0, 0, 1, NAN, 0}),
            "Point 1 has a coordinate that is not a finite number.");
  EXPECT_EQ(point_array_problem("mass", {1, 2, 3}, 1, 3, 1), "");
  EXPECT_EQ(point_array_problem("mass", {1, 2}, 1, 3, 1),
            "The point array \"mass\" has 2 tuples for 3 points.");
  EXPECT_EQ(point_array_problem("velocity", {1, 2, 3}, 1, 3, 3),
            "The point array \"velocity\" has 1 component(s), fewer than 3.");
  EXPECT_EQ(point_array_problem("velocity", {1, 0, 2, INFINITY}, 2, 2, 2),
            "The point array \"velocity\" has a value that is not a finite number at point 1.");
  EXPECT_NE(point_array_problem("particle_id", {1e19}, 1, 1, 1, kParticleIdLimit).find("within +-"),
            std::string::npos);
  EXPECT_EQ(extent_problem({{0, 0}, {1e6, 2}}, 0.1), "");
  EXPECT_NE(extent_problem({{0, 0}, {1e9, 2}}, 0.1).find("2^30"), std::string::npos);
  EXPECT_EQ(extent_problem({{0, 0}, {-1e12, 2}}, 1e4), "");
  EXPECT_EQ(extent_problem({{0, 0}, {-2e12, 2}}, 1e4),
            "The points reach 2000000000000.000000 m from the origin, more than 10^12 m: not a "
            "Runout particle frame.");
}

TEST(FrameBase, ReadAsTheEngineWritesIt) {
  // Two points at one height: the planar base, s = x.
  const std::optional<runout::Base> planar = base_from_points({-10, 1, 0, 200, 1, 0}, 3);
  ASSERT_TRUE(planar);
  EXPECT_EQ(planar->kind(), runout::BaseKind::Planar);
  EXPECT_DOUBLE_EQ(runout::locate_on_base(planar->view(), 5.0, 3.0).d, 2.0);
  // More points, or two at different heights: a polyline, s the arc length.
  const std::optional<runout::Base> line = base_from_points({0, 0, 0, 3, -4, 0, 10, -4, 0}, 3);
  ASSERT_TRUE(line);
  EXPECT_EQ(line->kind(), runout::BaseKind::Polyline);
  EXPECT_NEAR(runout::locate_on_base(line->view(), 6.0, -4.0).s, 8.0, 1e-12);
  EXPECT_EQ(base_from_points({0, 0, 1, -1}, 2)->kind(), runout::BaseKind::Polyline);  // (x, y) tuples
  // Unusable: one point, one component, x not increasing, not finite.
  EXPECT_FALSE(base_from_points({0, 0, 0}, 3));
  EXPECT_FALSE(base_from_points({0, 1}, 1));
  EXPECT_FALSE(base_from_points({0, 0, 0, 0, 1, 0}, 3));
  EXPECT_FALSE(base_from_points({0, 0, 0, NAN, 1, 0}, 3));
  // Fuzzers' bases: a segment whose |e|^2 underflows to 0, one whose length overflows,
  // and one whose differences are finite but whose |e|^2 overflows.
  EXPECT_FALSE(base_from_points({0, 0, 0, 5.4e-311, 2e-323, 0}, 3));
  EXPECT_FALSE(base_from_points({-1.7e308, 0, 0, 1.7e308, 1, 0}, 3));
  EXPECT_FALSE(base_from_points({0, 0, 0, 1e308, 1e308, 0}, 3));
  EXPECT_EQ(x_axis_base().kind(), runout::BaseKind::Planar);
}

// ---------------------------------------------------------------- result columns

namespace {

template <class Item>
std::vector<std::string> names_of(const std::vector<Column<Item>>& columns) {
  std::vector<std::string> names;
  for (const Column<Item>& c : columns) names.push_back(c.name);
  return names;
}

}  // namespace

// The columns docs/filters.md defines, in its order: the filters' tables
// and `runout analyse` write these.
TEST(ResultColumns, NamesInTheDocumentedOrder) {
  EXPECT_EQ(names_of(band_columns()),
            (std::vector<std::string>{"centroid_x", "centroid_y", "centroid_s", "dip", "length",
                                      "thickness", "mean_strain", "peak_strain",
                                      "particle_count"}));
  EXPECT_EQ(names_of(block_columns()),
            (std::vector<std::string>{"type", "type_code", "start_s", "end_s", "width", "top",
                                      "relief", "left_dip", "right_dip", "left_band",
                                      "right_band", "displacement", "particle_count"}));
  EXPECT_EQ(names_of(morphology_columns()),
            (std::vector<std::string>{"toe", "rear", "length", "max_thickness", "runout",
                                      "toe_velocity", "centroid_x", "centroid_y", "centroid_s",
                                      "centroid_velocity", "outside_mass", "initial_toe",
                                      "length_ratio", "thickness_ratio", "late_stretch",
                                      "particles", "troughs", "initial_troughs",
                                      "mechanism_id", "mechanism"}));
}

TEST(ResultColumns, ValuesOfABandABlockAndAFrame) {
  ShearBand band;
  band.particles = {1, 2, 3};
  band.dip = -30.0;
  const auto& bands = band_columns();
  EXPECT_EQ(bands[3].number(band), -30.0);
  EXPECT_EQ(bands.back().kind, Column<ShearBand>::Int);
  EXPECT_EQ(bands.back().number(band), 3.0);

  SlideBlock block;
  block.type = BlockType::Graben;
  block.left_band = 4;
  EXPECT_EQ(block_columns()[0].text(block), "graben");
  EXPECT_EQ(block_columns()[1].number(block), 2.0);
  EXPECT_EQ(block_columns()[9].number(block), 4.0);

  // A frame without particles: NaN lengths, zero counts, undetermined.
  const FrameMorphology empty;
  for (const Column<FrameMorphology>& c : morphology_columns()) {
    SCOPED_TRACE(c.name);
    if (c.kind == Column<FrameMorphology>::Double) {
      EXPECT_TRUE(std::isnan(c.number(empty)));
    } else if (c.kind == Column<FrameMorphology>::Int) {
      EXPECT_EQ(c.number(empty), 0.0);
    }
  }
  EXPECT_EQ(morphology_columns().back().text(empty), "undetermined");
  FrameMorphology moved;
  moved.now.particles = 5;
  moved.runout = 2.5;
  moved.mechanism = Mechanism::Spreading;
  EXPECT_EQ(morphology_columns()[4].number(moved), 2.5);
  EXPECT_EQ(morphology_columns().back().text(moved), "spreading");
}
