#include "MorphologyFrame.h"

#include "FrameArrays.h"

#include "vtkAlgorithm.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkStringArray.h"
#include "vtkTable.h"

#include <optional>
#include <utility>
#include <vector>

namespace runout::filters {

namespace {

// The point array `name` with `components` components into `out`; "" or
// what is missing or wrong with it.
std::string read_point_array(vtkPointSet* frame, const char* name, int components,
                             vtkDataArray*& out) {
  out = frame->GetPointData()->GetArray(name);
  if (!out)
    return std::string("The input has no point array \"") + name + "\" with " +
           std::to_string(components) + " component(s) per point: not a Runout particle frame.";
  return point_array_problem(frame, out, name, components);
}

struct ParticleFrame {
  runout::Particles particles;      // x, y, vx, vy, mass, x0, y0
  std::optional<runout::Base> base;
  double spacing = 0;               // h / ppc, 0 when the frame has none
};

// The frame in the engine's types; "" or the error.
std::string read_particle_frame(vtkPointSet* frame, const MorphologyArrays& arrays,
                                ParticleFrame& out) {
  vtkDataArray *velocity, *mass, *initial;
  for (const std::string& problem :
       {points_problem(frame), read_point_array(frame, arrays.velocity.c_str(), 3, velocity),
        read_point_array(frame, arrays.mass.c_str(), 1, mass),
        read_point_array(frame, arrays.initial_position.c_str(), 3, initial)})
    if (!problem.empty()) return problem;
  out.spacing = particle_spacing_of(frame);
  out.base = read_base_points(frame);
  out.particles = analysis::morphology_particles(
      coordinates_of(frame), values_of(velocity), velocity->GetNumberOfComponents(), values_of(mass),
      mass->GetNumberOfComponents(), values_of(initial), initial->GetNumberOfComponents());
  return "";
}

}  // namespace

MorphologyArrays selected_morphology_arrays(vtkAlgorithm* algorithm) {
  MorphologyArrays arrays;
  for (auto [index, name] : {std::pair<int, std::string*>{0, &arrays.velocity},
                             {1, &arrays.mass}, {2, &arrays.initial_position}}) {
    const std::string selected = selected_array_name(algorithm, index);
    if (!selected.empty()) *name = selected;
  }
  return arrays;
}

void select_morphology_arrays(vtkAlgorithm* algorithm) {
  const MorphologyArrays arrays;
  const std::string* names[] = {&arrays.velocity, &arrays.mass, &arrays.initial_position};
  for (int index = 0; index < 3; ++index)
    algorithm->SetInputArrayToProcess(index, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS,
                                      names[index]->c_str());
}

std::string measure_point_set(vtkPointSet* frame, double bin_spacings,
                              analysis::FrameMorphology& out, const MorphologyArrays& arrays) {
  out = analysis::FrameMorphology();
  if (frame->GetNumberOfPoints() == 0) return "";
  ParticleFrame read;
  std::string error = read_particle_frame(frame, arrays, read);
  if (error.empty())
    error = analysis::morphology_problem(read.particles, read.base, read.spacing, bin_spacings,
                                         arrays.mass);
  if (!error.empty()) return error;
  out = analysis::measure_frame(read.particles, read.base->view(), read.spacing,
                                bin_spacings * read.spacing);
  return "";
}

void add_morphology_columns(vtkTable* table) {
  vtkNew<vtkDoubleArray> time;
  time->SetName(analysis::kTimeColumn);
  table->AddColumn(time);
  for (const auto& c : analysis::morphology_columns()) {
    vtkSmartPointer<vtkAbstractArray> column;
    if (c.kind == c.Double) column = vtkSmartPointer<vtkDoubleArray>::New();
    if (c.kind == c.Int) column = vtkSmartPointer<vtkIntArray>::New();
    if (c.kind == c.String) column = vtkSmartPointer<vtkStringArray>::New();
    column->SetName(c.name);
    table->AddColumn(column);
  }
}

void append_morphology_row(vtkTable* table, double time, const analysis::FrameMorphology& m) {
  vtkDoubleArray::SafeDownCast(table->GetColumnByName(analysis::kTimeColumn))->InsertNextValue(time);
  for (const auto& c : analysis::morphology_columns()) {
    vtkAbstractArray* column = table->GetColumnByName(c.name);
    if (c.kind == c.Double) vtkDoubleArray::SafeDownCast(column)->InsertNextValue(c.number(m));
    if (c.kind == c.Int)
      vtkIntArray::SafeDownCast(column)->InsertNextValue(static_cast<int>(c.number(m)));
    if (c.kind == c.String) vtkStringArray::SafeDownCast(column)->InsertNextValue(c.text(m));
  }
}

}  // namespace runout::filters
