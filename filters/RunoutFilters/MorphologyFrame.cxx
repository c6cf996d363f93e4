#include "MorphologyFrame.h"

#include "FrameArrays.h"

#include "vtkAlgorithm.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkStringArray.h"
#include "vtkTable.h"

#include <algorithm>
#include <cmath>
#include <functional>
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

// The base's reach against the spacing, as for the points: the profile
// bins run along it.
std::string base_extent_problem(const runout::Base& base, double spacing) {
  const runout::BaseView view = base.view();
  std::vector<Vec2> points{{0.0, view.y0}};
  for (int k = 0; k < view.n; ++k) points.push_back({view.px[k], view.py[k]});
  return extent_problem(points, spacing);
}

struct ParticleFrame {
  runout::Particles particles;      // x, y, vx, vy, mass, x0, y0
  std::optional<runout::Base> base;
  double spacing = 0;               // h / ppc
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
  if (!(out.spacing > 0))
    return "The input has no field data \"particle_spacing\" (h / ppc, > 0): not a Runout "
           "particle frame.";
  out.base = read_base_points(frame);
  if (!out.base)
    return "The input has no field data \"base_points\" (the base polyline: at least two "
           "(x, y, 0) points, x strictly increasing): not a Runout particle frame.";

  const std::vector<Vec2> points = positions_of(frame);
  for (const std::string& problem :
       {extent_problem(points, out.spacing), base_extent_problem(*out.base, out.spacing)})
    if (!problem.empty()) return problem;

  runout::Particles& p = out.particles;
  p.x.clear();
  p.y.clear();
  for (const Vec2& xy : points) {
    p.x.push_back(xy.x);
    p.y.push_back(xy.y);
  }
  p.vx = component_of(velocity, 0);
  p.vy = component_of(velocity, 1);
  p.mass = component_of(mass, 0);
  p.x0 = component_of(initial, 0);
  p.y0 = component_of(initial, 1);
  // measure_slide divides by the masses.
  for (const double m : p.mass)
    if (!(m > 0 && std::isfinite(m)))
      return "The point array \"" + arrays.mass + "\" (the mass) must be > 0 everywhere.";
  return "";
}

// A column of the morphology table: its name and a frame's value in it.
template <class T>
struct Column {
  const char* name;
  std::function<T(const FrameMorphology&)> value;
};

// The double columns after Time, in table order.
const std::vector<Column<double>>& measure_columns() {
  static const std::vector<Column<double>> columns = {
      {"toe", [](const FrameMorphology& m) { return m.now.toe_s; }},
      {"rear", [](const FrameMorphology& m) { return m.now.rear_s; }},
      {"length", [](const FrameMorphology& m) { return m.now.length; }},
      {"max_thickness", [](const FrameMorphology& m) { return m.now.max_thickness; }},
      {"runout", [](const FrameMorphology& m) { return m.runout; }},
      {"toe_velocity", [](const FrameMorphology& m) { return m.now.toe_velocity; }},
      {"centroid_x", [](const FrameMorphology& m) { return m.now.centroid_x; }},
      {"centroid_y", [](const FrameMorphology& m) { return m.now.centroid_y; }},
      {"centroid_s", [](const FrameMorphology& m) { return m.now.centroid_s; }},
      {"centroid_velocity", [](const FrameMorphology& m) { return m.now.centroid_velocity_s; }},
      {"outside_mass", [](const FrameMorphology& m) { return m.now.outside_mass; }},
      {"initial_toe", [](const FrameMorphology& m) { return m.initial.toe_s; }},
      {"length_ratio", [](const FrameMorphology& m) { return m.evidence.length_ratio; }},
      {"thickness_ratio", [](const FrameMorphology& m) { return m.evidence.thickness_ratio; }},
  };
  return columns;
}

// The int columns after them.
const std::vector<Column<int>>& count_columns() {
  static const std::vector<Column<int>> columns = {
      {"particles", [](const FrameMorphology& m) { return m.now.particles; }},
      {"grabens", [](const FrameMorphology& m) { return m.evidence.grabens; }},
      {"initial_grabens", [](const FrameMorphology& m) { return m.evidence.initial_grabens; }},
      {"mechanism_id", [](const FrameMorphology& m) { return static_cast<int>(m.mechanism); }},
  };
  return columns;
}

// Profile bins a frame may need: far beyond any slide (a 10 km runout in
// 0.5 m bins is 2e4), well short of exhausting memory (48 B each), which a
// single stray point far from the slide would otherwise do.
constexpr double kMaxProfileBins = 1e6;

double span(const std::vector<double>& x, const std::vector<double>& y) {
  const auto [x_lo, x_hi] = std::minmax_element(x.begin(), x.end());
  const auto [y_lo, y_hi] = std::minmax_element(y.begin(), y.end());
  return std::hypot(*x_hi - *x_lo, *y_hi - *y_lo);
}

// The profile bins of width `width` run along the base over the points,
// now and (for the initial morphology) at their initial positions: "" or
// why there would be too many.
std::string bins_problem(const runout::Particles& p, double width) {
  const double widest = std::max(span(p.x, p.y), span(p.x0, p.y0));
  if (widest / width <= kMaxProfileBins) return "";
  return "The points (or their initial positions) span " + std::to_string(widest) +
         " m, more than 10^6 profile bins of " + std::to_string(width) +
         " m: a stray point? (BinSpacings sets the bins.)";
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

std::string measure_point_set(vtkPointSet* frame, double bin_spacings, FrameMorphology& out,
                              const MorphologyArrays& arrays) {
  out = FrameMorphology();
  if (frame->GetNumberOfPoints() == 0) return "";
  ParticleFrame particles;
  std::string error = read_particle_frame(frame, arrays, particles);
  if (error.empty())
    error = bins_problem(particles.particles,
                         std::min(bin_spacings, runout::kMainBodyBinSpacings) * particles.spacing);
  if (!error.empty()) return error;
  out = measure_frame(particles.particles, particles.base->view(), particles.spacing,
                      bin_spacings * particles.spacing);
  return "";
}

void add_morphology_columns(vtkTable* table) {
  // "Time", not "time": ParaView's line chart takes a column of that name
  // as its x axis, so the history plots against time as it opens.
  vtkNew<vtkDoubleArray> time;
  time->SetName("Time");
  table->AddColumn(time);
  for (const Column<double>& c : measure_columns()) {
    vtkNew<vtkDoubleArray> column;
    column->SetName(c.name);
    table->AddColumn(column);
  }
  for (const Column<int>& c : count_columns()) {
    vtkNew<vtkIntArray> column;
    column->SetName(c.name);
    table->AddColumn(column);
  }
  vtkNew<vtkStringArray> mechanism;
  mechanism->SetName("mechanism");
  table->AddColumn(mechanism);
}

void append_morphology_row(vtkTable* table, double time, const FrameMorphology& m) {
  const bool empty = m.now.particles == 0;
  vtkDoubleArray::SafeDownCast(table->GetColumnByName("Time"))->InsertNextValue(time);
  for (const Column<double>& c : measure_columns())
    vtkDoubleArray::SafeDownCast(table->GetColumnByName(c.name))
        ->InsertNextValue(empty ? vtkMath::Nan() : c.value(m));
  for (const Column<int>& c : count_columns())
    vtkIntArray::SafeDownCast(table->GetColumnByName(c.name))->InsertNextValue(c.value(m));
  vtkStringArray::SafeDownCast(table->GetColumnByName("mechanism"))
      ->InsertNextValue(mechanism_name(m.mechanism));
}

}  // namespace runout::filters
