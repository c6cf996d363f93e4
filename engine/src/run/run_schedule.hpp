#pragma once
// What every kind of run shares (run.cpp, cuda/run_cuda.cpp): the output
// folder, the schedule of history rows and frames, the at-rest test, and
// the MPM run over any driver of the step. Internal to the engine.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "runout/output/atomic_file.hpp"
#include "runout/output/checkpoint.hpp"
#include "runout/dam/dam.hpp"
#include "runout/output/history.hpp"
#include "runout/measure/basal_fill.hpp"
#include "runout/measure/remoulded_mass.hpp"
#include "runout/measure/morphology.hpp"
#include "runout/run/run.hpp"
#include "runout/run/rest_detector.hpp"
#include "runout/run/run_control.hpp"
#include "runout/output/run_summary_file.hpp"
#include "runout/scene/scene_parser.hpp"
#include "runout/mpm/simulation.hpp"
#include "runout/run/thread_governor.hpp"
#include "runout/output/vtu_writer.hpp"

namespace runout::run_detail {
namespace fs = std::filesystem;

// History rows come this many times per frame interval.
inline constexpr int kHistoryPerFrame = 10;

// A run replaces what an earlier run left in the same folder, so that no
// stale frame of a longer run is left beside the new index; temporaries of
// writes a killed run never finished go too (the folder's lock says no
// live writer owns them).
inline void clear_previous_output(const fs::path& dir) {
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    const std::string ext = entry.path().extension().string();
    const bool profile = name.rfind("profile_", 0) == 0 && ext == ".csv";
    if (ext == ".vtu" || ext == ".vtp" || ext == ".pvd" || ext == ".manifest" || profile ||
        name == "history.csv" ||
        name == kResolvedSceneFile || name == kCheckpointFile || name == kSummaryFile ||
        is_atomic_temporary(name))
      fs::remove(entry.path());
  }
  // What `runout analyse` wrote of the old run's frames.
  fs::remove_all(dir / kAnalysisFolder);
}

inline std::string numbered(const char* stem, int frame, const char* ext) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s_%05d.%s", stem, frame, ext);
  return buf;
}

// The base as the polyline the frames carry: a planar base, and the grid's
// bottom boundary of a scene without a base (which the morphology measures
// along too), is the grid's bottom line across the domain.
inline std::vector<double> base_polyline(const Scene& s) {
  if (s.base.kind != BaseKind::Polyline)
    return {s.grid.min.x(), s.grid.min.y(), s.grid.max.x(), s.grid.min.y()};
  std::vector<double> xy;
  for (const auto& p : s.base.points) {
    xy.push_back(p.x());
    xy.push_back(p.y());
  }
  return xy;
}

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

inline void write_resolved_scene(const fs::path& dir, const Scene& scene) {
  write_file_atomically((dir / kResolvedSceneFile).string(), to_toml(scene));
}

// The output folder, locked for this process (the caller releases it, see
// AdoptedFolderLock), emptied of an earlier run's files, with the resolved
// scene in it.
inline fs::path prepare_folder(const Scene& scene, const RunOptions& options) {
  const fs::path dir(options.out_dir);
  fs::create_directories(dir);
  lock_output_folder(dir.string());
  try {
    clear_previous_output(dir);
    write_resolved_scene(dir, scene);
  } catch (...) {
    unlock_output_folder(dir.string());
    throw;
  }
  return dir;
}

// One step of model.advance_to(t), the same step it would take: the last
// one is left to advance_to itself, which lands on t exactly. Taking steps
// one at a time lets the run look at its state between them, and the
// step depends on the state only, so a run resumed between rows takes the
// steps an uninterrupted one takes.
template <class Model>
void step_toward(Model& model, double t) {
  const double remaining = t - model.time();
  const double n = std::ceil(remaining / model.stable_dt());
  if (n <= 1.0)
    model.advance_to(t);
  else
    model.step(remaining / n);
}
inline void step_toward(DamSolver& model, double t) {
  const double dt = model.stable_dt();
  if (t - model.time() <= dt)
    model.advance_to(t);
  else
    model.step(dt);
}

// The at-rest test between history rows: every rest_duration / 10 of
// simulated time, however long the output interval (0: never).
inline double rest_probe_interval(const Scene& scene) {
  return scene.time.rest_fraction > 0.0 ? scene.time.rest_duration / 10.0 : 0.0;
}

enum class Interrupt { None, AtRest, Stop };

// Steps the model to t; stops early, at a step boundary, when a stop is
// requested (run_control.hpp) or when at_rest() says so at a probe. Probes
// fall on the first step past each multiple of probe_every, which depends
// on the step alone, not on where the run was started or resumed.
template <class Model, class AtRest>
Interrupt advance_watching(Model& model, double t, double probe_every, const AtRest& at_rest) {
  while (model.time() < t) {
    const double before = model.time();
    step_toward(model, t);
    if (stop_requested()) return Interrupt::Stop;
    if (probe_every > 0.0 &&
        std::floor(model.time() / probe_every) > std::floor(before / probe_every) && at_rest())
      return Interrupt::AtRest;
  }
  return Interrupt::None;
}

inline double history_interval(const Scene& scene) {
  return scene.time.output_interval / kHistoryPerFrame;
}

// --checkpoint-every in history rows: the nearest whole number, at least one.
inline long checkpoint_rows(const Scene& scene, double every) {
  return every > 0.0 ? std::max(1L, std::lround(every / history_interval(scene))) : 0;
}

// The schedule every method follows: a history row every output interval /
// kHistoryPerFrame, a frame every output interval, at the end and at rest.
// A fresh run (first_row 0) starts with frame 0 and row 0 at t = 0; a
// resumed one goes on after the row of its checkpoint, from the time of
// its checkpoint. A slide found at rest, at a row or between rows, gets its
// last row and frame at once. Checkpoints follow every
// checkpoint_every-th row but the last (a run that reaches it is done) and
// one at rest; a stop request (a signal) ends the run at the next step
// with the checkpoint of the last row written.
struct Schedule {
  const Scene& scene;
  const RunOptions& options;  // on_progress, on_finished
  Clock::time_point start;    // of the run, for its wall time
  long first_row = 0;         // the checkpoint's row of a resumed run; 0: a fresh run
  std::function<bool()> record;       // appends a history row; whether the slide is at rest
  std::function<void()> write_frame;  // writes the next frame
  long checkpoint_every = 0;          // in rows (checkpoint_rows); 0: none
  std::function<void(long)> checkpoint = [](long) {};  // the checkpoint of row k
  std::function<bool()> at_rest;  // the test between rows (rest_probe_interval)
  RunSummary& summary;            // the run's outcome, steps and times filled in
};

template <class Model>
void run_schedule(Model& model, const Schedule& s) {
  const Scene& scene = s.scene;
  RunSummary& summary = s.summary;
  const long first_step = model.steps();
  if (s.first_row == 0) {
    s.write_frame();
    s.record();
  }
  const double dt_history = history_interval(scene);
  const long rows = std::lround(std::ceil(scene.time.end / dt_history - 1e-9));
  try {
    const double probe_every = rest_probe_interval(scene);
    for (long k = s.first_row + 1; k <= rows; ++k) {
      const Interrupt why = advance_watching(model, std::min(scene.time.end, k * dt_history),
                                             probe_every, s.at_rest);
      if (why == Interrupt::Stop) {
        s.checkpoint(k - 1);
        mark_stopped(stop_requested());
        break;
      }
      summary.at_rest = s.record() || why == Interrupt::AtRest;
      if (k % kHistoryPerFrame == 0 || k == rows || summary.at_rest) s.write_frame();
      if (s.options.on_progress)
        s.options.on_progress(
            {model.time(), scene.time.end, model.steps(), seconds_since(s.start)});
      if (summary.at_rest) break;
      if (s.checkpoint_every > 0 && k % s.checkpoint_every == 0 && k < rows) s.checkpoint(k);
    }
  } catch (const NumericalFailure& e) {
    summary.failed = true;
    summary.failure = e.what();
  }
  summary.steps = model.steps();
  summary.steps_run = summary.steps - first_step;
  summary.end_time = model.time();
  summary.wall_seconds = seconds_since(s.start);
  if (s.options.on_finished) s.options.on_finished(summary);
}

// A checkpoint's frame count is the schedule's for its row: frame 0, then
// one every kHistoryPerFrame rows (none is written at rest or at the end).
inline void require_schedule(const ScheduleState& state, const std::string& source) {
  const long expected = state.row / kHistoryPerFrame + 1;
  if (state.frames != expected)
    throw CheckpointError(source + ": it counts " + std::to_string(state.frames) +
                          " frames, its history row " + std::to_string(state.row) +
                          " gives " + std::to_string(expected));
}

// history.csv cut back to the checkpoint's rows, read before anything is
// changed: a file too short refuses the resume instead of half doing it.
inline std::string kept_history(const fs::path& dir, const ScheduleState& state) {
  try {
    return first_history_rows((dir / "history.csv").string(), state.row + 1);
  } catch (const std::runtime_error& e) {
    throw ResumeRefused(e.what());
  }
}

// Throws ResumeRefused unless every frame the checkpoint keeps is the one it
// recorded: a damaged frame would otherwise enter the new manifest as whole,
// and another run's frames would be continued as this one's.
inline void require_kept_frames(const fs::path& dir, const ScheduleState& state) {
  for (std::size_t e = 0; e < state.pvd.size(); ++e) {
    const std::string& file = state.pvd[e].second;
    const std::string now = frame_record(dir.string(), file);
    const std::string recorded = e < state.frame_records.size() ? state.frame_records[e] : "";
    if (now != recorded)
      throw ResumeRefused((dir / file).string() +
                          " is not the frame the checkpoint kept (file, bytes, CRC-32): '" + now +
                          "' now, '" + recorded + "' in the checkpoint");
  }
}

// The folder of a run being resumed, put back as it was when the checkpoint
// was written: history.csv to `history` (kept_history), frames and profiles
// written after it removed (a killed run may have written some), the
// temporaries of writes the kill interrupted and the summary of an ended
// run deleted; the caller's PvdIndex rewrites the index.
inline void rewind_folder(const fs::path& dir, const ScheduleState& state,
                          const std::string& history) {
  write_file_atomically((dir / "history.csv").string(), history);
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    const std::string ext = entry.path().extension().string();
    int frame = -1;
    const bool numbered_file =
        (std::sscanf(name.c_str(), "frame_%d.", &frame) == 1 && (ext == ".vtu" || ext == ".vtp")) ||
        (std::sscanf(name.c_str(), "profile_%d.", &frame) == 1 && ext == ".csv");
    if ((numbered_file && frame >= state.frames) || is_atomic_temporary(name))
      fs::remove(entry.path());
  }
  fs::remove(dir / kSummaryFile);
}

// The scene a checkpoint's run goes on with: its own, which the folder's
// resolved scene must be, or the folder's where that is the checkpoint's
// with another end after the checkpoint's time, as a `resume --end` writes
// it before it runs on: one stopped before its first checkpoint leaves such
// a folder, and it goes on to that end. Anything else throws
// require_same_scene's CheckpointError.
inline Scene resumed_scene(const CheckpointState& state, const fs::path& dir,
                           const std::string& path) {
  const std::string resolved = (dir / kResolvedSceneFile).string();
  const std::string own = path + " (its scene)";
  try {
    require_same_scene(state, resolved, path);
    return parse_scene(state.scene_toml, own);
  } catch (const CheckpointError&) {
    try {
      Scene extended = parse_scene(state.scene_toml, own);
      const std::string text = read_scene_text(resolved);
      apply_overrides(extended, std::nullopt, std::nullopt, parse_scene(text, resolved).time.end);
      if (extended.time.end > state.counters.time && to_toml(extended) == text) return extended;
    } catch (const std::exception&) {
    }
    throw;
  }
}

// The scene and state of a run to resume from the checkpoint in
// options.out_dir, with the folder locked for this process (run_mpm
// releases it) and rewound to the checkpoint. Everything is checked before
// the folder changes: throws CheckpointError (a checkpoint of another run
// among them), ResumeRefused (the folder does not go with it),
// OutputFolderBusy, or SceneError for a stored scene this build does not
// read.
inline Checkpoint load_for_resume(const RunOptions& options, Scene& scene) {
  const fs::path dir(options.out_dir);
  const std::string path = (dir / kCheckpointFile).string();
  if (!fs::is_directory(dir))
    throw CheckpointMissing("cannot open checkpoint '" + path + "': no folder " + dir.string());
  lock_output_folder(dir.string());
  try {
    Checkpoint cp = read_checkpoint(path);
    scene = resumed_scene(cp.state, dir, path);
    require_particles_fit(cp.particles, scene, path);
    require_schedule(cp.state.schedule, path);
    if (options.end) {
      if (!(*options.end > cp.state.counters.time)) {
        char msg[128];
        std::snprintf(msg, sizeof msg, "--end %.6g s is not after the checkpoint's t = %.6g s",
                      *options.end, cp.state.counters.time);
        throw ResumeRefused(msg);
      }
      apply_overrides(scene, std::nullopt, std::nullopt, options.end);  // SceneError if refused
    }
    const std::string history = kept_history(dir, cp.state.schedule);
    require_kept_frames(dir, cp.state.schedule);
    rewind_folder(dir, cp.state.schedule, history);
    // The folder's scene is the one the run goes on with; later checkpoints
    // carry the same text (run_mpm), so a later resume finds them matched.
    if (options.end) write_resolved_scene(dir, scene);
    return cp;
  } catch (...) {
    unlock_output_folder(dir.string());
    throw;
  }
}

// model's steps on the OpenMP thread count a ThreadGovernor picks from
// their wall times (RunOptions::adapt_threads); the same steps on any count.
// The count OpenMP had comes back at the end.
template <class Model>
class GovernedSteps {
 public:
  GovernedSteps(Model& model, int most) : model_(model), governor_(most) {}
  GovernedSteps(const GovernedSteps&) = delete;
  GovernedSteps& operator=(const GovernedSteps&) = delete;
  ~GovernedSteps() { set_threads(most_); }

  double time() const { return model_.time(); }
  long steps() const { return model_.steps(); }
  double stable_dt() const { return model_.stable_dt(); }
  void step(double dt) {
    timed([&] { model_.step(dt); });
  }
  void advance_to(double t) {
    timed([&] { model_.advance_to(t); });
  }

 private:
  static void set_threads([[maybe_unused]] int n) {
#ifdef _OPENMP
    omp_set_num_threads(n);
#endif
  }
  template <class F>
  void timed(F&& f) {
    set_threads(governor_.threads());
    const Clock::time_point t0 = Clock::now();
    f();
    governor_.took(seconds_since(t0));
  }

  Model& model_;
  ThreadGovernor governor_;
#ifdef _OPENMP
  int most_ = omp_get_max_threads();
#else
  int most_ = 1;
#endif
};

// A whole MPM run with any driver of the MPM step (the CPU Simulation, the
// CUDA one): particles() gives the current particles on the host, which for
// a device driver means a copy back, done for frames, history rows and
// checkpoints only. resumed: the schedule's state from a checkpoint, whose
// counters and particles the driver was built with; null for a fresh run.
template <class Driver, class HostParticles>
RunSummary run_mpm(const Scene& scene, const RunOptions& options, Clock::time_point start,
                   Driver& sim, HostParticles particles,
                   const ScheduleState* resumed = nullptr) {
  const fs::path dir = resumed ? fs::path(options.out_dir) : prepare_folder(scene, options);
  const AdoptedFolderLock lock(dir.string());
  const BaseView base = sim.base().view();
  const double spacing = sim.particle_spacing();
  RunSummary summary;
  summary.particles = particles().size();
  summary.pvd_path = (dir / (scene.name + ".pvd")).string();
  // A resume's kept frames were checked against their records
  // (require_kept_frames): the index takes the records, without reading the
  // frames again.
  PvdIndex pvd(summary.pvd_path, resumed ? resumed->pvd : PvdIndex::Entries{},
               resumed ? resumed->frame_records : std::vector<std::string>{});
  HistoryWriter history((dir / "history.csv").string(), resumed != nullptr);
  FrameInfo info{0.0, spacing, base_polyline(scene), {}};
  for (const MaterialParams& m : sim.materials()) info.strengths.push_back(m.strength);
  info.clay_band = scene.base.clay_band;

  if (resumed) summary.frames = resumed->frames;
  const auto write_frame = [&] {
    const Particles& P = particles();
    const int frame = summary.frames++;
    info.time = sim.time();
    write_particles_vtu((dir / numbered("frame", frame, "vtu")).string(), P, info,
                        scene.output.compress);
    write_profile_csv((dir / numbered("profile", frame, "csv")).string(), sim.time(),
                      slide_profile(P, base, scene.grid.cell_size, spacing));
    pvd.add(sim.time(), numbered("frame", frame, "vtu"));
  };
  const double initial_toe =
      resumed ? resumed->initial_toe : measure_slide(particles(), base, spacing).toe_s;
  RestDetector rest = resumed ? RestDetector(scene.time.rest_fraction, scene.time.rest_duration,
                                             resumed->rest_peak, resumed->rest_since)
                              : RestDetector(scene.time.rest_fraction, scene.time.rest_duration);
  const auto record = [&] {
    const Particles& P = particles();
    const SlideMorphology shape = measure_slide(P, base, spacing);
    history.append(mpm_history_row(P, shape, initial_toe, sim.time(),
                                   sim.steps(), sim.last_dt(), sim.basal_shear_force(),
                                   basal_fill(P, base, scene.grid.cell_size),
                                   remoulded_mass(P, sim.materials())));
    return rest.at_rest(sim.time(), shape.toe_velocity,
                        std::hypot(shape.centroid_vx, shape.centroid_vy), shape.block_speed);
  };
  const auto at_rest = [&] {
    const SlideMorphology shape = measure_slide(particles(), base, spacing);
    return rest.at_rest(sim.time(), shape.toe_velocity,
                        std::hypot(shape.centroid_vx, shape.centroid_vy), shape.block_speed);
  };

  const long every =
      resumed ? resumed->checkpoint_rows : checkpoint_rows(scene, options.checkpoint_every);
  const std::string checkpoint_path = (dir / kCheckpointFile).string();
  const std::string scene_toml = to_toml(scene);
  const auto checkpoint = [&](long k) {
    history.sync();  // the rows it counts reach the disk before it does
    const ScheduleState state{k,           every,        summary.frames, pvd.entries(),
                              pvd.records(), rest.peak(), rest.since(),   initial_toe};
    write_checkpoint(checkpoint_path, CheckpointState{scene_toml, sim.counters(), state},
                     particles());
    summary.checkpoint_path = checkpoint_path;
    summary.checkpoint_time = sim.time();
  };
  if (resumed) {
    summary.checkpoint_path = checkpoint_path;
    summary.checkpoint_time = summary.resumed_from = sim.time();
  }
  // The steps themselves, or the same steps on the threads a governor picks.
  const auto schedule = [&](auto& steps) {
    run_schedule(steps, {.scene = scene,
                         .options = options,
                         .start = start,
                         .first_row = resumed ? resumed->row : 0,
                         .record = record,
                         .write_frame = write_frame,
                         .checkpoint_every = every,
                         .checkpoint = checkpoint,
                         .at_rest = at_rest,
                         .summary = summary});
  };
  if (options.adapt_threads > 1) {
    GovernedSteps<Driver> governed(sim, options.adapt_threads);
    schedule(governed);
  } else {
    schedule(sim);
  }
  return summary;
}

}  // namespace runout::run_detail
