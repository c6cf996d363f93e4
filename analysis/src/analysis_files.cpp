#include "runout/analysis/analysis_files.hpp"

#include <cstdio>
#include <filesystem>
#include <regex>

#include "runout/analysis/result_columns.hpp"
#include "runout/output/atomic_file.hpp"
#include "runout/measure/morphology.hpp"
#include "text_format.hpp"

namespace runout::analysis {

namespace {

namespace fs = std::filesystem;

std::string numbered(const char* stem, std::size_t index) {
  char name[64];
  std::snprintf(name, sizeof name, "%s_%05zu.csv", stem, index);
  return name;
}

// Whether `name` is a file write_analysis writes (or a temporary of one).
bool is_analysis_file(const std::string& name) {
  static const std::regex per_frame("(bands|blocks|profile)_[0-9]{5,}\\.csv");
  return name == "morphology.csv" || name == "analysis.json" ||
         std::regex_match(name, per_frame) || is_atomic_temporary(name);
}

void clear_previous_analysis(const fs::path& dir) {
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file() && is_analysis_file(entry.path().filename().string()))
      fs::remove(entry.path());
}

// One value of a column, for CSV or for JSON.
template <class Item>
std::string cell(const Column<Item>& c, const Item& item, bool json) {
  if (c.kind == Column<Item>::String) return json ? text::json_text(c.text(item)) : text::csv_text(c.text(item));
  if (c.kind == Column<Item>::Int) return std::to_string(static_cast<long long>(c.number(item)));
  return json ? text::json_number(c.number(item)) : text::csv_number(c.number(item));
}

// "# time = T", the header, then one row per item: its index under
// id_name, then the columns; the filters' table of one frame.
template <class Item>
std::string item_table(double time, const char* id_name, const std::vector<Item>& items,
                       const std::vector<Column<Item>>& columns) {
  std::string out = "# time = " + text::csv_number(time) + "\n" + id_name;
  for (const Column<Item>& c : columns) out += std::string(",") + c.name;
  out += '\n';
  for (std::size_t k = 0; k < items.size(); ++k) {
    out += std::to_string(k);
    for (const Column<Item>& c : columns) {
      out += ',';
      out += cell(c, items[k], false);
    }
    out += '\n';
  }
  return out;
}

std::string morphology_table(const RunAnalysis& run) {
  std::string out = std::string("frame,") + kTimeColumn;
  for (const auto& c : morphology_columns()) out += std::string(",") + c.name;
  out += '\n';
  for (const FrameAnalysis& f : run.frames) {
    out += std::to_string(f.index) + "," + text::csv_number(f.time);
    for (const auto& c : morphology_columns()) {
      out += ',';
      out += cell(c, f.morphology, false);
    }
    out += '\n';
  }
  return out;
}

// ---- JSON

template <class Item>
std::string json_fields(const std::vector<Column<Item>>& columns, const Item& item) {
  std::string out;
  for (const Column<Item>& c : columns) out += ", " + text::json_text(c.name) + ": " + cell(c, item, true);
  return out;
}

std::string json_points(const std::vector<Vec2>& points) {
  std::string out = "[";
  for (std::size_t k = 0; k < points.size(); ++k)
    out += (k ? ", [" : "[") + text::json_number(points[k].x) + ", " +
           text::json_number(points[k].y) + "]";
  return out + "]";
}

// The items as objects: the index under id_name, the columns, then their
// geometry (a band's skeleton, a block's outline) under geometry_name.
template <class Item>
std::string json_items(const char* id_name, const std::vector<Item>& items,
                       const std::vector<Column<Item>>& columns, std::vector<Vec2> Item::*geometry,
                       const char* geometry_name) {
  std::string out = "[";
  for (std::size_t k = 0; k < items.size(); ++k)
    out += std::string(k ? ",\n        {" : "\n        {") + text::json_text(id_name) + ": " +
           std::to_string(k) + json_fields(columns, items[k]) + ", " +
           text::json_text(geometry_name) + ": " + json_points(items[k].*geometry) + "}";
  return out + (items.empty() ? "]" : "\n      ]");
}

const char* threshold_mode_name(ThresholdMode mode) {
  switch (mode) {
    case ThresholdMode::Absolute: return "absolute";
    case ThresholdMode::RelativeToReference: return "relative to reference";
    case ThresholdMode::Percentile: break;
  }
  return "percentile";
}

std::string json_parameters(const AnalysisParameters& p) {
  const BandParameters& b = p.bands;
  const BlockParameters& k = p.blocks;
  using text::json_number;
  return "{\"bin_spacings\": " + json_number(p.bin_spacings) +
         ",\n    \"bands\": {\"threshold_mode\": " + text::json_text(threshold_mode_name(b.threshold.mode)) +
         ", \"threshold\": " + json_number(b.threshold.absolute) +
         ", \"relative_threshold\": " + json_number(b.threshold.relative) +
         ", \"reference_strain\": " + json_number(b.threshold.reference) +
         ", \"percentile\": " + json_number(b.threshold.percentile) +
         ", \"linking_factor\": " + json_number(b.linking_factor) +
         ", \"orientation_radius\": " + json_number(b.orientation_radius) +
         ", \"maximum_angle\": " + json_number(b.max_angle) +
         ", \"minimum_particles\": " + std::to_string(b.min_particles) +
         ", \"skeleton_bin\": " + json_number(b.skeleton_bin) +
         "},\n    \"blocks\": {\"dip_tolerance\": " + json_number(k.dip_tolerance) +
         ", \"surface_gap\": " + json_number(k.surface_gap) +
         ", \"outline_bin\": " + json_number(k.outline_bin) + "}}";
}

std::string json_frame(const FrameAnalysis& f) {
  return "    {\"frame\": " + std::to_string(f.index) + ", \"file\": " + text::json_text(f.file) +
         ", " + text::json_text(kTimeColumn) + ": " + text::json_number(f.time) +
         ",\n      \"morphology\": {" + json_fields(morphology_columns(), f.morphology).substr(2) +
         "},\n      \"bands\": " +
         json_items(kBandIdColumn, f.bands, band_columns(), &ShearBand::skeleton, "skeleton") +
         ",\n      \"blocks\": " +
         json_items(kBlockIdColumn, f.blocks, block_columns(), &SlideBlock::outline, "outline") +
         "}";
}

std::string analysis_json(const RunAnalysis& run, const AnalysisParameters& parameters) {
  std::string out = "{\n  \"index\": " + text::json_text(run.index_file) +
                    ",\n  \"manifest_checked\": " + (run.manifest_checked ? "true" : "false") +
                    ",\n  \"parameters\": " + json_parameters(parameters) + ",\n  \"frames\": [";
  for (std::size_t k = 0; k < run.frames.size(); ++k) out += (k ? ",\n" : "\n") + json_frame(run.frames[k]);
  out += run.frames.empty() ? "],\n  \"skipped\": [" : "\n  ],\n  \"skipped\": [";
  for (std::size_t k = 0; k < run.skipped.size(); ++k) {
    const SkippedFrame& s = run.skipped[k];
    out += std::string(k ? ",\n" : "\n") + "    {\"frame\": " + std::to_string(s.index) +
           ", \"file\": " + text::json_text(s.file) + ", \"reason\": " + text::json_text(s.reason) +
           "}";
  }
  return out + (run.skipped.empty() ? "]\n}\n" : "\n  ]\n}\n");
}

}  // namespace

void write_analysis(const std::string& dir, const RunAnalysis& run,
                    const AnalysisParameters& parameters) {
  const fs::path folder(dir);
  std::error_code error;
  fs::create_directories(folder, error);
  if (error) throw std::runtime_error("cannot create " + dir + ": " + error.message());
  clear_previous_analysis(folder);
  for (const FrameAnalysis& f : run.frames) {
    write_file_atomically((folder / numbered("bands", f.index)).string(),
                          item_table(f.time, kBandIdColumn, f.bands, band_columns()));
    write_file_atomically((folder / numbered("blocks", f.index)).string(),
                          item_table(f.time, kBlockIdColumn, f.blocks, block_columns()));
    write_profile_csv((folder / numbered("profile", f.index)).string(), f.time,
                      f.morphology.profile);
  }
  write_file_atomically((folder / "morphology.csv").string(), morphology_table(run));
  write_file_atomically((folder / "analysis.json").string(), analysis_json(run, parameters));
}

}  // namespace runout::analysis
