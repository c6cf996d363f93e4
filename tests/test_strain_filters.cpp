// The plastic strain, shear band and horst/graben filters: their plain
// algorithms on synthetic particle lattices whose answers are known, then
// the VTK classes (pipeline time, arrays, robustness).
#include <gtest/gtest.h>

#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkStringArray.h>
#include <vtkTable.h>
#include <vtkTypeInt64Array.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkUnstructuredGridAlgorithm.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "HorstGraben.h"
#include "ShearBands.h"
#include "StrainAlgorithms.h"
#include "filter_fixtures.hpp"
#include "vtkRunoutHorstGraben.h"
#include "vtkRunoutPlasticStrain.h"
#include "vtkRunoutShearBands.h"

using namespace runout::filters;
using runout::filter_fixtures::ErrorCounter;
using runout::filter_fixtures::value;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A straight band through (surface_x, top of the slab) at `dip` degrees to
// the base, positive descending towards +x, `width` thick.
struct BandLine {
  double surface_x, dip, width;
};

// A slab of particles on a square lattice of spacing h over [0, length] x
// [0, top(x)], the base the x axis; xi is band_xi within a band, else
// background_xi.
struct Slab {
  double length = 20, height = 5, h = 0.1;
  std::vector<BandLine> bands;
  double band_xi = 10, background_xi = 0.05;
  std::function<double(double)> top;  // default: height everywhere
};

struct Lattice {
  std::vector<Vec2> points;
  std::vector<double> xi;
};

double distance_to(const BandLine& b, double height, Vec2 q) {
  const double d = b.dip * kPi / 180;
  return std::abs((q.x - b.surface_x) * -std::sin(d) - (q.y - height) * std::cos(d));
}

Lattice make_lattice(const Slab& slab) {
  Lattice out;
  const int nx = static_cast<int>(std::lround(slab.length / slab.h));
  const int ny = static_cast<int>(std::lround(2 * slab.height / slab.h));  // room for a raised top
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Vec2 q{(i + 0.5) * slab.h, (j + 0.5) * slab.h};
      if (q.y > (slab.top ? slab.top(q.x) : slab.height)) continue;
      bool in_band = false;
      for (const BandLine& b : slab.bands) in_band |= distance_to(b, slab.height, q) <= b.width / 2;
      out.points.push_back(q);
      out.xi.push_back(in_band ? slab.band_xi : slab.background_xi);
    }
  return out;
}

// Turned by `angle` degrees about the origin.
std::vector<Vec2> rotated(const std::vector<Vec2>& points, double angle) {
  const double c = std::cos(angle * kPi / 180), s = std::sin(angle * kPi / 180);
  std::vector<Vec2> out;
  for (const Vec2& p : points) out.push_back({c * p.x - s * p.y, s * p.x + c * p.y});
  return out;
}

runout::Base x_axis() {
  runout::BaseSpec spec;
  spec.kind = runout::BaseKind::Planar;
  return runout::Base(spec, 0.0);
}

BandParameters band_parameters(double h) {
  BandParameters p;
  p.spacing = h;
  return p;
}

std::vector<ShearBand> bands_of(const Lattice& lattice, const BandParameters& p,
                                const runout::Base& base = x_axis()) {
  return find_shear_bands(lattice.points, lattice.xi, base.view(), p);
}

// What the engine writes, from a lattice: plastic_shear_strain,
// particle_id, displacement (0.9, 1.2, 0) and the field data
// particle_spacing and base_points (the x axis from 0 to 100), each
// optional.
struct FrameOptions {
  bool xi = true, ids = true, displacement = true, spacing = true, base = true;
};

vtkSmartPointer<vtkUnstructuredGrid> to_frame(const Lattice& lattice, double h,
                                              FrameOptions options = {}) {
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> points;
  vtkNew<vtkDoubleArray> xi, displacement;
  vtkNew<vtkTypeInt64Array> ids;
  xi->SetName("plastic_shear_strain");
  displacement->SetName("displacement");
  displacement->SetNumberOfComponents(3);
  ids->SetName("particle_id");
  for (size_t i = 0; i < lattice.points.size(); ++i) {
    points->InsertNextPoint(lattice.points[i].x, lattice.points[i].y, 0.0);
    xi->InsertNextValue(lattice.xi[i]);
    displacement->InsertNextTuple3(0.9, 1.2, 0.0);
    ids->InsertNextValue(static_cast<vtkTypeInt64>(i));
  }
  grid->SetPoints(points);
  if (options.xi) grid->GetPointData()->AddArray(xi);
  if (options.ids) grid->GetPointData()->AddArray(ids);
  if (options.displacement) grid->GetPointData()->AddArray(displacement);
  if (options.spacing) {
    vtkNew<vtkDoubleArray> spacing;
    spacing->SetName("particle_spacing");
    spacing->InsertNextValue(h);
    grid->GetFieldData()->AddArray(spacing);
  }
  if (options.base) {
    vtkNew<vtkDoubleArray> base;
    base->SetName("base_points");
    base->SetNumberOfComponents(3);
    base->InsertNextTuple3(0.0, 0.0, 0.0);
    base->InsertNextTuple3(100.0, 0.0, 0.0);
    grid->GetFieldData()->AddArray(base);
  }
  return grid;
}

const std::vector<std::string> kBandColumns = {
    "band_id",   "centroid_x", "centroid_y",  "centroid_s",  "dip",
    "length",    "thickness",  "mean_strain", "peak_strain", "particle_count"};
const std::vector<std::string> kBlockColumns = {
    "block_id", "type",      "type_code",  "start_s",      "end_s",
    "width",    "top",       "relief",     "left_dip",     "right_dip",
    "left_band", "right_band", "displacement", "particle_count"};

void expect_columns(vtkTable* table, const std::vector<std::string>& names) {
  ASSERT_EQ(table->GetNumberOfColumns(), static_cast<vtkIdType>(names.size()));
  for (const std::string& name : names) EXPECT_NE(table->GetColumnByName(name.c_str()), nullptr) << name;
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

std::vector<SlideBlock> blocks_of(const Slab& slab) {
  const Lattice lattice = make_lattice(slab);
  const runout::Base base = x_axis();
  const std::vector<ShearBand> bands =
      find_shear_bands(lattice.points, lattice.xi, base.view(), band_parameters(slab.h));
  const std::vector<double> displacement(lattice.points.size(), 1.5);
  return find_blocks(lattice.points, displacement, bands, base.view(), block_parameters(slab.h));
}

}  // namespace

TEST(HorstGraben, HorstBetweenBandsDippingAway) {
  // / and \: a wedge 4 m wide at the top, 14 m at the base, raised 0.5 m
  // (narrowing on upwards between the flanks).
  Slab slab;
  slab.length = 40;
  slab.bands = {{18.0, -45.0, 0.4}, {22.0, 45.0, 0.4}};
  slab.top = [](double x) { return x > 18.5 && x < 21.5 ? 5.5 : 5.0; };
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
  double area = 0;
  for (size_t k = 0; k < horst.outline.size(); ++k) {
    const Vec2 a = horst.outline[k], b = horst.outline[(k + 1) % horst.outline.size()];
    area += 0.5 * (a.x * b.y - b.x * a.y);
  }
  EXPECT_NEAR(area, horst.particles * slab.h * slab.h, 0.1 * area);  // counter-clockwise
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

// ---------------------------------------------------------------- VTK: plastic strain

namespace {

// A time series of frames: TIME_STEPS in the information pass, the frame of
// the largest step <= the requested time in the data pass.
class SeriesSource : public vtkUnstructuredGridAlgorithm {
 public:
  static SeriesSource* New();
  vtkTypeMacro(SeriesSource, vtkUnstructuredGridAlgorithm);

  std::vector<double> Times;
  std::function<vtkSmartPointer<vtkUnstructuredGrid>(double)> Frame;
  std::vector<double> Delivered;  // the times of the frames it made, in order

 protected:
  SeriesSource() { this->SetNumberOfInputPorts(0); }

  int RequestInformation(vtkInformation*, vtkInformationVector**,
                         vtkInformationVector* out) override {
    vtkInformation* info = out->GetInformationObject(0);
    info->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), this->Times.data(),
              static_cast<int>(this->Times.size()));
    const double range[2] = {this->Times.front(), this->Times.back()};
    info->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
    return 1;
  }
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* out) override {
    vtkInformation* info = out->GetInformationObject(0);
    double t = this->Times.front();
    if (info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP())) {
      const double asked = info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
      for (const double step : this->Times)
        if (step <= asked) t = step;
    }
    vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(out);
    output->ShallowCopy(this->Frame(t));
    output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), t);
    this->Delivered.push_back(t);
    return 1;
  }
};
vtkStandardNewMacro(SeriesSource);

// Particles 0..4, listed in an order that changes with time, with
// xi = t (id + 1) and the point array "doubled" = 2 xi.
vtkSmartPointer<vtkUnstructuredGrid> strain_frame(double t) {
  Lattice lattice;
  std::vector<vtkTypeInt64> ids = {0, 1, 2, 3, 4};
  std::rotate(ids.begin(), ids.begin() + static_cast<int>(t) % 5, ids.end());
  for (const vtkTypeInt64 id : ids) {
    lattice.points.push_back({static_cast<double>(id), 0.0});
    lattice.xi.push_back(t * static_cast<double>(id + 1));
  }
  auto frame = to_frame(lattice, 0.1);
  auto* id_array = vtkTypeInt64Array::SafeDownCast(frame->GetPointData()->GetArray("particle_id"));
  for (size_t i = 0; i < ids.size(); ++i) id_array->SetValue(static_cast<vtkIdType>(i), ids[i]);
  vtkNew<vtkDoubleArray> doubled;
  doubled->SetName("doubled");
  for (const double xi : lattice.xi) doubled->InsertNextValue(2 * xi);
  frame->GetPointData()->AddArray(doubled);
  vtkNew<vtkDoubleArray> time;
  time->SetName("TimeValue");
  time->InsertNextValue(t);
  frame->GetFieldData()->AddArray(time);
  return frame;
}

// The array `name` of `data` by particle id: value[id].
std::vector<double> by_id(vtkDataSet* data, const char* name) {
  vtkDataArray* values = data->GetPointData()->GetArray(name);
  vtkDataArray* ids = data->GetPointData()->GetArray("particle_id");
  std::vector<double> out(data->GetNumberOfPoints());
  for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
    out[static_cast<size_t>(ids->GetComponent(i, 0))] = values->GetComponent(i, 0);
  return out;
}

vtkDataSet* particles(vtkRunoutPlasticStrain* filter) {
  return vtkDataSet::SafeDownCast(filter->GetOutputDataObject(0));
}

}  // namespace

TEST(PlasticStrainFilter, IncrementFromThePreviousStepInAnyOrder) {
  vtkNew<SeriesSource> source;
  source->Times = {0.0, 1.0, 2.0, 3.0};
  source->Frame = strain_frame;
  vtkNew<vtkRunoutPlasticStrain> filter;
  filter->SetInputConnection(source->GetOutputPort());

  const std::vector<double> rate = {1, 2, 3, 4, 5};  // d xi / dt by id
  // A jump to the end, back to the start, then forward step by step.
  for (const double t : {3.0, 0.0, 1.0, 2.0, 3.0, 1.5}) {
    filter->UpdateTimeStep(t);
    vtkDataSet* out = vtkDataSet::SafeDownCast(filter->GetOutputDataObject(0));
    ASSERT_EQ(out->GetNumberOfPoints(), 5) << t;
    const std::vector<double> increment = by_id(out, "plastic_strain_increment");
    for (size_t id = 0; id < 5; ++id)
      EXPECT_DOUBLE_EQ(increment[id], t < 1 ? 0.0 : rate[id]) << "t " << t << " id " << id;
    const std::vector<double> normalised = by_id(out, "normalised_plastic_strain");
    EXPECT_DOUBLE_EQ(normalised[4], t < 1 ? 0.0 : 1.0);
    EXPECT_DOUBLE_EQ(normalised[0], t < 1 ? 0.0 : 0.2);
  }
  // The survey of the grid's extent reads every step once, keeping the
  // strains of 2 for 3 and ending on 3 itself; then 0, 1 (0 cached), 2, 3
  // (cached before them), 1.5 is step 1 (after 0, no longer cached): no
  // frame read twice in a row needlessly.
  EXPECT_EQ(source->Delivered, (std::vector<double>{0, 1, 2, 3, 0, 1, 2, 3, 0, 1}));

  // Another strain array: the strains cached from the first are not used.
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "doubled");
  filter->UpdateTimeStep(2.0);
  const std::vector<double> increment =
      by_id(vtkDataSet::SafeDownCast(filter->GetOutputDataObject(0)), "plastic_strain_increment");
  for (size_t id = 0; id < 5; ++id) EXPECT_DOUBLE_EQ(increment[id], 2 * rate[id]) << id;
}

TEST(PlasticStrainFilter, SeriesGridHasOneExtentDeclaredInRequestInformation) {
  // A slide that lengthens: its particles spread with the time.
  vtkNew<SeriesSource> source;
  source->Times = {0.0, 1.0, 2.0};
  source->Frame = [](double t) {
    auto frame = strain_frame(t);
    vtkPoints* points = frame->GetPoints();
    for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i) {
      double p[3];
      points->GetPoint(i, p);
      points->SetPoint(i, p[0] * (1 + t), p[1] + 0.3 * t, 0.0);
    }
    return frame;
  };
  vtkNew<vtkRunoutPlasticStrain> filter;
  filter->SetGridSpacing(0.5);
  filter->SetInputConnection(source->GetOutputPort());

  // The last frame reaches x = 12, y = 0.6; the first starts at x = y = 0.
  const int expected[6] = {0, 24, 0, 2, 0, 0};
  for (const double t : {0.0, 2.0, 1.0}) {
    filter->UpdateTimeStep(t);
    int extent[6];
    filter->GetGridOutput()->GetExtent(extent);
    double origin[3];
    filter->GetGridOutput()->GetOrigin(origin);
    for (int k = 0; k < 6; ++k) EXPECT_EQ(extent[k], expected[k]) << "t " << t << " k " << k;
    EXPECT_DOUBLE_EQ(origin[0], 0.0);
    EXPECT_DOUBLE_EQ(origin[1], 0.0);
  }
  // Once surveyed, RequestInformation declares it (ParaView's image
  // representations ask for it before the data pass).
  filter->Modified();
  filter->UpdateInformation();
  int whole[6];
  filter->GetOutputInformation(1)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  for (int k = 0; k < 6; ++k) EXPECT_EQ(whole[k], expected[k]) << k;
  // Another spacing: the same box on the new lattice, still in RequestInformation.
  filter->SetGridSpacing(1.0);
  filter->UpdateInformation();
  filter->GetOutputInformation(1)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  EXPECT_EQ(whole[1], 12);
  EXPECT_EQ(whole[3], 1);
  // The survey reads each step once, however often the time changes.
  EXPECT_EQ(std::count(source->Delivered.begin(), source->Delivered.end(), 2.0), 2);
}

TEST(PlasticStrainFilter, FramesFedOneByOneUseTheirTimeValue) {
  vtkNew<vtkRunoutPlasticStrain> filter;
  filter->SetXi95(5.0);
  for (const double t : {1.0, 2.0, 4.0}) {
    filter->SetInputData(strain_frame(t));
    filter->Update();
    const std::vector<double> increment = by_id(particles(filter), "plastic_strain_increment");
    const double expected = t == 1.0 ? 0.0 : (t == 2.0 ? 1.0 : 2.0);  // per unit id + 1
    for (size_t id = 0; id < 5; ++id) EXPECT_DOUBLE_EQ(increment[id], expected * (id + 1)) << t;
    EXPECT_DOUBLE_EQ(by_id(particles(filter), "normalised_plastic_strain")[0], t / 5.0);
  }
}

TEST(PlasticStrainFilter, GriddedFieldOfAUniformStrain) {
  Slab slab;
  slab.length = 6;
  slab.height = 2;
  slab.background_xi = 0.7;
  vtkNew<vtkRunoutPlasticStrain> filter;
  filter->SetInputData(to_frame(make_lattice(slab), slab.h));
  filter->Update();
  vtkImageData* image = filter->GetGridOutput();
  ASSERT_NE(image, nullptr);
  double spacing[3];
  image->GetSpacing(spacing);
  EXPECT_DOUBLE_EQ(spacing[0], 0.2);  // 2 particle spacings by default
  int dims[3];
  image->GetDimensions(dims);
  EXPECT_EQ(dims[2], 1);
  EXPECT_GE(dims[0] * 0.2, 5.8);
  vtkDataArray* xi = image->GetPointData()->GetArray("plastic_shear_strain");
  vtkDataArray* coverage = image->GetPointData()->GetArray("coverage");
  ASSERT_NE(xi, nullptr);
  ASSERT_NE(coverage, nullptr);
  ASSERT_NE(image->GetPointData()->GetArray("plastic_strain_increment"), nullptr);
  ASSERT_NE(image->GetPointData()->GetArray("normalised_plastic_strain"), nullptr);
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i) {
    EXPECT_EQ(coverage->GetComponent(i, 0), 1.0);  // the lattice fills the box
    EXPECT_NEAR(xi->GetComponent(i, 0), 0.7, 1e-12);
  }

  filter->SetGridSpacing(0.5);
  filter->Update();
  filter->GetGridOutput()->GetSpacing(spacing);
  EXPECT_DOUBLE_EQ(spacing[0], 0.5);

  filter->SetGridSpacing(0);
  filter->SetInputData(to_frame(make_lattice(slab), slab.h, {true, true, true, false, true}));
  filter->Update();
  filter->GetGridOutput()->GetSpacing(spacing);
  EXPECT_DOUBLE_EQ(spacing[0], 0.5);  // without particle_spacing
}

TEST(PlasticStrainFilter, MissingArraysAreErrorsWithEmptyOutputs) {
  Slab slab;
  slab.length = 1;
  const Lattice lattice = make_lattice(slab);
  vtkNew<vtkRunoutPlasticStrain> filter;
  vtkNew<ErrorCounter> counter;
  filter->AddObserver(vtkCommand::ErrorEvent, counter);
  filter->SetInputData(to_frame(lattice, slab.h));
  filter->Update();
  ASSERT_GT(particles(filter)->GetNumberOfPoints(), 0);
  ASSERT_GT(filter->GetGridOutput()->GetNumberOfPoints(), 0);

  filter->SetInputData(to_frame(lattice, slab.h, {false, true, true, true, true}));
  filter->Update();
  EXPECT_EQ(counter->errors, 1);
  EXPECT_NE(counter->last.find("\"plastic_shear_strain\""), std::string::npos) << counter->last;
  EXPECT_EQ(particles(filter)->GetNumberOfPoints(), 0);
  EXPECT_EQ(filter->GetGridOutput()->GetNumberOfPoints(), 0);

  filter->SetInputData(to_frame(lattice, slab.h, {true, false, true, true, true}));
  filter->Update();
  EXPECT_EQ(counter->errors, 2);
  EXPECT_NE(counter->last.find("\"particle_id\""), std::string::npos) << counter->last;
  EXPECT_EQ(particles(filter)->GetNumberOfPoints(), 0);

  // A grid spacing that would need more memory than there is: no grid.
  filter->SetInputData(to_frame(lattice, slab.h));
  filter->SetGridSpacing(1e-6);
  filter->Update();
  EXPECT_EQ(counter->errors, 3);
  EXPECT_NE(counter->last.find("GridSpacing"), std::string::npos) << counter->last;
  EXPECT_EQ(filter->GetGridOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(particles(filter)->GetNumberOfPoints(), static_cast<vtkIdType>(lattice.points.size()));

  // So does one particle scattered far from the others at the default
  // spacing (as in the fuzzer's out-of-memory input): 2e7 nodes of 0.2 m.
  Lattice scattered = lattice;
  scattered.points.front() = {900, 900};
  filter->SetGridSpacing(0);
  filter->SetInputData(to_frame(scattered, slab.h));
  filter->Update();
  EXPECT_EQ(counter->errors, 4);
  EXPECT_NE(counter->last.find("too many"), std::string::npos) << counter->last;
  EXPECT_EQ(filter->GetGridOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(particles(filter)->GetNumberOfPoints(), static_cast<vtkIdType>(lattice.points.size()));
}

TEST(PlasticStrainFilter, EmptyFrameAndOneParticle) {
  vtkNew<vtkRunoutPlasticStrain> filter;
  vtkNew<ErrorCounter> counter;
  filter->AddObserver(vtkCommand::ErrorEvent, counter);
  filter->SetInputData(to_frame(Lattice{}, 0.1));
  filter->Update();
  EXPECT_EQ(counter->errors, 0);
  EXPECT_EQ(particles(filter)->GetNumberOfPoints(), 0);
  EXPECT_NE(particles(filter)->GetPointData()->GetArray("plastic_strain_increment"), nullptr);
  EXPECT_EQ(filter->GetGridOutput()->GetNumberOfPoints(), 0);

  filter->SetInputData(to_frame(Lattice{{{1.0, 2.0}}, {0.3}}, 0.1));
  filter->Update();
  EXPECT_EQ(counter->errors, 0);
  EXPECT_DOUBLE_EQ(by_id(particles(filter), "normalised_plastic_strain")[0], 1.0);
  vtkImageData* image = filter->GetGridOutput();
  ASSERT_GE(image->GetNumberOfPoints(), 1);
  vtkDataArray* coverage = image->GetPointData()->GetArray("coverage");
  vtkDataArray* xi = image->GetPointData()->GetArray("plastic_shear_strain");
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i) {
    EXPECT_EQ(coverage->GetComponent(i, 0), 1.0);
    EXPECT_DOUBLE_EQ(xi->GetComponent(i, 0), 0.3);
  }
}

// ---------------------------------------------------------------- VTK: bands and blocks

TEST(ShearBandsFilter, DefaultsFindTheBand) {
  Slab slab;
  slab.bands = {{10.0, 45.0, 0.5}};
  vtkNew<vtkRunoutShearBands> filter;
  filter->SetInputData(to_frame(make_lattice(slab), slab.h));
  filter->Update();
  vtkPolyData* lines = filter->GetOutput();
  vtkTable* table = vtkTable::SafeDownCast(filter->GetOutputDataObject(1));
  ASSERT_NE(table, nullptr);
  expect_columns(table, kBandColumns);
  ASSERT_EQ(table->GetNumberOfRows(), 1);
  EXPECT_NEAR(value(table, "dip", 0), 45, 2);
  EXPECT_NEAR(value(table, "thickness", 0), 0.5, slab.h);
  EXPECT_EQ(value(table, "band_id", 0), 0);
  EXPECT_GT(value(table, "particle_count", 0), 200);
  ASSERT_EQ(lines->GetNumberOfLines(), 1);
  EXPECT_NEAR(lines->GetCellData()->GetArray("dip")->GetComponent(0, 0), 45, 2);
  EXPECT_GE(lines->GetCell(0)->GetNumberOfPoints(), 10);

  filter->SetThresholdModeToAbsolute();
  filter->SetThreshold(20);
  filter->Update();
  table = vtkTable::SafeDownCast(filter->GetOutputDataObject(1));
  expect_columns(table, kBandColumns);  // all below the threshold: no rows
  EXPECT_EQ(table->GetNumberOfRows(), 0);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfLines(), 0);
}

TEST(ShearBandsFilter, RobustInputs) {
  Slab slab;
  slab.bands = {{10.0, 45.0, 0.5}};
  const Lattice lattice = make_lattice(slab);
  vtkNew<vtkRunoutShearBands> filter;
  vtkNew<ErrorCounter> counter;
  filter->AddObserver(vtkCommand::ErrorEvent, counter);
  auto table = [&] { return vtkTable::SafeDownCast(filter->GetOutputDataObject(1)); };

  filter->SetInputData(to_frame(lattice, slab.h, {false, true, true, true, true}));
  filter->Update();
  EXPECT_EQ(counter->errors, 1);
  EXPECT_NE(counter->last.find("\"plastic_shear_strain\""), std::string::npos) << counter->last;
  EXPECT_EQ(table()->GetNumberOfColumns(), 0);

  filter->SetInputData(to_frame(lattice, slab.h, {true, true, true, false, true}));
  filter->Update();
  EXPECT_EQ(counter->errors, 2);
  EXPECT_NE(counter->last.find("\"particle_spacing\""), std::string::npos) << counter->last;
  filter->SetParticleSpacing(slab.h);  // given by hand instead
  filter->Update();
  EXPECT_EQ(counter->errors, 2);
  EXPECT_EQ(table()->GetNumberOfRows(), 1);
  filter->SetParticleSpacing(0);

  for (const Lattice& small : {Lattice{}, Lattice{{{1.0, 1.0}}, {2.0}}}) {
    filter->SetInputData(to_frame(small, slab.h));
    filter->Update();
    expect_columns(table(), kBandColumns);
    EXPECT_EQ(table()->GetNumberOfRows(), 0);
  }
  Lattice unstrained = lattice;
  std::fill(unstrained.xi.begin(), unstrained.xi.end(), 0.0);
  filter->SetInputData(to_frame(unstrained, slab.h));
  filter->Update();
  expect_columns(table(), kBandColumns);
  EXPECT_EQ(table()->GetNumberOfRows(), 0);
  EXPECT_EQ(counter->errors, 2);
}

TEST(HorstGrabenFilter, DefaultsFindTheHorst) {
  Slab slab;
  slab.length = 40;
  slab.bands = {{18.0, -45.0, 0.4}, {22.0, 45.0, 0.4}};
  vtkNew<vtkRunoutHorstGraben> filter;
  filter->SetInputData(to_frame(make_lattice(slab), slab.h));
  filter->Update();
  vtkTable* table = vtkTable::SafeDownCast(filter->GetOutputDataObject(1));
  ASSERT_NE(table, nullptr);
  expect_columns(table, kBlockColumns);
  ASSERT_EQ(table->GetNumberOfRows(), 3);
  auto* type = vtkStringArray::SafeDownCast(table->GetColumnByName("type"));
  ASSERT_NE(type, nullptr);
  EXPECT_EQ(type->GetValue(0), "block");
  EXPECT_EQ(type->GetValue(1), "horst");
  EXPECT_EQ(type->GetValue(2), "block");
  EXPECT_EQ(value(table, "type_code", 1), 1);
  EXPECT_NEAR(value(table, "left_dip", 1), -45, 2);
  EXPECT_NEAR(value(table, "right_dip", 1), 45, 2);
  EXPECT_NEAR(value(table, "displacement", 1), 1.5, 1e-12);  // |(0.9, 1.2, 0)|
  EXPECT_NEAR(value(table, "top", 1), 5.0, 1e-6);  // float points
  vtkPolyData* outlines = filter->GetOutput();
  ASSERT_EQ(outlines->GetNumberOfPolys(), 3);
  EXPECT_NE(outlines->GetCellData()->GetAbstractArray("type"), nullptr);
}

TEST(HorstGrabenFilter, RobustInputs) {
  Slab slab;
  slab.bands = {{10.0, 45.0, 0.5}};
  const Lattice lattice = make_lattice(slab);
  vtkNew<vtkRunoutHorstGraben> filter;
  vtkNew<ErrorCounter> counter;
  filter->AddObserver(vtkCommand::ErrorEvent, counter);
  auto table = [&] { return vtkTable::SafeDownCast(filter->GetOutputDataObject(1)); };

  filter->SetInputData(to_frame(lattice, slab.h));
  filter->Update();
  ASSERT_EQ(table()->GetNumberOfRows(), 2);  // one band: a block on either side

  filter->SetInputData(to_frame(lattice, slab.h, {true, true, false, true, true}));
  filter->Update();
  EXPECT_EQ(counter->errors, 1);
  EXPECT_NE(counter->last.find("\"displacement\""), std::string::npos) << counter->last;
  EXPECT_EQ(table()->GetNumberOfRows(), 0);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPolys(), 0);

  filter->SetInputData(to_frame(lattice, slab.h, {false, true, true, true, true}));
  filter->Update();
  EXPECT_EQ(counter->errors, 2);
  EXPECT_NE(counter->last.find("\"plastic_shear_strain\""), std::string::npos) << counter->last;

  Lattice unstrained = lattice;
  std::fill(unstrained.xi.begin(), unstrained.xi.end(), 0.0);
  for (const Lattice& frame : {Lattice{}, Lattice{{{1.0, 1.0}}, {2.0}}, unstrained}) {
    filter->SetInputData(to_frame(frame, slab.h));
    filter->Update();
    expect_columns(table(), kBlockColumns);
    EXPECT_EQ(table()->GetNumberOfRows(), 0);
  }
  EXPECT_EQ(counter->errors, 2);
}
