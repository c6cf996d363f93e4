// vtkRunoutRunoutDistance on small synthetic frames.
#include <gtest/gtest.h>

#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTable.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>
#include <string>
#include <vector>

#include "vtkRunoutRunoutDistance.h"

namespace {

// Points at x (y = 1, z = 0) and, unless x0 is empty, initial positions at x0.
template <class PointSet>
vtkNew<PointSet> frame(const std::vector<double>& x, const std::vector<double>& x0) {
  vtkNew<PointSet> data;
  vtkNew<vtkPoints> points;
  for (const double xi : x) points->InsertNextPoint(xi, 1.0, 0.0);
  data->SetPoints(points);
  if (!x0.empty()) {
    vtkNew<vtkDoubleArray> initial;
    initial->SetName("initial_position");
    initial->SetNumberOfComponents(3);
    for (const double xi : x0) initial->InsertNextTuple3(xi, 2.0, 0.0);
    data->GetPointData()->AddArray(initial);
  }
  return data;
}

void set_time_value(vtkDataObject* data, double time) {
  vtkNew<vtkDoubleArray> t;
  t->SetName("TimeValue");
  t->InsertNextValue(time);
  data->GetFieldData()->AddArray(t);
}

double column(vtkTable* table, const char* name) {
  vtkAbstractArray* a = table->GetColumnByName(name);
  EXPECT_NE(a, nullptr) << name;
  return a ? a->GetVariantValue(0).ToDouble() : NAN;
}

// Counts the filter's errors instead of printing them.
class ErrorCounter : public vtkCommand {
 public:
  static ErrorCounter* New() { return new ErrorCounter; }
  void Execute(vtkObject*, unsigned long, void* message) override {
    ++errors;
    last = static_cast<const char*>(message);
  }
  int errors = 0;
  std::string last;
};

}  // namespace

TEST(RunoutDistance, MeasuresUnstructuredGrid) {
  auto data = frame<vtkUnstructuredGrid>({3.0, -1.0, 7.5, 2.0}, {0.0, 5.0, 1.0, 2.0});
  set_time_value(data, 4.5);
  vtkNew<vtkRunoutRunoutDistance> filter;
  filter->SetInputData(data);
  filter->Update();
  vtkTable* out = filter->GetOutput();
  ASSERT_EQ(out->GetNumberOfRows(), 1);
  ASSERT_EQ(out->GetNumberOfColumns(), 5);
  EXPECT_EQ(column(out, "time"), 4.5);
  EXPECT_EQ(column(out, "toe_x"), 7.5);
  EXPECT_EQ(column(out, "rear_x"), -1.0);
  EXPECT_EQ(column(out, "length"), 8.5);
  EXPECT_EQ(column(out, "runout"), 2.5);
}

TEST(RunoutDistance, PipelineTimeWinsOverTimeValueOnPolyData) {
  auto data = frame<vtkPolyData>({1.0, 2.0}, {0.5, 1.0});
  set_time_value(data, 4.5);
  data->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), 6.0);
  vtkNew<vtkRunoutRunoutDistance> filter;
  filter->SetInputData(data);
  filter->Update();
  vtkTable* out = filter->GetOutput();
  ASSERT_EQ(out->GetNumberOfRows(), 1);
  EXPECT_EQ(column(out, "time"), 6.0);
  EXPECT_EQ(column(out, "runout"), 1.0);
}

TEST(RunoutDistance, NoTimeAtAllIsNaN) {
  auto data = frame<vtkPolyData>({1.0}, {1.0});
  vtkNew<vtkRunoutRunoutDistance> filter;
  filter->SetInputData(data);
  filter->Update();
  ASSERT_EQ(filter->GetOutput()->GetNumberOfRows(), 1);
  EXPECT_TRUE(std::isnan(column(filter->GetOutput(), "time")));
  EXPECT_EQ(column(filter->GetOutput(), "length"), 0.0);
}

TEST(RunoutDistance, MissingInitialPositionIsAnErrorWithEmptyOutput) {
  vtkNew<vtkRunoutRunoutDistance> filter;
  vtkNew<ErrorCounter> counter;
  filter->AddObserver(vtkCommand::ErrorEvent, counter);

  // A good frame first, so the empty output is not just the initial state.
  filter->SetInputData(frame<vtkUnstructuredGrid>({1.0}, {0.0}));
  filter->Update();
  ASSERT_EQ(filter->GetOutput()->GetNumberOfRows(), 1);

  filter->SetInputData(frame<vtkUnstructuredGrid>({1.0, 2.0}, {}));
  filter->Update();
  EXPECT_EQ(counter->errors, 1);
  EXPECT_NE(counter->last.find("initial_position"), std::string::npos) << counter->last;
  EXPECT_EQ(filter->GetOutput()->GetNumberOfRows(), 0);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfColumns(), 0);
}

TEST(RunoutDistance, EmptyFrameGivesEmptyTableWithoutError) {
  vtkNew<vtkRunoutRunoutDistance> filter;
  vtkNew<ErrorCounter> counter;
  filter->AddObserver(vtkCommand::ErrorEvent, counter);
  auto data = frame<vtkUnstructuredGrid>({}, {});
  vtkNew<vtkDoubleArray> initial;  // present but empty, as the engine writes it
  initial->SetName("initial_position");
  initial->SetNumberOfComponents(3);
  data->GetPointData()->AddArray(initial);
  filter->SetInputData(data);
  filter->Update();
  EXPECT_EQ(counter->errors, 0);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfRows(), 0);
}
