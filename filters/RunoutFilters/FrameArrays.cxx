#include "FrameArrays.h"

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

std::vector<Vec2> positions_of(vtkPointSet* frame) {
  std::vector<Vec2> points(frame->GetNumberOfPoints());
  for (vtkIdType i = 0; i < frame->GetNumberOfPoints(); ++i) {
    double p[3];
    frame->GetPoint(i, p);
    points[i] = {p[0], p[1]};
  }
  return points;
}

std::string points_problem(vtkPointSet* frame) {
  for (vtkIdType i = 0; i < frame->GetNumberOfPoints(); ++i) {
    double p[3];
    frame->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      return "Point " + std::to_string(i) + " has a coordinate that is not a finite number.";
  }
  return "";
}

std::string point_array_problem(vtkPointSet* frame, vtkDataArray* array, const char* name,
                                int components, double limit) {
  const std::string quoted = std::string("The point array \"") + name + "\"";
  if (array->GetNumberOfTuples() != frame->GetNumberOfPoints())
    return quoted + " has " + std::to_string(array->GetNumberOfTuples()) + " tuples for " +
           std::to_string(frame->GetNumberOfPoints()) + " points.";
  if (array->GetNumberOfComponents() < components)
    return quoted + " has " + std::to_string(array->GetNumberOfComponents()) +
           " component(s), fewer than " + std::to_string(components) + ".";
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
    for (int c = 0; c < array->GetNumberOfComponents(); ++c) {
      const double v = array->GetComponent(i, c);
      if (!(std::abs(v) <= limit))
        return quoted + " has a value that is not a finite number" +
               (limit < 1.7976931348623157e308 ? " within +-" + std::to_string(limit) : "") +
               " at point " + std::to_string(i) + ".";
    }
  return "";
}

std::string extent_problem(const std::vector<Vec2>& points, double spacing) {
  if (points.empty()) return "";
  Vec2 lo = points[0], hi = points[0];
  for (const Vec2& p : points) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  const double reach = std::max({std::abs(lo.x), std::abs(lo.y), std::abs(hi.x), std::abs(hi.y)});
  if (reach / spacing < 1073741824.0) return "";
  return "The points reach " + std::to_string(reach) + " from the origin, more than 2^30 " +
         "particle spacings of " + std::to_string(spacing) + ": not a Runout particle frame.";
}

std::vector<double> component_of(vtkDataArray* array, int component) {
  std::vector<double> values(array->GetNumberOfTuples());
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
    values[i] = array->GetComponent(i, component);
  return values;
}

std::vector<double> magnitude_of(vtkDataArray* array) {
  std::vector<double> values(array->GetNumberOfTuples());
  const int components = array->GetNumberOfComponents();
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i) {
    double sum = 0;
    for (int c = 0; c < components; ++c) sum += array->GetComponent(i, c) * array->GetComponent(i, c);
    values[i] = std::sqrt(sum);
  }
  return values;
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
  if (!points || points->GetNumberOfComponents() < 2 || points->GetNumberOfTuples() < 2)
    return std::nullopt;
  runout::BaseSpec spec;
  spec.kind = runout::BaseKind::Polyline;
  for (vtkIdType k = 0; k < points->GetNumberOfTuples(); ++k) {
    const Eigen::Vector2d p(points->GetComponent(k, 0), points->GetComponent(k, 1));
    if (!p.allFinite()) return std::nullopt;
    // A repeated point would make a segment without a direction.
    if (!spec.points.empty() && !(p.x() > spec.points.back().x())) return std::nullopt;
    spec.points.push_back(p);
  }
  if (spec.points.size() == 2 && spec.points[0].y() == spec.points[1].y())
    spec.kind = runout::BaseKind::Planar;
  return runout::Base(spec, spec.points[0].y());
}

runout::Base base_of(vtkDataObject* frame) {
  if (std::optional<runout::Base> base = read_base_points(frame)) return *base;
  runout::BaseSpec x_axis;
  x_axis.kind = runout::BaseKind::Planar;
  return runout::Base(x_axis, 0.0);
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
