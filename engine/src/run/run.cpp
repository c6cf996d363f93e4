#include "runout/run/run.hpp"

#include <stdexcept>

#include "run_schedule.hpp"
#include "runout/dam/dam_output.hpp"
#include "runout/mpm/seeding.hpp"

namespace runout {

using namespace run_detail;

RunSummary run_scene(const Scene& scene, const RunOptions& options) {
  const auto start = Clock::now();
  Simulation sim(scene, seed_particles(scene, options.memory));
  return run_mpm(scene, options, start, sim, [&]() -> const Particles& { return sim.particles(); });
}

RunSummary resume_scene(const RunOptions& options) {
  const auto start = Clock::now();
  Scene scene;
  Checkpoint cp = load_for_resume(options, scene);
  // The particles in the memory order they had, with the step count that
  // decides when they are next reordered: the run goes on bit for bit.
  Simulation sim(scene, std::move(cp.particles));
  sim.restore(cp.state.counters);
  return run_mpm(scene, options, start, sim, [&]() -> const Particles& { return sim.particles(); },
                 &cp.state.schedule);
}

RunSummary run_dam(const Scene& scene, const RunOptions& options) {
  const auto start = Clock::now();
  if (options.checkpoint_every > 0)
    throw std::invalid_argument("the depth-averaged model writes no checkpoints");
  DamSolver dam(scene, options.memory);  // before the folder: a scene it cannot run leaves none
  const fs::path dir = prepare_folder(scene, options);
  const AdoptedFolderLock lock(dir.string());

  RunSummary summary;
  summary.particles = dam.elements();
  summary.pvd_path = (dir / (scene.name + ".pvd")).string();
  PvdIndex pvd(summary.pvd_path);
  HistoryWriter history((dir / "history.csv").string());
  const std::vector<double> base_xy = base_polyline(scene);

  const auto write_frame = [&] {
    const int frame = summary.frames++;
    write_dam_vtp((dir / numbered("frame", frame, "vtp")).string(), dam, base_xy,
                  scene.output.compress);
    write_profile_csv((dir / numbered("profile", frame, "csv")).string(), dam.time(),
                      dam_profile(dam));
    pvd.add(dam.time(), numbered("frame", frame, "vtp"));
  };
  const double initial_toe = dam.s().back();
  RestDetector rest(scene.time.rest_fraction, scene.time.rest_duration);
  const auto record = [&] {
    const HistoryRow row = dam_history_row(dam, initial_toe);
    history.append(row);
    return rest.at_rest(row.time, row.toe_velocity, row.centroid_velocity, 0.0);  // one layer, one block
  };
  const auto at_rest = [&] {
    const HistoryRow row = dam_history_row(dam, initial_toe);
    return rest.at_rest(row.time, row.toe_velocity, row.centroid_velocity, 0.0);  // one layer, one block
  };
  run_schedule(dam, {.scene = scene,
                     .options = options,
                     .start = start,
                     .record = record,
                     .write_frame = write_frame,
                     .at_rest = at_rest,
                     .summary = summary});
  return summary;
}

}  // namespace runout
