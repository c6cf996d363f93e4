#pragma once
// Helpers shared by the GoogleTest suites of the ParaView filters
// (test_strain_filters.cpp, test_morphology_filter.cpp).
#include <gtest/gtest.h>

#include <vtkAbstractArray.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkTable.h>
#include <vtkVariant.h>

#include <cmath>
#include <string>

namespace runout::filter_fixtures {

// Counts an algorithm's errors instead of printing them.
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

// Row `row` of the table's column `name` as a double: NaN, after a failed
// expectation, without the column; NaN without the row.
inline double value(vtkTable* table, const char* name, vtkIdType row = 0) {
  vtkAbstractArray* a = table->GetColumnByName(name);
  EXPECT_NE(a, nullptr) << name;
  return a && row < a->GetNumberOfTuples() ? a->GetVariantValue(row).ToDouble() : NAN;
}

// The point arrays Runout Morphology reads, named as the engine names them
// (docs/output.md), to fill a tuple a particle and add to a frame.
struct MorphologyArrays {
  vtkNew<vtkDoubleArray> velocity, mass, initial;
  MorphologyArrays() {
    velocity->SetName("velocity");
    velocity->SetNumberOfComponents(3);
    mass->SetName("mass");
    initial->SetName("initial_position");
    initial->SetNumberOfComponents(3);
  }
  void add_to(vtkPointData* data) {
    data->AddArray(velocity);
    data->AddArray(mass);
    data->AddArray(initial);
  }
};

}  // namespace runout::filter_fixtures
