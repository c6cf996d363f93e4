#include "runout/run.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "runout/atomic_file.hpp"
#include "runout/history.hpp"
#include "runout/morphology.hpp"
#include "runout/scene_parser.hpp"
#include "runout/simulation.hpp"
#include "runout/vtu_writer.hpp"

namespace runout {
namespace fs = std::filesystem;

namespace {

// History rows come this many times per frame interval.
constexpr int kHistoryPerFrame = 10;

// A run replaces what an earlier run left in the same folder, so that no
// stale frame of a longer run is left beside the new index.
void clear_previous_output(const fs::path& dir) {
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    const std::string ext = entry.path().extension().string();
    const bool profile = name.rfind("profile_", 0) == 0 && ext == ".csv";
    if (ext == ".vtu" || ext == ".pvd" || profile || name == "history.csv" ||
        name == "scene.resolved.toml")
      fs::remove(entry.path());
  }
}

std::string numbered(const char* stem, int frame, const char* ext) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s_%05d.%s", stem, frame, ext);
  return buf;
}

// The base as the polyline the frames carry: a planar base, and the grid's
// bottom boundary of a scene without a base (which the morphology measures
// along too), is the grid's bottom line across the domain.
std::vector<double> base_polyline(const Scene& s) {
  if (s.base.kind != BaseKind::Polyline)
    return {s.grid.min.x(), s.grid.min.y(), s.grid.max.x(), s.grid.min.y()};
  std::vector<double> xy;
  for (const auto& p : s.base.points) {
    xy.push_back(p.x());
    xy.push_back(p.y());
  }
  return xy;
}

// Ends the run once the kinetic energy has stayed below fraction x its
// peak for `duration` seconds (scene time.rest_*).
class RestDetector {
 public:
  RestDetector(double fraction, double duration) : fraction_(fraction), duration_(duration) {}
  bool at_rest(double time, double kinetic_energy) {
    if (fraction_ <= 0.0) return false;
    peak_ = std::max(peak_, kinetic_energy);
    if (peak_ <= 0.0 || kinetic_energy >= fraction_ * peak_) {
      since_ = -1.0;
      return false;
    }
    if (since_ < 0.0) since_ = time;
    return time - since_ >= duration_;
  }

 private:
  double fraction_, duration_;
  double peak_ = 0.0, since_ = -1.0;
};

}  // namespace

RunSummary run_scene(const Scene& scene, const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path dir(options.out_dir);
  fs::create_directories(dir);
  clear_previous_output(dir);
  write_file_atomically((dir / "scene.resolved.toml").string(), to_toml(scene));

  Simulation sim(scene);
  const BaseView base = sim.base().view();
  const double spacing = sim.particle_spacing();
  RunSummary summary;
  summary.particles = sim.particles().size();
  summary.pvd_path = (dir / (scene.name + ".pvd")).string();
  PvdIndex pvd(summary.pvd_path);
  HistoryWriter history((dir / "history.csv").string());
  FrameInfo info{0.0, spacing, base_polyline(scene), {}};
  for (const MaterialParams& m : sim.materials()) info.strengths.push_back(m.strength);

  const auto write_frame = [&] {
    const int frame = summary.frames++;
    info.time = sim.time();
    write_particles_vtu((dir / numbered("frame", frame, "vtu")).string(), sim.particles(), info,
                        scene.output.compress);
    write_profile_csv((dir / numbered("profile", frame, "csv")).string(), sim.time(),
                      slide_profile(sim.particles(), base, scene.grid.cell_size, spacing));
    pvd.add(sim.time(), numbered("frame", frame, "vtu"));
  };
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  const double initial_toe = measure_slide(sim.particles(), base, spacing).toe_s;
  RestDetector rest(scene.time.rest_fraction, scene.time.rest_duration);
  const auto record = [&] {
    const SlideMorphology shape = measure_slide(sim.particles(), base, spacing);
    history.append(sim, shape, runout_distance(shape, initial_toe));
    return rest.at_rest(sim.time(), shape.kinetic_energy);
  };

  write_frame();
  record();
  const double dt_history = scene.time.output_interval / kHistoryPerFrame;
  const long rows = std::lround(std::ceil(scene.time.end / dt_history - 1e-9));
  try {
    for (long k = 1; k <= rows; ++k) {
      sim.advance_to(std::min(scene.time.end, k * dt_history));
      summary.at_rest = record();
      if (k % kHistoryPerFrame == 0 || k == rows || summary.at_rest) write_frame();
      if (options.on_progress)
        options.on_progress({sim.time(), scene.time.end, sim.steps(), elapsed()});
      if (summary.at_rest) break;
    }
  } catch (const NumericalFailure& e) {
    summary.failed = true;
    summary.failure = e.what();
  }
  summary.steps = sim.steps();
  summary.end_time = sim.time();
  summary.wall_seconds = elapsed();
  return summary;
}

}  // namespace runout
