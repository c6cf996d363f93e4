#include "runout/analysis/run_analysis.hpp"

#include <cmath>
#include <filesystem>
#include <optional>

#include "runout/analysis/frame_base.hpp"
#include "runout/analysis/frame_checks.hpp"
#include "runout/analysis/tuples.hpp"
#include "runout/output/vtu_writer.hpp"

namespace runout::analysis {

namespace {

// The point arrays the filters read, by the engine's names (docs/output.md),
// with the components each needs: the band search's strain, the block
// search's displacement (its magnitude, whatever its components), and the
// morphology's velocity, mass and initial position.
struct NeededArray {
  const char* name;
  int components;
};
constexpr NeededArray kStrain{"plastic_shear_strain", 1}, kDisplacement{"displacement", 1},
    kVelocity{"velocity", 3}, kMass{"mass", 1}, kInitialPosition{"initial_position", 3};

const VtuArray* point_array(const VtuFrame& frame, NeededArray needed, std::string& problem) {
  const VtuArray* a = frame.point_array(needed.name);
  if (!a)
    problem = std::string("The frame has no point array \"") + needed.name + "\" with " +
              std::to_string(needed.components) +
              " component(s) per point: not a Runout particle frame.";
  else
    problem = point_array_problem(needed.name, a->values, a->components, frame.points,
                                  needed.components);
  return a;
}

// The first value of a one-tuple field array, NaN without it.
double field_value(const VtuFrame& frame, const char* name) {
  const VtuArray* a = frame.field_array(name);
  return a && !a->values.empty() ? a->values[0] : std::nan("");
}

}  // namespace

std::string analyse_frame(const VtuFrame& frame, const AnalysisParameters& parameters,
                          FrameAnalysis& out) {
  std::string problem = points_problem(frame.positions.values);
  if (!problem.empty()) return problem;
  const VtuArray* arrays[5];
  const NeededArray needed[5] = {kStrain, kDisplacement, kVelocity, kMass, kInitialPosition};
  for (int k = 0; k < 5; ++k) {
    arrays[k] = point_array(frame, needed[k], problem);
    if (!problem.empty()) return problem;
  }
  const VtuArray &xi = *arrays[0], &displacement = *arrays[1], &velocity = *arrays[2],
                 &mass = *arrays[3], &initial = *arrays[4];

  // As the filters read them (particle_spacing_of, read_base_points).
  const double field_spacing = field_value(frame, "particle_spacing");
  const double spacing = std::isfinite(field_spacing) ? field_spacing : 0.0;
  const VtuArray* base_points = frame.field_array("base_points");
  const std::optional<Base> base =
      base_points ? base_from_points(base_points->values, base_points->components) : std::nullopt;

  const Particles particles =
      morphology_particles(frame.positions.values, velocity.values, velocity.components,
                           mass.values, mass.components, initial.values, initial.components);
  problem = morphology_problem(particles, base, spacing, parameters.bin_spacings, kMass.name);
  if (!problem.empty()) return problem;
  out.morphology =
      measure_frame(particles, base->view(), spacing, parameters.bin_spacings * spacing);

  const std::vector<Vec2> points = points_of(frame.positions.values);
  BandParameters bands = parameters.bands;
  bands.spacing = spacing;
  out.bands = find_shear_bands(points, component_of(xi.values, xi.components, 0), base->view(),
                               bands);
  BlockParameters blocks = parameters.blocks;
  blocks.spacing = spacing;
  out.blocks = find_blocks(points, norms_of(displacement.values, displacement.components),
                           out.bands, base->view(), blocks);
  return "";
}

RunAnalysis analyse_run(const std::string& pvd_path, const AnalysisParameters& parameters,
                        const std::function<void(const std::string&)>& warn) {
  namespace fs = std::filesystem;
  RunAnalysis run;
  run.index_file = fs::path(pvd_path).filename().string();
  const PvdIndex::Entries entries = read_pvd_entries(pvd_path);
  std::optional<FrameManifest> manifest;
  try {
    manifest.emplace(pvd_path);
  } catch (const std::runtime_error&) {
    run.manifest_checked = false;
    warn("no manifest " + fs::path(manifest_path(pvd_path)).filename().string() +
         ": the frames are read without checking them against it");
  }
  const std::string folder = fs::path(pvd_path).parent_path().string();
  for (std::size_t k = 0; k < entries.size(); ++k) {
    // (Not a structured binding: C++17 lambdas cannot capture one.)
    const double time = entries[k].first;
    const std::string& file = entries[k].second;
    const auto skip = [&](const std::string& reason) {
      warn(file + ": " + reason + "; skipped");
      run.skipped.push_back({k, file, reason});
    };
    std::string bytes;
    const std::string unreadable =
        read_listed_frame(folder, file, manifest ? &*manifest : nullptr, bytes);
    if (!unreadable.empty()) {
      skip(unreadable);
      continue;
    }
    FrameAnalysis frame;
    frame.index = k;
    frame.file = file;
    std::string problem;
    try {
      const VtuFrame vtu = parse_vtu_frame(bytes);
      frame.time = std::isnan(time) ? field_value(vtu, "TimeValue") : time;
      problem = analyse_frame(vtu, parameters, frame);
    } catch (const VtuReadError& e) {
      problem = e.what();
    }
    if (!problem.empty()) {
      skip(problem);
      continue;
    }
    run.frames.push_back(std::move(frame));
  }
  // Each frame's class from the travel up to it, so that a block whose
  // faces slumped early is not called an elongation for that slump.
  std::vector<TravelSample> travel;
  for (FrameAnalysis& frame : run.frames) {
    travel.push_back({frame.morphology.runout, frame.morphology.now.length});
    classify_by_travel(frame.morphology, travel);
  }
  return run;
}

}  // namespace runout::analysis
