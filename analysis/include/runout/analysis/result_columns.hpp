#pragma once
// The columns of the analysis' result tables: one list per table, read by
// the VTK filters (their vtkTable outputs and cell arrays) and by `runout
// analyse` (its CSV and JSON), so that both give the same columns in the
// same order with the same values. docs/filters.md defines each column.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "runout/analysis/horst_graben.hpp"
#include "runout/analysis/morphology_rules.hpp"
#include "runout/analysis/shear_bands.hpp"

namespace runout::analysis {

// A column: its name, its kind, and how it reads an item (number for
// Double and Int, text for String).
template <class Item>
struct Column {
  enum Kind { Double, Int, String };
  Column(const char* name, Kind kind, std::function<double(const Item&)> number)
      : name(name), kind(kind), number(std::move(number)) {}
  Column(const char* name, std::function<std::string(const Item&)> text)
      : name(name), kind(String), text(std::move(text)) {}
  const char* name;
  Kind kind;
  std::function<double(const Item&)> number;
  std::function<std::string(const Item&)> text;
};

// The band table, one row per band after its index `band_id`:
// centroid_x, centroid_y, centroid_s, dip, length, thickness, mean_strain,
// peak_strain, particle_count.
constexpr const char* kBandIdColumn = "band_id";
const std::vector<Column<ShearBand>>& band_columns();

// The block table, one row per block after its index `block_id`: type,
// type_code, start_s, end_s, width, top, relief, left_dip, right_dip,
// left_band, right_band, displacement, particle_count.
constexpr const char* kBlockIdColumn = "block_id";
const std::vector<Column<SlideBlock>>& block_columns();

// The morphology table, one row per frame after its time (the column
// kTimeColumn): toe, rear, length, max_thickness, runout, toe_velocity,
// centroid_x, centroid_y, centroid_s, centroid_velocity, outside_mass,
// initial_toe, length_ratio, thickness_ratio (NaN, all of them, for a frame
// without particles), late_stretch (NaN without the frames before),
// particles, troughs, initial_troughs, mechanism_id,
// mechanism.
// "Time", not "time": ParaView's line chart takes a column of that name as
// its x axis, so the morphology history plots against time as it opens.
constexpr const char* kTimeColumn = "Time";
const std::vector<Column<FrameMorphology>>& morphology_columns();

}  // namespace runout::analysis
