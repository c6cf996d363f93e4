#pragma once
// A Runout particle frame (docs/output.md) read into the engine's types for
// the analysis' morphology (morphology_rules.hpp), and the morphology table
// that vtkRunoutMorphology (one row) and vtkRunoutMorphologyHistory (one row
// per time step) output, with the columns of result_columns.hpp, as `runout
// analyse` writes them. Not wrapped.
#include <string>

#include "runout/analysis/morphology_rules.hpp"

class vtkAlgorithm;
class vtkPointSet;
class vtkTable;

namespace runout::filters {

// The point arrays the morphology reads, by name: the filters' array
// selections (input arrays 0, 1, 2), the engine's names by default.
struct MorphologyArrays {
  std::string velocity = "velocity";
  std::string mass = "mass";
  std::string initial_position = "initial_position";
};

// The names input arrays 0, 1 and 2 of `algorithm` select; the engine's
// name for one that selects none.
MorphologyArrays selected_morphology_arrays(vtkAlgorithm* algorithm);

// Points input arrays 0, 1 and 2 of `algorithm` at the engine's names: the
// defaults of a filter that reads the morphology.
void select_morphology_arrays(vtkAlgorithm* algorithm);

// The morphology of a frame: measure_frame with profile bins of
// bin_spacings particle spacings. Reads the points, the point arrays
// `arrays` names, and the field data base_points (read_base_points) and
// particle_spacing. Returns "", else what is missing or wrong, naming the
// array (analysis::morphology_problem). No points: all zero, undetermined,
// and no array is needed.
std::string measure_point_set(vtkPointSet* frame, double bin_spacings,
                              analysis::FrameMorphology& out,
                              const MorphologyArrays& arrays = MorphologyArrays());

// Adds the (empty) columns of the morphology table.
void add_morphology_columns(vtkTable* table);

// Appends the row of one frame at `time`; a frame without particles gets
// NaN lengths and velocities.
void append_morphology_row(vtkTable* table, double time, const analysis::FrameMorphology& m);

}  // namespace runout::filters
