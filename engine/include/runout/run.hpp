#pragma once
// A whole run of a scene into an output folder: frames, PVD index, history
// and the resolved scene. The CLI is a thin layer over run_scene.
#include <functional>
#include <string>

#include "runout/scene.hpp"

namespace runout {

struct RunProgress {
  double time = 0, end = 0;
  long steps = 0;
  double wall_seconds = 0;
};

struct RunOptions {
  std::string out_dir;
  std::function<void(const RunProgress&)> on_progress;  // called after each history row
};

struct RunSummary {
  int particles = 0;  // elements for the depth-averaged model
  long steps = 0;
  int frames = 0;
  double end_time = 0;
  double wall_seconds = 0;
  std::string pvd_path;
  bool at_rest = false;  // ended by the scene's at-rest criterion
  bool failed = false;
  std::string failure;  // the NumericalFailure message when failed
};

// Runs to scene.time.end or until at rest. A numerical failure ends the run early with
// failed = true: every frame and history row written before it stays, and
// the index lists only those frames. Throws std::runtime_error when the
// output cannot be written.
RunSummary run_scene(const Scene& scene, const RunOptions& options);

// The same run with the depth-averaged model (dam.hpp; scene.method = dam): the same folder
// layout, history columns and schedule, the frames frame_NNNNN.vtp. Throws
// SceneError, before any output is written, for a scene it cannot run.
RunSummary run_dam(const Scene& scene, const RunOptions& options);

}  // namespace runout
