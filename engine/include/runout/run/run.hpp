#pragma once
// A whole run of a scene into an output folder: frames, PVD index, history
// and the resolved scene. The CLI is a thin layer over run_scene.
#include <functional>
#include <optional>
#include <string>

#include "runout/run/memory_estimate.hpp"
#include "runout/scene/scene.hpp"

namespace runout {

struct RunProgress {
  double time = 0, end = 0;
  long steps = 0;
  double wall_seconds = 0;
};

struct RunSummary;

struct RunOptions {
  std::string out_dir;
  std::function<void(const RunProgress&)> on_progress;  // called after each history row
  // Called once the run has ended (its summary complete), while it still
  // holds its output folder, so what it writes there (summary.json) cannot
  // land in a later run's folder.
  std::function<void(const RunSummary&)> on_finished;
  // A checkpoint (checkpoint.hpp) every this many simulated seconds,
  // rounded to whole history rows; 0: none. MPM only; a resumed run keeps
  // the interval of its checkpoint.
  double checkpoint_every = 0;
  // More than 1: an MPM run steps on this many OpenMP threads, or half,
  // or a quarter, ... or one, whichever its steps' wall times say is the
  // fastest now (thread_governor.hpp); the results are the same. 0: on
  // OpenMP's count.
  int adapt_threads = 0;
  // The memory estimate of the run, already passed by require_memory (the
  // CLI's one estimate of a run): the MPM seeding and the DAM do not make
  // it again.
  // Empty: the run estimates and checks it itself.
  std::optional<MemoryEstimate> memory;
  // A resume only: run on to this time instead of the run's own end (a run
  // that ended still moving goes on). Later than the checkpoint; recorded in
  // the folder's resolved scene as an override, as `runout run --end` is.
  std::optional<double> end;
};

struct RunSummary {
  int particles = 0;  // elements for the depth-averaged model
  long steps = 0;        // the step count at the end
  long steps_run = 0;    // the steps this call took: all of them unless resumed
  double resumed_from = -1;  // the checkpoint's time in a resumed run
  int frames = 0;
  double end_time = 0;
  double wall_seconds = 0;
  std::string pvd_path;
  bool at_rest = false;  // ended by the scene's at-rest criterion
  bool failed = false;
  std::string failure;  // the NumericalFailure message when failed
  // The last checkpoint written (or resumed from), empty when none, and its
  // simulated time.
  std::string checkpoint_path;
  double checkpoint_time = 0;
};

// Runs to scene.time.end or until at rest. A numerical failure ends the run early with
// failed = true: every frame and history row written before it stays, and
// the index lists only those frames. Throws std::runtime_error when the
// output cannot be written.
RunSummary run_scene(const Scene& scene, const RunOptions& options);

// Continues the MPM run whose checkpoint.bin is in options.out_dir: the
// folder is rewound to the checkpoint (later history rows, frames and
// profiles removed, the index rewritten) and the run goes on as if never
// stopped; on the CPU with the same number of threads, bit for bit.
// options.checkpoint_every is ignored. Throws CheckpointError for a missing
// or unusable checkpoint, std::runtime_error when the output cannot be
// written.
RunSummary resume_scene(const RunOptions& options);

// The same run with the depth-averaged model (dam.hpp; scene.method = dam): the same folder
// layout, history columns and schedule, the frames frame_NNNNN.vtp. Throws
// SceneError, before any output is written, for a scene it cannot run, and
// std::invalid_argument for options.checkpoint_every (it has no checkpoints).
RunSummary run_dam(const Scene& scene, const RunOptions& options);

}  // namespace runout
