#include "FrameArrays.h"

#include "runout/analysis/frame_base.hpp"
#include "runout/analysis/tuples.hpp"

#include "vtkAlgorithm.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkMath.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTable.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace runout::filters {

std::vector<double> coordinates_of(vtkPointSet* frame) {
  std::vector<double> xyz(3 * static_cast<size_t>(frame->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < frame->GetNumberOfPoints(); ++i) frame->GetPoint(i, &xyz[3 * i]);
  return xyz;
}

std::vector<Vec2> positions_of(vtkPointSet* frame) {
  return analysis::points_of(coordinates_of(frame));
}

std::vector<double> values_of(vtkDataArray* array) {
  const int components = array->GetNumberOfComponents();
  std::vector<double> values(static_cast<size_t>(array->GetNumberOfTuples()) * components);
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
    for (int c = 0; c < components; ++c) values[i * components + c] = array->GetComponent(i, c);
  return values;
}

std::string points_problem(vtkPointSet* frame) {
  return analysis::points_problem(coordinates_of(frame));
}

std::string point_array_problem(vtkPointSet* frame, vtkDataArray* array, const char* name,
                                int components, double limit) {
  return analysis::point_array_problem(name, values_of(array), array->GetNumberOfComponents(),
                                       static_cast<size_t>(frame->GetNumberOfPoints()),
                                       components, limit);
}

std::vector<double> component_of(vtkDataArray* array, int component) {
  std::vector<double> values(array->GetNumberOfTuples());
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
    values[i] = array->GetComponent(i, component);
  return values;
}

std::vector<double> magnitude_of(vtkDataArray* array) {
  return analysis::norms_of(values_of(array), array->GetNumberOfComponents());
}

std::vector<std::int64_t> ids_of(vtkDataArray* array) {
  std::vector<std::int64_t> ids(array->GetNumberOfTuples());
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
    ids[i] = static_cast<std::int64_t>(array->GetComponent(i, 0));
  return ids;
}

double particle_spacing_of(vtkDataObject* frame) {
  vtkDataArray* spacing = frame->GetFieldData()->GetArray("particle_spacing");
  const double value =
      spacing && spacing->GetNumberOfTuples() > 0 ? spacing->GetComponent(0, 0) : 0.0;
  return std::isfinite(value) ? value : 0.0;
}

std::optional<runout::Base> read_base_points(vtkDataObject* frame) {
  vtkDataArray* points = frame->GetFieldData()->GetArray("base_points");
  if (!points) return std::nullopt;
  return analysis::base_from_points(values_of(points), points->GetNumberOfComponents());
}

runout::Base base_of(vtkDataObject* frame) {
  if (std::optional<runout::Base> base = read_base_points(frame)) return *base;
  return analysis::x_axis_base();
}

double frame_time_of(vtkDataObject* frame) {
  vtkInformation* info = frame->GetInformation();
  if (info->Has(vtkDataObject::DATA_TIME_STEP())) return info->Get(vtkDataObject::DATA_TIME_STEP());
  vtkDataArray* time = frame->GetFieldData()->GetArray("TimeValue");
  return time && time->GetNumberOfTuples() > 0 ? time->GetComponent(0, 0) : vtkMath::Nan();
}

const char* selected_array_name(vtkAlgorithm* algorithm, int index) {
  vtkInformation* info = algorithm->GetInputArrayInformation(index);
  const char* name = info->Get(vtkDataObject::FIELD_NAME());
  return name ? name : "";
}

vtkSmartPointer<vtkDoubleArray> make_double_array(const char* name,
                                                  const std::vector<double>& values) {
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  return array;
}

vtkSmartPointer<vtkIntArray> make_int_array(const char* name, const std::vector<int>& values) {
  auto array = vtkSmartPointer<vtkIntArray>::New();
  array->SetName(name);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  return array;
}

void add_cell_column(vtkPolyData* cells, vtkTable* table, vtkAbstractArray* array) {
  cells->GetCellData()->AddArray(array);
  table->AddColumn(array);
}

void write_cells_and_table(vtkInformationVector* outputVector,
                           const std::vector<const std::vector<Vec2>*>& outlines, bool polygons,
                           const std::vector<vtkSmartPointer<vtkAbstractArray>>& columns) {
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> cells;
  for (const std::vector<Vec2>* outline : outlines) {
    cells->InsertNextCell(static_cast<vtkIdType>(outline->size()));
    for (const Vec2& p : *outline) cells->InsertCellPoint(points->InsertNextPoint(p.x, p.y, 0.0));
  }
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  output->SetPoints(points);
  if (polygons)
    output->SetPolys(cells);
  else
    output->SetLines(cells);
  vtkTable* table = vtkTable::GetData(outputVector, 1);
  for (const vtkSmartPointer<vtkAbstractArray>& column : columns)
    add_cell_column(output, table, column);
}

}  // namespace runout::filters
