#pragma once
// What a Runout particle frame carries (docs/output.md), read into the plain
// arrays that the filters' algorithms take, and their results back into VTK
// arrays. Shared by the VTK classes of the module; not wrapped.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "vtkDoubleArray.h"
#include "vtkIntArray.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include "runout/base.hpp"

#include "Vec2.h"

class vtkAbstractArray;
class vtkAlgorithm;
class vtkDataArray;
class vtkDataObject;
class vtkInformationVector;
class vtkPointSet;
class vtkPolyData;
class vtkTable;

namespace runout::filters {

// The points' (x, y): a run is two-dimensional, z is 0.
std::vector<Vec2> positions_of(vtkPointSet* frame);

// What makes the frame's points unusable, or "": a coordinate that is not
// finite (a NaN or infinity in a position would become an index or a bin).
std::string points_problem(vtkPointSet* frame);

// What makes `array` unusable as the point array `name` of `frame` read
// with `components` components, or "": a tuple count other than the
// frame's point count, fewer components, or a value that is not finite or
// exceeds `limit` in magnitude (particle ids must fit 64-bit integers).
std::string point_array_problem(vtkPointSet* frame, vtkDataArray* array, const char* name,
                                int components, double limit = 1.7976931348623157e308);

// What makes the points too far apart for neighbour searches at `spacing`,
// or "": a bounding box wider than 2^30 spacings, whose cell indices would
// not fit the 32 bits of PointGrid's keys (any real slide is far smaller).
std::string extent_problem(const std::vector<Vec2>& points, double spacing);

// Component `component` of every tuple.
std::vector<double> component_of(vtkDataArray* array, int component = 0);

// Euclidean norm of every tuple.
std::vector<double> magnitude_of(vtkDataArray* array);

// The array as 64-bit integers (particle_id).
std::vector<std::int64_t> ids_of(vtkDataArray* array);

// The `particle_spacing` field data (h / ppc), 0 when absent or not a
// finite number.
double particle_spacing_of(vtkDataObject* frame);

// The base from the `base_points` field data, as the engine wrote it: two
// points at one height are its planar base (s = x, as the engine measures
// it), more points its polyline. nullopt without base_points, with fewer
// than two points, with x not strictly increasing or with a coordinate
// that is not finite.
std::optional<runout::Base> read_base_points(vtkDataObject* frame);

// read_base_points, or the x axis (s = x, d = y) when it gives none.
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

// A column of the band and block outputs: its name, its array type, and
// how it reads an item (number for Double and Int, text for String).
template <class Item>
struct ItemColumn {
  enum Kind { Double, Int, String };
  ItemColumn(const char* name, Kind kind, std::function<double(const Item&)> number)
      : name(name), kind(kind), number(std::move(number)) {}
  ItemColumn(const char* name, std::function<std::string(const Item&)> text)
      : name(name), kind(String), text(std::move(text)) {}
  const char* name;
  Kind kind;
  std::function<double(const Item&)> number;
  std::function<std::string(const Item&)> text;
};

// write_cells_and_table with one cell and row per item: the cell through
// the item's `outline` points, then the column `id_name` (the item's
// index, an int) and `columns`.
template <class Item>
void write_items(vtkInformationVector* outputVector, const std::vector<Item>& items,
                 std::vector<Vec2> Item::*outline, bool polygons, const char* id_name,
                 const std::vector<ItemColumn<Item>>& columns) {
  const size_t n = items.size();
  std::vector<const std::vector<Vec2>*> outlines(n);
  std::vector<int> id(n);
  for (size_t b = 0; b < n; ++b) {
    outlines[b] = &(items[b].*outline);
    id[b] = static_cast<int>(b);
  }
  std::vector<vtkSmartPointer<vtkAbstractArray>> arrays{make_int_array(id_name, id)};
  for (const ItemColumn<Item>& column : columns) {
    if (column.kind == ItemColumn<Item>::String) {
      auto text = vtkSmartPointer<vtkStringArray>::New();
      text->SetName(column.name);
      text->SetNumberOfValues(static_cast<vtkIdType>(n));
      for (size_t b = 0; b < n; ++b) text->SetValue(static_cast<vtkIdType>(b), column.text(items[b]));
      arrays.push_back(text);
      continue;
    }
    std::vector<double> values(n);
    for (size_t b = 0; b < n; ++b) values[b] = column.number(items[b]);
    if (column.kind == ItemColumn<Item>::Int)
      arrays.push_back(make_int_array(column.name, std::vector<int>(values.begin(), values.end())));
    else
      arrays.push_back(make_double_array(column.name, values));
  }
  write_cells_and_table(outputVector, outlines, polygons, arrays);
}

}  // namespace runout::filters
