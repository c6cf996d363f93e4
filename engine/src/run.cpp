#include "runout/run.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "runout/atomic_file.hpp"
#include "runout/history.hpp"
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
    if (ext == ".vtu" || ext == ".pvd" || name == "history.csv" || name == "scene.resolved.toml")
      fs::remove(entry.path());
  }
}

std::string frame_name(int frame) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame_%05d.vtu", frame);
  return buf;
}

}  // namespace

RunSummary run_scene(const Scene& scene, const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path dir(options.out_dir);
  fs::create_directories(dir);
  clear_previous_output(dir);
  write_file_atomically((dir / "scene.resolved.toml").string(), to_toml(scene));

  Simulation sim(scene);
  RunSummary summary;
  summary.particles = sim.particles().size();
  summary.pvd_path = (dir / (scene.name + ".pvd")).string();
  PvdIndex pvd(summary.pvd_path);
  HistoryWriter history((dir / "history.csv").string());

  const auto write_frame = [&] {
    const std::string name = frame_name(summary.frames++);
    write_particles_vtu((dir / name).string(), sim.particles(), sim.time(), scene.output.compress);
    pvd.add(sim.time(), name);
  };
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };

  write_frame();
  history.append(sim);
  const double dt_history = scene.time.output_interval / kHistoryPerFrame;
  const long rows = std::lround(std::ceil(scene.time.end / dt_history - 1e-9));
  try {
    for (long k = 1; k <= rows; ++k) {
      sim.advance_to(std::min(scene.time.end, k * dt_history));
      history.append(sim);
      if (k % kHistoryPerFrame == 0 || k == rows) write_frame();
      if (options.on_progress)
        options.on_progress({sim.time(), scene.time.end, sim.steps(), elapsed()});
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
