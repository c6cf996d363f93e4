// The Runout filters given malformed frames (docs/filters.md,
// "Robustness"): a frame the engine writes, read back by VTK's reader and
// then spoilt one way at a time (a NaN or infinite position or value, an
// array of the wrong length or width, ids beyond 64 bits, points beyond
// any slide, no points at all). Each filter that reads the spoilt part
// reports an error and leaves every output empty; the others are not
// disturbed; none crashes. Also a series whose index lists a missing frame,
// and the Runout Series Reader on frames that do not match the manifest.
#include <gtest/gtest.h>
#include <unistd.h>

#include <vtkCommand.h>
#include <vtkDataSet.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkPVDReader.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkTable.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "filter_fixtures.hpp"
#include "runout/output/history.hpp"
#include "runout/mpm/seeding.hpp"
#include "runout/output/vtu_writer.hpp"
#include "run_folder.hpp"
#include "scene_builders.hpp"
#include "vtkRunoutHorstGraben.h"
#include "vtkRunoutMorphology.h"
#include "vtkRunoutMorphologyHistory.h"
#include "vtkRunoutPlasticStrain.h"
#include "vtkRunoutSeriesReader.h"
#include "vtkRunoutShearBands.h"

namespace fs = std::filesystem;
using runout::filter_fixtures::ErrorCounter;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// A 20 m x 4 m slab at h = 0.5, ppc 2, moved 1 m downslope, with a 45-degree
// band of plastic strain 2 through x = 10: every filter has something to
// find in it (a grid, a band, a block on either side, a profile).
runout::Particles slab() {
  const runout::Scene s = runout::fixtures::block_scene(
      {0.0, 0.0}, {20.0, 4.0}, {0.0, 0.0}, {30.0, 6.0}, 0.5, 2, 600, 1e5, 0.3);
  runout::Particles p = runout::seed_particles(s);
  for (int i = 0; i < p.size(); ++i) {
    p.x[i] += 1.0;
    p.vx[i] = 0.5;
    p.xi[i] = std::abs((p.x0[i] - 10.0) - p.y0[i]) < 0.5 ? 2.0 : 0.0;
  }
  return p;
}

void write_slab(const fs::path& path, double time) {
  runout::write_particles_vtu(path.string(), slab(),
                              runout::FrameInfo{time, 0.25, {0.0, 0.0, 30.0, 0.0}, {}}, true);
}

// The slab as the engine writes it, read back with VTK's reader.
vtkSmartPointer<vtkUnstructuredGrid> engine_frame() {
  const fs::path path = fs::temp_directory_path() / ("runout_robust_" + std::to_string(getpid()) + ".vtu");
  write_slab(path, 1.0);
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(path.string().c_str());
  reader->Update();
  fs::remove(path);
  auto frame = vtkSmartPointer<vtkUnstructuredGrid>::New();
  frame->DeepCopy(reader->GetOutput());
  return frame;
}

enum Filter { Strain, Bands, Blocks, Morphology, kFilters };
const char* const kNames[] = {"PlasticStrain", "ShearBands", "HorstGraben", "Morphology"};

vtkSmartPointer<vtkAlgorithm> make_filter(Filter f) {
  switch (f) {
    case Strain: return vtkSmartPointer<vtkRunoutPlasticStrain>::New();
    case Bands: return vtkSmartPointer<vtkRunoutShearBands>::New();
    case Blocks: return vtkSmartPointer<vtkRunoutHorstGraben>::New();
    default: return vtkSmartPointer<vtkRunoutMorphology>::New();
  }
}

// Points of a data set, rows of a table: 0 on every port means empty output.
vtkIdType items(vtkDataObject* output) {
  if (auto* table = vtkTable::SafeDownCast(output)) return table->GetNumberOfRows();
  return vtkDataSet::SafeDownCast(output)->GetNumberOfPoints();
}

// A filter with its error and warning counters.
struct FilterRun {
  explicit FilterRun(Filter f) : filter(make_filter(f)) {
    filter->AddObserver(vtkCommand::ErrorEvent, errors);
    filter->AddObserver(vtkCommand::WarningEvent, warnings);
  }
  void update(vtkDataObject* frame) {
    filter->SetInputDataObject(frame);
    filter->Update();
  }
  bool all_outputs_empty() {
    for (int port = 0; port < filter->GetNumberOfOutputPorts(); ++port)
      if (items(filter->GetOutputDataObject(port)) != 0) return false;
    return true;
  }
  bool all_outputs_full() {
    for (int port = 0; port < filter->GetNumberOfOutputPorts(); ++port)
      if (items(filter->GetOutputDataObject(port)) == 0) return false;
    return true;
  }
  vtkSmartPointer<vtkAlgorithm> filter;
  vtkNew<ErrorCounter> errors, warnings;
};

vtkDataArray* point_array(vtkUnstructuredGrid* g, const char* name) {
  return g->GetPointData()->GetArray(name);
}

// Replaces point array `name` by one of `components` components and
// `tuples` tuples, all `value`.
void replace_array(vtkUnstructuredGrid* g, const char* name, int components, vtkIdType tuples,
                   double value) {
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(tuples);
  a->Fill(value);
  g->GetPointData()->RemoveArray(name);
  g->GetPointData()->AddArray(a);
}

void set_point(vtkUnstructuredGrid* g, vtkIdType i, double x, double y) {
  g->GetPoints()->SetPoint(i, x, y, 0.0);
  g->GetPoints()->Modified();
}

struct Spoilt {
  const char* name;
  std::function<void(vtkUnstructuredGrid*)> spoil;
  std::vector<Filter> failing;  // the filters that must report it
  const char* message;          // a part of each one's error
};

const std::vector<Spoilt>& spoilt_frames() {
  static const std::vector<Spoilt> cases = {
      {"NaN position", [](vtkUnstructuredGrid* g) { set_point(g, 7, kNaN, 1.0); },
       {Strain, Bands, Blocks, Morphology}, "Point 7 has a coordinate that is not a finite number"},
      {"infinite position", [](vtkUnstructuredGrid* g) { set_point(g, 3, 1.0, -kInf); },
       {Strain, Bands, Blocks, Morphology}, "Point 3"},
      {"points beyond any slide", [](vtkUnstructuredGrid* g) { set_point(g, 0, 1e300, 0.0); },
       {Strain, Bands, Blocks, Morphology}, ""},
      // The slow input fuzz_vtu found: an initial position 8e6 m away made
      // 8e6 profile bins (10 s and 1.4 GB for 32 particles).
      {"a stray initial position 8000 km away",
       [](vtkUnstructuredGrid* g) { point_array(g, "initial_position")->SetComponent(4, 0, 8e6); },
       {Morphology}, "more than 10^6 profile bins"},
      {"NaN strain",
       [](vtkUnstructuredGrid* g) { point_array(g, "plastic_shear_strain")->SetComponent(5, 0, kNaN); },
       {Strain, Bands, Blocks}, "\"plastic_shear_strain\" has a value that is not a finite number"},
      {"infinite strain",
       [](vtkUnstructuredGrid* g) { point_array(g, "plastic_shear_strain")->SetComponent(5, 0, kInf); },
       {Strain, Bands, Blocks}, "\"plastic_shear_strain\""},
      {"strain with a tuple short",
       [](vtkUnstructuredGrid* g) {
         replace_array(g, "plastic_shear_strain", 1, g->GetNumberOfPoints() - 1, 0.5);
       },
       {Strain, Bands, Blocks}, "tuples for"},
      {"strain with no components",
       [](vtkUnstructuredGrid* g) { replace_array(g, "plastic_shear_strain", 1, 0, 0.5); },
       {Strain, Bands, Blocks}, "\"plastic_shear_strain\" has 0 tuples"},
      {"ids beyond 64 bits",
       [](vtkUnstructuredGrid* g) { replace_array(g, "particle_id", 1, g->GetNumberOfPoints(), 1e30); },
       {Strain}, "\"particle_id\""},
      {"ids with too many tuples",
       [](vtkUnstructuredGrid* g) { replace_array(g, "particle_id", 1, g->GetNumberOfPoints() + 5, 1); },
       {Strain}, "tuples for"},
      {"NaN displacement",
       [](vtkUnstructuredGrid* g) { point_array(g, "displacement")->SetComponent(2, 1, kNaN); },
       {Blocks}, "\"displacement\""},
      {"infinite velocity",
       [](vtkUnstructuredGrid* g) { point_array(g, "velocity")->SetComponent(2, 0, kInf); },
       {Morphology}, "\"velocity\""},
      {"velocity of one component",
       [](vtkUnstructuredGrid* g) { replace_array(g, "velocity", 1, g->GetNumberOfPoints(), 0.1); },
       {Morphology}, "\"velocity\" has 1 component(s), fewer than 3"},
      {"mass a tuple short",
       [](vtkUnstructuredGrid* g) { replace_array(g, "mass", 1, g->GetNumberOfPoints() - 1, 1.0); },
       {Morphology}, "\"mass\""},
      {"NaN initial position",
       [](vtkUnstructuredGrid* g) { point_array(g, "initial_position")->SetComponent(0, 0, kNaN); },
       {Morphology}, "\"initial_position\""},
      {"NaN particle spacing",
       [](vtkUnstructuredGrid* g) {
         g->GetFieldData()->GetArray("particle_spacing")->SetComponent(0, 0, kNaN);
       },
       {Bands, Blocks, Morphology}, "\"particle_spacing\""},
      {"infinite base point",
       [](vtkUnstructuredGrid* g) { g->GetFieldData()->GetArray("base_points")->SetComponent(1, 1, kInf); },
       {Morphology}, "\"base_points\""},
  };
  return cases;
}

bool fails(const Spoilt& c, Filter f) {
  for (const Filter g : c.failing)
    if (g == f) return true;
  return false;
}

}  // namespace

TEST(FilterRobustness, EachSpoiltFrameIsAnErrorWithEmptyOutputsForTheFiltersThatReadIt) {
  for (const Spoilt& c : spoilt_frames()) {
    for (int f = 0; f < kFilters; ++f) {
      SCOPED_TRACE(std::string(c.name) + ", " + kNames[f]);
      FilterRun run(static_cast<Filter>(f));
      // A good frame first, so that empty outputs are not the initial state.
      run.update(engine_frame());
      ASSERT_EQ(run.errors->errors, 0) << run.errors->last;
      ASSERT_TRUE(run.all_outputs_full());
      auto bad = engine_frame();
      c.spoil(bad);
      run.update(bad);
      if (!fails(c, static_cast<Filter>(f))) {
        EXPECT_EQ(run.errors->errors, 0) << run.errors->last;
        continue;
      }
      EXPECT_EQ(run.errors->errors, 1);
      EXPECT_NE(run.errors->last.find(c.message), std::string::npos) << run.errors->last;
      EXPECT_TRUE(run.all_outputs_empty());
    }
  }
}

TEST(FilterRobustness, EmptyFrameIsAWarningWithEmptyOutputs) {
  for (int f = 0; f < kFilters; ++f) {
    SCOPED_TRACE(kNames[f]);
    FilterRun run(static_cast<Filter>(f));
    auto empty = engine_frame();
    empty->Initialize();  // no points, no arrays
    auto with_arrays = engine_frame();
    vtkNew<vtkPoints> none;
    with_arrays->SetPoints(none);
    for (int a = 0; a < with_arrays->GetPointData()->GetNumberOfArrays(); ++a)
      with_arrays->GetPointData()->GetArray(a)->SetNumberOfTuples(0);
    run.update(with_arrays);
    EXPECT_EQ(run.errors->errors, 0) << run.errors->last;
    EXPECT_EQ(run.warnings->errors, 1) << "no warning";
    EXPECT_NE(run.warnings->last.find("no points"), std::string::npos) << run.warnings->last;
    // Runout Morphology keeps its one (undetermined) row per frame.
    for (int port = 0; port < run.filter->GetNumberOfOutputPorts(); ++port)
      EXPECT_EQ(items(run.filter->GetOutputDataObject(port)), f == Morphology && port == 1 ? 1 : 0)
          << "port " << port;
    run.update(empty);  // without the arrays: an error where one is needed, never a crash
    EXPECT_LE(run.errors->errors, 1);
  }
}

namespace {

// A series of three frames (times 0, 1, 2) written as the engine writes
// one: the index, and the manifest beside it.
std::string three_frame_series(const fs::path& dir) {
  fs::remove_all(dir);
  fs::create_directories(dir);
  runout::PvdIndex index((dir / "series.pvd").string());
  for (int k = 0; k < 3; ++k) {
    const std::string name = "frame_0000" + std::to_string(k) + ".vtu";
    write_slab(dir / name, k);
    index.add(k, name);
  }
  return index.path();
}

// The history of a series read by `reader`, with the history filter's and
// the reader's errors and warnings counted.
struct SeriesHistory {
  vtkNew<vtkRunoutMorphologyHistory> history;
  vtkNew<ErrorCounter> errors, warnings, reader_errors, reader_warnings;
  explicit SeriesHistory(vtkAlgorithm* reader) {
    reader->AddObserver(vtkCommand::ErrorEvent, reader_errors);
    reader->AddObserver(vtkCommand::WarningEvent, reader_warnings);
    history->AddObserver(vtkCommand::ErrorEvent, errors);
    history->AddObserver(vtkCommand::WarningEvent, warnings);
    history->SetInputConnection(reader->GetOutputPort());
    history->Update();
  }
  std::vector<double> times() {
    vtkTable* rows = vtkTable::SafeDownCast(history->GetOutputDataObject(0));
    std::vector<double> t;
    for (vtkIdType r = 0; r < rows->GetNumberOfRows(); ++r) t.push_back(rows->GetValue(r, 0).ToDouble());
    return t;
  }
};

fs::path series_folder(const std::string& tag) {
  return fs::temp_directory_path() / ("runout_robust_" + tag + "_" + std::to_string(getpid()));
}

}  // namespace

// The index lists three frames; the second file is gone. VTK's PVD reader
// reports it; the history filter skips that step with a warning naming it
// and keeps the rows of the others, so one lost frame costs one row.
TEST(FilterRobustness, SeriesWithAMissingFrameSkipsItWithAWarning) {
  const fs::path dir = series_folder("pvd");
  const std::string pvd = three_frame_series(dir);
  fs::remove(dir / "frame_00001.vtu");
  vtkNew<vtkPVDReader> reader;
  reader->SetFileName(pvd.c_str());
  SeriesHistory run(reader);
  EXPECT_EQ(run.errors->errors, 0) << run.errors->last;
  EXPECT_EQ(run.warnings->errors, 1) << run.warnings->last;
  EXPECT_NE(run.warnings->last.find("Time step 1"), std::string::npos) << run.warnings->last;
  EXPECT_EQ(run.times(), (std::vector<double>{0.0, 2.0}));
  fs::remove_all(dir);
}

// The Runout Series Reader checks each frame against the manifest before
// VTK parses it: a frame altered in one byte (one base64 character of its
// first array, as a flipped bit on disk would: VTK's reader can abort on
// such a frame), cut short, or gone, is a warning naming the file and why,
// and an empty output at its step; the history keeps the other rows.
TEST(FilterRobustness, SeriesReaderSkipsFramesThatDoNotMatchTheManifest) {
  const fs::path dir = series_folder("manifest");
  const std::string pvd = three_frame_series(dir);
  {  // the whole series first: every frame read, nothing reported
    vtkNew<vtkRunoutSeriesReader> reader;
    reader->SetFileName(pvd.c_str());
    SeriesHistory run(reader);
    EXPECT_EQ(run.reader_warnings->errors + run.reader_errors->errors + run.warnings->errors, 0)
        << run.reader_warnings->last << run.warnings->last;
    EXPECT_EQ(run.times(), (std::vector<double>{0.0, 1.0, 2.0}));
    reader->UpdateTimeStep(1.5);  // the last frame at or before the time, as vtkPVDReader
    EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), slab().size());
    EXPECT_EQ(reader->GetOutput()->GetInformation()->Get(vtkDataObject::DATA_TIME_STEP()), 1.0);
  }
  const fs::path frame = dir / "frame_00001.vtu";
  const std::string whole = runout::run_folder::read_file(frame);
  std::string altered = whole;
  const auto data = altered.find("format=\"binary\"");
  ASSERT_NE(data, std::string::npos);
  char& c = altered[altered.find('>', data) + 8];
  c = c == 'A' ? 'B' : 'A';
  const std::vector<std::pair<std::string, std::string>> spoilt = {
      {altered, "CRC-32"}, {whole.substr(0, whole.size() / 2), "bytes, the manifest says"}, {"", "missing"}};
  for (const auto& [bytes, why] : spoilt) {
    SCOPED_TRACE(why);
    fs::remove(frame);
    if (!bytes.empty()) std::ofstream(frame, std::ios::binary) << bytes;
    vtkNew<vtkRunoutSeriesReader> reader;
    reader->SetFileName(pvd.c_str());
    SeriesHistory run(reader);
    EXPECT_EQ(run.reader_errors->errors + run.errors->errors, 0) << run.errors->last;
    ASSERT_EQ(run.reader_warnings->errors, 1);
    EXPECT_NE(run.reader_warnings->last.find("frame_00001.vtu"), std::string::npos);
    EXPECT_NE(run.reader_warnings->last.find(why), std::string::npos) << run.reader_warnings->last;
    EXPECT_EQ(run.warnings->errors, 1) << run.warnings->last;  // the history's skipped step
    EXPECT_EQ(run.times(), (std::vector<double>{0.0, 2.0}));
  }
  fs::remove_all(dir);
}

// A run older than the manifest is read unchecked, with one warning.
TEST(FilterRobustness, SeriesReaderWithoutAManifestReadsUncheckedAndSaysSo) {
  const fs::path dir = series_folder("nomanifest");
  const std::string pvd = three_frame_series(dir);
  fs::remove(runout::manifest_path(pvd));
  vtkNew<vtkRunoutSeriesReader> reader;
  reader->SetFileName(pvd.c_str());
  SeriesHistory run(reader);
  EXPECT_EQ(run.reader_warnings->errors, 1);
  EXPECT_NE(run.reader_warnings->last.find("unchecked"), std::string::npos) << run.reader_warnings->last;
  EXPECT_EQ(run.times(), (std::vector<double>{0.0, 1.0, 2.0}));
  fs::remove_all(dir);
}

// An index that is not there is an error, and the output is empty.
TEST(FilterRobustness, SeriesReaderWithoutAnIndexIsAnError) {
  vtkNew<vtkRunoutSeriesReader> reader;
  vtkNew<ErrorCounter> errors;
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->SetFileName((series_folder("none") / "none.pvd").string().c_str());
  reader->Update();
  EXPECT_EQ(errors->errors, 1);
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 0);
}

// As ParaView makes it from the Sources menu, before a file is picked: the
// information pass (which ParaView runs at once) offers no time steps and
// reports nothing; run without a file, it is one error and an empty output.
TEST(FilterRobustness, SeriesReaderWithoutAFileWaitsForOne) {
  vtkNew<vtkRunoutSeriesReader> reader;
  vtkNew<ErrorCounter> errors, warnings;
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->AddObserver(vtkCommand::WarningEvent, warnings);
  reader->UpdateInformation();
  EXPECT_EQ(errors->errors + warnings->errors, 0) << errors->last << warnings->last;
  EXPECT_FALSE(
      reader->GetOutputInformation(0)->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()));
  reader->Update();
  EXPECT_EQ(errors->errors, 1);
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 0);
}

// The engine's index stores each time as the sum of its steps (0.1 + 0.1 +
// 0.1 = 0.30000000000000004): the time asked, 0.3, is that frame, not the
// one before it.
TEST(FilterRobustness, SeriesReaderShowsTheFrameOfTheTimeAsked) {
  const fs::path dir = series_folder("times");
  fs::remove_all(dir);
  fs::create_directories(dir);
  runout::PvdIndex index((dir / "series.pvd").string());
  double time = 0;
  for (int k = 0; k < 4; ++k, time += 0.1) {
    const std::string name = "frame_0000" + std::to_string(k) + ".vtu";
    write_slab(dir / name, k);
    index.add(time, name);
  }
  ASSERT_NE(0.1 + 0.1 + 0.1, 0.3);
  vtkNew<vtkRunoutSeriesReader> reader;
  reader->SetFileName(index.path().c_str());
  auto shown = [&](double asked) {
    reader->UpdateTimeStep(asked);
    return reader->GetOutput()->GetInformation()->Get(vtkDataObject::DATA_TIME_STEP());
  };
  for (const double asked : {0.0, 0.1, 0.2, 0.3}) EXPECT_NEAR(shown(asked), asked, 1e-12) << asked;
  EXPECT_NEAR(shown(0.25), 0.2, 1e-12);  // between frames: the one before
  fs::remove_all(dir);
}
