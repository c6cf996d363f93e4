#pragma once
// What a Runout particle frame carries (docs/output.md), read into the plain
// arrays that the filters' algorithms take, and their results back into VTK
// arrays. Shared by the VTK classes of the module; not wrapped.
#include <cstdint>
#include <optional>
#include <vector>

#include "vtkDoubleArray.h"
#include "vtkIntArray.h"
#include "vtkSmartPointer.h"

#include "runout/base.hpp"

#include "Vec2.h"

class vtkAbstractArray;
class vtkAlgorithm;
class vtkDataArray;
class vtkDataObject;
class vtkPointSet;
class vtkPolyData;
class vtkTable;

namespace runout::filters {

// The points' (x, y): a run is two-dimensional, z is 0.
std::vector<Vec2> positions_of(vtkPointSet* frame);

// Component `component` of every tuple.
std::vector<double> component_of(vtkDataArray* array, int component = 0);

// Euclidean norm of every tuple.
std::vector<double> magnitude_of(vtkDataArray* array);

// The array as 64-bit integers (particle_id).
std::vector<std::int64_t> ids_of(vtkDataArray* array);

// The `particle_spacing` field data (h / ppc), 0 when absent.
double particle_spacing_of(vtkDataObject* frame);

// The base from the `base_points` field data, as the engine wrote it: two
// points at one height are its planar base (s = x, as the engine measures
// it), more points its polyline. nullopt without base_points, with fewer
// than two points or with x not strictly increasing.
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

}  // namespace runout::filters
