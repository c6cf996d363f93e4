#pragma once
// What a Runout particle frame carries (docs/output.md), read into the plain
// arrays that the analysis' algorithms take (runout_analysis), and their
// results back into VTK arrays. Shared by the VTK classes of the module; not
// wrapped. The checks and the base are the analysis' own (frame_checks.hpp,
// frame_base.hpp), so a frame is read as `runout analyse` reads it.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "vtkDoubleArray.h"
#include "vtkIntArray.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include "runout/analysis/frame_checks.hpp"
#include "runout/analysis/result_columns.hpp"
#include "runout/analysis/shear_bands.hpp"
#include "runout/analysis/vec2.hpp"
#include "runout/mpm/base.hpp"

class vtkAbstractArray;
class vtkAlgorithm;
class vtkDataArray;
class vtkDataObject;
class vtkInformationVector;
class vtkPointSet;
class vtkPolyData;
class vtkTable;

namespace runout::filters {

using analysis::Vec2;

// A frame as the band search read it, with its bands: what
// vtkRunoutHorstGraben builds its blocks from.
struct BandFrame {
  std::vector<Vec2> points;
  std::vector<double> xi;
  runout::Base base{runout::BaseSpec{}, 0.0};  // the x axis until read
  double spacing = 0;
  std::vector<analysis::ShearBand> bands;
};

// The points' (x, y, z), interleaved.
std::vector<double> coordinates_of(vtkPointSet* frame);

// The points' (x, y): a run is two-dimensional, z is 0.
std::vector<Vec2> positions_of(vtkPointSet* frame);

// analysis::points_problem of the frame's points.
std::string points_problem(vtkPointSet* frame);

// analysis::point_array_problem of `array` as the point array `name` of
// `frame` read with `components` components (particle ids within
// analysis::kParticleIdLimit).
std::string point_array_problem(vtkPointSet* frame, vtkDataArray* array, const char* name,
                                int components, double limit = analysis::kAnyFinite);

// Every component of every tuple, interleaved as VTK stores them (the
// layout of analysis/tuples.hpp).
std::vector<double> values_of(vtkDataArray* array);

// Component `component` of every tuple.
std::vector<double> component_of(vtkDataArray* array, int component = 0);

// Euclidean norm of every tuple.
std::vector<double> magnitude_of(vtkDataArray* array);

// The array as 64-bit integers (particle_id).
std::vector<std::int64_t> ids_of(vtkDataArray* array);

// The `particle_spacing` field data (h / ppc), 0 when absent or not a
// finite number.
double particle_spacing_of(vtkDataObject* frame);

// The base from the `base_points` field data (analysis::base_from_points);
// nullopt without it or when it is unusable.
std::optional<runout::Base> read_base_points(vtkDataObject* frame);

// read_base_points, or the x axis (analysis::x_axis_base) when it gives none.
runout::Base base_of(vtkDataObject* frame);

// The time of the frame: its data time step, else its TimeValue field data,
// else NaN.
double frame_time_of(vtkDataObject* frame);

// Name of the array that input array `index` of `algorithm` selects
// ("" when none is set), for error messages.
const char* selected_array_name(vtkAlgorithm* algorithm, int index);

vtkSmartPointer<vtkDoubleArray> make_double_array(const char* name,
                                                  const std::vector<double>& values);
vtkSmartPointer<vtkIntArray> make_int_array(const char* name, const std::vector<int>& values);

// Adds `array` both as a cell array of `cells` and as a column of `table`:
// the band and block filters give the same values per cell and per row.
void add_cell_column(vtkPolyData* cells, vtkTable* table, vtkAbstractArray* array);

// The two outputs of the band and block filters: port 0 a vtkPolyData with
// one cell per outline through its points (a polyline, or a polygon when
// `polygons`), port 1 a vtkTable; each of `columns` goes to both, as a cell
// array and as a column (add_cell_column), in order.
void write_cells_and_table(vtkInformationVector* outputVector,
                           const std::vector<const std::vector<Vec2>*>& outlines, bool polygons,
                           const std::vector<vtkSmartPointer<vtkAbstractArray>>& columns);

// write_cells_and_table with one cell and row per item: the cell through
// the item's `outline` points, then the column `id_name` (the item's
// index, an int) and `columns` (result_columns.hpp).
template <class Item>
void write_items(vtkInformationVector* outputVector, const std::vector<Item>& items,
                 std::vector<Vec2> Item::*outline, bool polygons, const char* id_name,
                 const std::vector<analysis::Column<Item>>& columns) {
  const size_t n = items.size();
  std::vector<const std::vector<Vec2>*> outlines(n);
  std::vector<int> id(n);
  for (size_t b = 0; b < n; ++b) {
    outlines[b] = &(items[b].*outline);
    id[b] = static_cast<int>(b);
  }
  std::vector<vtkSmartPointer<vtkAbstractArray>> arrays{make_int_array(id_name, id)};
  for (const analysis::Column<Item>& column : columns) {
    if (column.kind == analysis::Column<Item>::String) {
      auto text = vtkSmartPointer<vtkStringArray>::New();
      text->SetName(column.name);
      text->SetNumberOfValues(static_cast<vtkIdType>(n));
      for (size_t b = 0; b < n; ++b) text->SetValue(static_cast<vtkIdType>(b), column.text(items[b]));
      arrays.push_back(text);
      continue;
    }
    std::vector<double> values(n);
    for (size_t b = 0; b < n; ++b) values[b] = column.number(items[b]);
    if (column.kind == analysis::Column<Item>::Int)
      arrays.push_back(make_int_array(column.name, std::vector<int>(values.begin(), values.end())));
    else
      arrays.push_back(make_double_array(column.name, values));
  }
  write_cells_and_table(outputVector, outlines, polygons, arrays);
}

}  // namespace runout::filters
