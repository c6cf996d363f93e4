// The plastic strain, shear band and horst/graben filters as VTK classes
// (pipeline time, arrays, robustness) on synthetic particle lattices, and
// what Runout Morphology calls the horst/graben filter's grabens; their
// algorithms are tested without VTK in test_analysis_algorithms.cpp.
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

#include "filter_fixtures.hpp"
#include "lattice_fixtures.hpp"
#include "vtkRunoutHorstGraben.h"
#include "vtkRunoutMorphology.h"
#include "vtkRunoutPlasticStrain.h"
#include "vtkRunoutShearBands.h"

using namespace runout::lattice_fixtures;
using runout::filter_fixtures::ErrorCounter;
using runout::filter_fixtures::value;

namespace {

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

// One word, one meaning: in a frame where Runout Horsts And Grabens types a
// block graben (two bands converging downwards under a flat surface),
// Runout Morphology, which reads only the surface and sees no trough there,
// must not report a count under the name "graben" that says otherwise.
TEST(HorstGrabenFilter, MorphologyNamesNoOtherGrabenCount) {
  Slab slab;
  slab.length = 40;
  slab.bands = {{18.0, 45.0, 0.4}, {22.0, -45.0, 0.4}};
  auto frame = to_frame(make_lattice(slab), slab.h);
  // What Runout Morphology reads besides the positions: the particles at
  // rest, of unit mass, where they started.
  runout::filter_fixtures::MorphologyArrays arrays;
  for (vtkIdType i = 0; i < frame->GetNumberOfPoints(); ++i) {
    arrays.velocity->InsertNextTuple3(0.0, 0.0, 0.0);
    arrays.mass->InsertNextValue(1.0);
    arrays.initial->InsertNextTuple(frame->GetPoint(i));
  }
  arrays.add_to(frame->GetPointData());

  vtkNew<vtkRunoutHorstGraben> blocks;
  blocks->SetInputData(frame);
  blocks->Update();
  vtkTable* typed = vtkTable::SafeDownCast(blocks->GetOutputDataObject(1));
  int grabens = 0;
  for (vtkIdType row = 0; row < typed->GetNumberOfRows(); ++row)
    grabens += value(typed, "type_code", row) == 2;
  ASSERT_EQ(grabens, 1);

  vtkNew<vtkRunoutMorphology> morphology;
  morphology->SetInputData(frame);
  morphology->Update();
  vtkTable* row = vtkTable::SafeDownCast(morphology->GetOutputDataObject(1));
  ASSERT_EQ(row->GetNumberOfRows(), 1);
  EXPECT_EQ(value(row, "troughs"), 0);
  for (vtkIdType c = 0; c < row->GetNumberOfColumns(); ++c) {
    const std::string name = row->GetColumnName(c);
    if (name.find("graben") != std::string::npos && name.rfind("initial", 0) != 0) {
      EXPECT_EQ(value(row, name.c_str()), grabens) << name;
    }
  }
}
