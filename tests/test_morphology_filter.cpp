// vtkRunoutMorphology and vtkRunoutMorphologyHistory on synthetic slabs
// whose answers are known: a translated block, a thinning and lengthening
// slab, a slab with grabens, one particle, no particle, frames without
// their arrays, and a three-frame series written by the engine's writer.
// The mechanism rule behind them (morphology_rules.hpp) is tested without
// VTK in test_analysis_algorithms.cpp.
#include <gtest/gtest.h>
#include <unistd.h>

#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPVDReader.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkTable.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "runout/analysis/morphology_rules.hpp"
#include "filter_fixtures.hpp"
#include "runout/output/vtu_writer.hpp"
#include "vtkRunoutMorphology.h"
#include "vtkRunoutMorphologyHistory.h"

namespace fs = std::filesystem;
using runout::Particles;
using runout::analysis::Mechanism;
using runout::filter_fixtures::ErrorCounter;
using runout::filter_fixtures::value;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kSpacing = 0.25;
// The planar base as the engine writes it: the grid's bottom line.
const std::vector<double> kPlanarBase = {-10.0, 0.0, 200.0, 0.0};

// The slab [0, length] x [0, height] on the particle lattice of kSpacing,
// at rest where it was seeded; `moved` maps each particle's initial (x0, y0)
// to its current (x, y).
Particles slab(double length, double height,
               const std::function<void(double x0, double y0, double& x, double& y)>& moved) {
  Particles p;
  const int nx = static_cast<int>(std::lround(length / kSpacing));
  const int ny = static_cast<int>(std::lround(height / kSpacing));
  p.resize(nx * ny);
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) {
      const int k = i * ny + j;
      p.x0[k] = (i + 0.5) * kSpacing;
      p.y0[k] = (j + 0.5) * kSpacing;
      moved(p.x0[k], p.y0[k], p.x[k], p.y[k]);
      p.mass[k] = 600.0 * kSpacing * kSpacing;
    }
  return p;
}

Particles translated_slab(double dx, double vx) {
  Particles p = slab(40.0, 4.0, [dx](double x0, double y0, double& x, double& y) {
    x = x0 + dx;
    y = y0;
  });
  p.vx.assign(p.x.size(), vx);
  return p;
}

// Lengthened 1.5 times and thinned as much: what elongation does.
Particles elongated_slab() {
  return slab(40.0, 4.0, [](double x0, double y0, double& x, double& y) {
    x = 5.0 + 1.5 * x0;
    y = y0 / 1.5;
  });
}

void add_field(vtkDataObject* data, const char* name, int components,
               const std::vector<double>& values) {
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(components);
  for (const double v : values) a->InsertNextValue(v);
  data->GetFieldData()->AddArray(a);
}

// A frame as the engine writes it (docs/output.md), without the arrays the
// morphology does not read.
vtkSmartPointer<vtkUnstructuredGrid> frame(const Particles& p, double time,
                                           const std::vector<double>& base_xy = kPlanarBase) {
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  runout::filter_fixtures::MorphologyArrays arrays;
  for (int i = 0; i < p.size(); ++i) {
    points->InsertNextPoint(p.x[i], p.y[i], 0.0);
    arrays.velocity->InsertNextTuple3(p.vx[i], p.vy[i], 0.0);
    arrays.mass->InsertNextValue(p.mass[i]);
    arrays.initial->InsertNextTuple3(p.x0[i], p.y0[i], 0.0);
  }
  grid->SetPoints(points);
  arrays.add_to(grid->GetPointData());
  add_field(grid, "TimeValue", 1, {time});
  add_field(grid, "particle_spacing", 1, {kSpacing});
  std::vector<double> base;
  for (std::size_t k = 0; k + 1 < base_xy.size(); k += 2)
    base.insert(base.end(), {base_xy[k], base_xy[k + 1], 0.0});
  add_field(grid, "base_points", 3, base);
  return grid;
}

std::string mechanism(vtkTable* table, vtkIdType row = 0) {
  vtkAbstractArray* a = table->GetColumnByName("mechanism");
  EXPECT_NE(a, nullptr);
  return a && row < a->GetNumberOfTuples() ? a->GetVariantValue(row).ToString() : "";
}

// The filter run on one frame.
struct Morphology {
  vtkNew<vtkRunoutMorphology> filter;
  vtkNew<ErrorCounter> counter;
  Morphology() { filter->AddObserver(vtkCommand::ErrorEvent, counter); }
  vtkTable* run(vtkDataObject* data) {
    filter->SetInputData(data);
    filter->Update();
    return filter->GetTableOutput();
  }
  vtkPolyData* profile() { return filter->GetOutput(); }
};

}  // namespace

// ---- vtkRunoutMorphology on one frame ---------------------------------

TEST(RunoutMorphology, TranslatedBlockHasItsRunoutAndSlidesAsABlock) {
  Morphology m;
  vtkTable* table = m.run(frame(translated_slab(10.0, 2.0), 4.5));
  EXPECT_EQ(m.counter->errors, 0) << m.counter->last;
  ASSERT_EQ(table->GetNumberOfRows(), 1);
  EXPECT_EQ(value(table, "Time"), 4.5);
  // The lattice fills [0, 40] x [0, 4]: edges half a spacing beyond the
  // outermost centres. On a planar base s = x.
  EXPECT_DOUBLE_EQ(value(table, "toe"), 50.0);
  EXPECT_DOUBLE_EQ(value(table, "rear"), 10.0);
  EXPECT_DOUBLE_EQ(value(table, "length"), 40.0);
  EXPECT_DOUBLE_EQ(value(table, "initial_toe"), 40.0);
  EXPECT_DOUBLE_EQ(value(table, "runout"), 10.0);
  EXPECT_DOUBLE_EQ(value(table, "max_thickness"), 4.0);
  EXPECT_NEAR(value(table, "centroid_x"), 30.0, 1e-9);
  EXPECT_NEAR(value(table, "centroid_y"), 2.0, 1e-9);
  EXPECT_NEAR(value(table, "centroid_s"), 30.0, 1e-9);
  EXPECT_NEAR(value(table, "toe_velocity"), 2.0, 1e-12);
  EXPECT_NEAR(value(table, "centroid_velocity"), 2.0, 1e-12);
  EXPECT_EQ(value(table, "particles"), 160 * 16);
  EXPECT_EQ(value(table, "outside_mass"), 0.0);
  EXPECT_DOUBLE_EQ(value(table, "length_ratio"), 1.0);
  EXPECT_DOUBLE_EQ(value(table, "thickness_ratio"), 1.0);
  EXPECT_EQ(value(table, "troughs"), 0);
  EXPECT_EQ(mechanism(table), "block sliding");
  EXPECT_EQ(value(table, "mechanism_id"), static_cast<int>(Mechanism::BlockSliding));

  // The profile: bins of 2 spacings, on the block's top.
  vtkPolyData* profile = m.profile();
  ASSERT_EQ(profile->GetNumberOfPoints(), 81);
  ASSERT_EQ(profile->GetNumberOfLines(), 1);
  vtkDataArray* s = profile->GetPointData()->GetArray("s");
  vtkDataArray* thickness = profile->GetPointData()->GetArray("thickness");
  vtkDataArray* velocity = profile->GetPointData()->GetArray("velocity_s");
  vtkDataArray* particles = profile->GetPointData()->GetArray("particles");
  ASSERT_TRUE(s && thickness && velocity && particles);
  for (vtkIdType k = 0; k < 81; ++k) {
    SCOPED_TRACE(k);
    EXPECT_NEAR(s->GetTuple1(k), 10.125 + 0.5 * k, 1e-9);
    EXPECT_DOUBLE_EQ(thickness->GetTuple1(k), 4.0);
    EXPECT_NEAR(velocity->GetTuple1(k), 2.0, 1e-12);
    // The first bin is centred on the rear column, so the first and last
    // bins hold one column of 16 particles, the others two.
    EXPECT_EQ(particles->GetTuple1(k), k == 0 || k == 80 ? 16 : 32);
    double xyz[3];
    profile->GetPoint(k, xyz);
    EXPECT_NEAR(xyz[0], s->GetTuple1(k), 1e-12);
    EXPECT_DOUBLE_EQ(xyz[1], 4.0);
  }
}

TEST(RunoutMorphology, RunoutIsMeasuredAlongAnInclinedBase) {
  // The same block on a base dipping 30 degrees, moved 12 m down it. s is
  // the arc length from the base's first point, (-5, 0).
  const double c = std::cos(kPi / 6), sn = -std::sin(kPi / 6);  // base tangent
  const double nx = -sn, ny = c;                                   // outward normal
  auto to_run_frame = [&](double s, double d, double& x, double& y) {
    x = -5.0 + s * c + d * nx;
    y = s * sn + d * ny;
  };
  Particles p = slab(40.0, 4.0, [&](double s0, double d0, double& x, double& y) {
    to_run_frame(s0 + 5.0 + 12.0, d0, x, y);
  });
  for (int i = 0; i < p.size(); ++i) to_run_frame(p.x0[i] + 5.0, p.y0[i], p.x0[i], p.y0[i]);
  Morphology m;
  vtkTable* table = m.run(frame(p, 1.0, {-5.0, 0.0, -5.0 + 200 * c, 200 * sn}));
  EXPECT_EQ(m.counter->errors, 0) << m.counter->last;
  EXPECT_NEAR(value(table, "initial_toe"), 45.0, 1e-9);
  EXPECT_NEAR(value(table, "toe"), 57.0, 1e-9);
  EXPECT_NEAR(value(table, "runout"), 12.0, 1e-9);
  EXPECT_NEAR(value(table, "length"), 40.0, 1e-9);
  EXPECT_NEAR(value(table, "max_thickness"), 4.0, 1e-9);
  EXPECT_EQ(mechanism(table), "block sliding");
  // The profile's points lie on the slab's top, 4 m above the base.
  vtkPolyData* profile = m.profile();
  ASSERT_GT(profile->GetNumberOfPoints(), 0);
  double xyz[3];
  profile->GetPoint(10, xyz);
  const double s = profile->GetPointData()->GetArray("s")->GetTuple1(10);
  double x = 0, y = 0;
  to_run_frame(s, 4.0, x, y);
  EXPECT_NEAR(xyz[0], x, 1e-9);
  EXPECT_NEAR(xyz[1], y, 1e-9);
}

TEST(RunoutMorphology, ThinningLengtheningSlabIsElongationNotBlockSliding) {
  Morphology m;
  vtkTable* table = m.run(frame(elongated_slab(), 8.0));
  EXPECT_EQ(m.counter->errors, 0) << m.counter->last;
  // Toe 5 + 1.5 x 39.875 + 0.125; rear 5 + 1.5 x 0.125 - 0.125.
  EXPECT_DOUBLE_EQ(value(table, "length"), 59.875);
  EXPECT_DOUBLE_EQ(value(table, "length_ratio"), 59.875 / 40.0);
  EXPECT_DOUBLE_EQ(value(table, "thickness_ratio"), (3.875 / 1.5 + 0.125) / 4.0);
  EXPECT_DOUBLE_EQ(value(table, "runout"), 5.0 + 1.5 * 39.875 + 0.125 - 40.0);
  EXPECT_EQ(value(table, "troughs"), 0);
  EXPECT_EQ(mechanism(table), "elongation");

  // The same slab only translated slides as a block.
  EXPECT_EQ(mechanism(m.run(frame(translated_slab(25.0, 0.0), 8.0))), "block sliding");
}

TEST(RunoutMorphology, NarrowDipsOfAThinningSlabAreNotGrabens) {
  // Every 8th particle column of the elongated slab is 30 % lower: troughs
  // one bin wide, particle-scale noise that the closing fills.
  Particles p = elongated_slab();
  for (int i = 0; i < p.size(); ++i)
    if (static_cast<int>(p.x0[i] / kSpacing) % 8 == 0) p.y[i] *= 0.7;
  Morphology m;
  vtkTable* table = m.run(frame(p, 8.0));
  EXPECT_EQ(value(table, "troughs"), 0);
  EXPECT_EQ(mechanism(table), "elongation");
}

TEST(RunoutMorphology, DroppedBlocksBetweenHorstsAreSpreading) {
  // Stretched 1.3 times; two 8 m wide blocks drop to half their height
  // while the horsts between them keep theirs.
  auto graben = [](double x) { return (x > 14.0 && x < 22.0) || (x > 34.0 && x < 42.0); };
  Particles p = slab(40.0, 4.0, [&](double x0, double y0, double& x, double& y) {
    x = 1.3 * x0;
    y = graben(x) ? 0.5 * y0 : y0;
  });
  Morphology m;
  vtkTable* table = m.run(frame(p, 20.0));
  EXPECT_EQ(m.counter->errors, 0) << m.counter->last;
  EXPECT_EQ(value(table, "troughs"), 2);
  EXPECT_EQ(value(table, "initial_troughs"), 0);
  EXPECT_EQ(mechanism(table), "spreading");
}

TEST(RunoutMorphology, UnmovedSlabIsUndetermined) {
  Morphology m;
  vtkTable* table = m.run(frame(translated_slab(0.0, 0.0), 0.0));
  EXPECT_EQ(value(table, "runout"), 0.0);
  EXPECT_EQ(mechanism(table), "undetermined");
  EXPECT_EQ(value(table, "mechanism_id"), static_cast<int>(Mechanism::Undetermined));
}

TEST(RunoutMorphology, BinSpacingsSetsTheProfileBins) {
  Morphology m;
  m.filter->SetBinSpacings(4.0);
  m.run(frame(translated_slab(10.0, 0.0), 1.0));
  EXPECT_EQ(m.profile()->GetNumberOfPoints(), 41);
  EXPECT_NEAR(m.profile()->GetPointData()->GetArray("s")->GetTuple1(1), 10.125 + 1.0, 1e-9);
}

TEST(RunoutMorphology, OneParticle) {
  Particles p;
  p.resize(1);
  p.x0[0] = 5.0;
  p.y0[0] = 0.125;
  p.x[0] = 7.0;
  p.y[0] = 0.125;
  p.vx[0] = 1.5;
  p.mass[0] = 2.0;
  Morphology m;
  vtkTable* table = m.run(frame(p, 3.0));
  EXPECT_EQ(m.counter->errors, 0) << m.counter->last;
  ASSERT_EQ(table->GetNumberOfRows(), 1);
  EXPECT_EQ(value(table, "particles"), 1);
  EXPECT_DOUBLE_EQ(value(table, "toe"), 7.125);
  EXPECT_DOUBLE_EQ(value(table, "rear"), 6.875);
  EXPECT_DOUBLE_EQ(value(table, "length"), kSpacing);
  EXPECT_DOUBLE_EQ(value(table, "max_thickness"), kSpacing);
  EXPECT_DOUBLE_EQ(value(table, "runout"), 2.0);
  EXPECT_DOUBLE_EQ(value(table, "toe_velocity"), 1.5);
  // A particle that moved 8 times its own length without changing shape.
  EXPECT_EQ(mechanism(table), "block sliding");
  EXPECT_EQ(m.profile()->GetNumberOfPoints(), 1);
}

TEST(RunoutMorphology, EmptyFrameGivesEmptyProfileAndAnUndeterminedRow) {
  Morphology m;
  // With the engine's (empty) arrays, and with none at all.
  for (auto data : {frame(Particles(), 2.0), vtkSmartPointer<vtkUnstructuredGrid>::New()}) {
    vtkTable* table = m.run(data);
    EXPECT_EQ(m.counter->errors, 0) << m.counter->last;
    EXPECT_EQ(m.profile()->GetNumberOfPoints(), 0);
    ASSERT_EQ(table->GetNumberOfRows(), 1);
    EXPECT_EQ(value(table, "particles"), 0);
    EXPECT_TRUE(std::isnan(value(table, "toe")));
    EXPECT_TRUE(std::isnan(value(table, "runout")));
    EXPECT_EQ(mechanism(table), "undetermined");
  }
  EXPECT_EQ(value(m.filter->GetTableOutput(), "particles"), 0);
}

TEST(RunoutMorphology, PipelineTimeWinsOverTimeValue) {
  auto data = frame(translated_slab(1.0, 0.0), 4.5);
  data->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), 6.0);
  Morphology m;
  EXPECT_EQ(value(m.run(data), "Time"), 6.0);
}

TEST(RunoutMorphology, MissingArrayIsAnErrorNamingItWithEmptyOutputs) {
  const std::vector<std::pair<std::string, std::function<void(vtkUnstructuredGrid*)>>> cases = {
      {"velocity", [](vtkUnstructuredGrid* g) { g->GetPointData()->RemoveArray("velocity"); }},
      {"mass", [](vtkUnstructuredGrid* g) { g->GetPointData()->RemoveArray("mass"); }},
      {"initial_position",
       [](vtkUnstructuredGrid* g) { g->GetPointData()->RemoveArray("initial_position"); }},
      {"particle_spacing",
       [](vtkUnstructuredGrid* g) { g->GetFieldData()->RemoveArray("particle_spacing"); }},
      {"base_points",
       [](vtkUnstructuredGrid* g) { g->GetFieldData()->RemoveArray("base_points"); }},
  };
  for (const auto& [name, remove] : cases) {
    SCOPED_TRACE(name);
    Morphology m;
    // A good frame first, so the empty outputs are not just the initial state.
    m.run(frame(translated_slab(1.0, 0.0), 1.0));
    ASSERT_EQ(m.filter->GetTableOutput()->GetNumberOfRows(), 1);
    auto bad = frame(translated_slab(1.0, 0.0), 1.0);
    remove(bad);
    vtkTable* table = m.run(bad);
    EXPECT_EQ(m.counter->errors, 1);
    EXPECT_NE(m.counter->last.find("\"" + name + "\""), std::string::npos) << m.counter->last;
    EXPECT_EQ(table->GetNumberOfRows(), 0);
    EXPECT_EQ(table->GetNumberOfColumns(), 0);
    EXPECT_EQ(m.profile()->GetNumberOfPoints(), 0);
  }
}

// ---- vtkRunoutMorphologyHistory over a series -------------------------

class MorphologyHistory : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("runout_test_morphology_history_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The translated block at `times`, moved `shifts`, as the engine writes a
  // run: its frames and the .pvd index. Returns the index's path.
  std::string write_series(const std::vector<double>& times, const std::vector<double>& shifts) {
    runout::PvdIndex index((dir_ / "series.pvd").string());
    for (std::size_t k = 0; k < times.size(); ++k) {
      const std::string name = "frame_0000" + std::to_string(k) + ".vtu";
      write_particles_vtu((dir_ / name).string(), translated_slab(shifts[k], 1.0),
                          runout::FrameInfo{times[k], kSpacing, kPlanarBase, {}}, true);
      index.add(times[k], name);
    }
    return index.path();
  }
  fs::path dir_;
};

TEST_F(MorphologyHistory, OneRowPerFrameWithItsToe) {
  vtkNew<vtkPVDReader> reader;
  reader->SetFileName(write_series({0.0, 1.0, 2.5}, {0.0, 3.0, 7.5}).c_str());
  vtkNew<vtkRunoutMorphologyHistory> history;
  vtkNew<ErrorCounter> counter;
  history->AddObserver(vtkCommand::ErrorEvent, counter);
  history->SetInputConnection(reader->GetOutputPort());
  history->Update();
  EXPECT_EQ(counter->errors, 0) << counter->last;
  vtkTable* table = history->GetOutput();
  ASSERT_EQ(table->GetNumberOfRows(), 3);
  const std::vector<double> times = {0.0, 1.0, 2.5}, toes = {40.0, 43.0, 47.5};
  for (vtkIdType k = 0; k < 3; ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(value(table, "Time", k), times[k]);
    EXPECT_DOUBLE_EQ(value(table, "toe", k), toes[k]);
    EXPECT_DOUBLE_EQ(value(table, "runout", k), toes[k] - 40.0);
    EXPECT_DOUBLE_EQ(value(table, "length", k), 40.0);
    EXPECT_DOUBLE_EQ(value(table, "max_thickness", k), 4.0);
    EXPECT_NEAR(value(table, "toe_velocity", k), 1.0, 1e-12);
  }
  EXPECT_EQ(mechanism(table, 0), "undetermined");
  EXPECT_EQ(mechanism(table, 2), "block sliding");

  // Run again from scratch: the same three rows, not six.
  history->Modified();
  history->Update();
  EXPECT_EQ(history->GetOutput()->GetNumberOfRows(), 3);
}

TEST_F(MorphologyHistory, InputWithoutTimeStepsGivesOneRow) {
  vtkNew<vtkRunoutMorphologyHistory> history;
  history->SetInputData(frame(translated_slab(2.0, 0.0), 1.5));
  history->Update();
  ASSERT_EQ(history->GetOutput()->GetNumberOfRows(), 1);
  EXPECT_EQ(value(history->GetOutput(), "Time"), 1.5);
  EXPECT_DOUBLE_EQ(value(history->GetOutput(), "runout"), 2.0);
}

TEST_F(MorphologyHistory, FrameWithoutItsArraysStopsWithAnErrorAndEmptyOutput) {
  // The middle frame of three lacks its mass: written by VTK's own writer
  // (inline binary, never appended: ../shared/BUILD.md) over the engine's.
  const std::string pvd = write_series({0.0, 1.0, 2.0}, {0.0, 3.0, 6.0});
  auto stripped = frame(translated_slab(3.0, 1.0), 1.0);
  stripped->GetPointData()->RemoveArray("mass");
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetInputData(stripped);
  writer->SetDataModeToBinary();
  writer->SetFileName((dir_ / "frame_00001.vtu").c_str());
  ASSERT_EQ(writer->Write(), 1);

  vtkNew<vtkPVDReader> reader;
  reader->SetFileName(pvd.c_str());
  vtkNew<vtkRunoutMorphologyHistory> history;
  vtkNew<ErrorCounter> counter;
  history->AddObserver(vtkCommand::ErrorEvent, counter);
  history->SetInputConnection(reader->GetOutputPort());
  history->Update();
  EXPECT_EQ(counter->errors, 1);
  EXPECT_NE(counter->last.find("\"mass\""), std::string::npos) << counter->last;
  EXPECT_EQ(history->GetOutput()->GetNumberOfRows(), 0);
}
