#pragma once
// How much memory a run of a scene takes, estimated from the scene alone
// before anything is allocated, and the refusal of a scene that would not
// fit in this machine's available memory or whose counts overflow an int
// (particles, grid nodes and elements are indexed by int). seed_particles
// and DamSolver call require_memory first, so every run, check and study
// is refused before it allocates; `runout check` prints the estimate. A
// run of the CLI makes its estimate once and passes it on: to the cost
// estimate, the thread count and the seeding (RunOptions::memory).
#include <optional>
#include <string>

#include "runout/scene/scene.hpp"

namespace runout {

struct MemoryEstimate {
  // Particles (the MPM) or elements (the depth-averaged model).
  double items = 0;       // expected count: body areas / spacing^2, or the element count
  double items_bound = 0; // upper bound on the count, for the int limit
  double item_bytes = 0;  // per particle or element, state + scratch + a frame being written
  // The MPM grid box, at its largest: the whole domain.
  double grid_nodes = 0;
  double node_bytes = 0;
  double bytes() const { return items * item_bytes + grid_nodes * node_bytes; }
};

// The estimate of a run of `scene` with `method` (the MPM seeds particles,
// the depth-averaged model builds elements; scene.method is not looked at,
// so `runout check` can size the particles of a depth-averaged scene too).
MemoryEstimate estimate_memory(const Scene& scene, Method method);

// MemAvailable of /proc/meminfo in bytes; nullopt where it cannot be read.
std::optional<double> available_memory();

// Throws SceneError (line 0) when a count of `estimate`, the estimate of
// (scene, method), overflows int, or when available_bytes is given and the
// estimate exceeds it; the message gives the estimate, the memory
// available and the keys that drive it.
void require_memory(const Scene& scene, Method method, const MemoryEstimate& estimate,
                    std::optional<double> available_bytes);

// require_memory of estimate_memory(scene, method).
void require_memory(const Scene& scene, Method method, std::optional<double> available_bytes);

// require_memory against available_memory().
void require_memory(const Scene& scene, Method method);

// "1.5 GiB", for messages.
std::string byte_text(double bytes);

}  // namespace runout

namespace runout {

// What a run of a scene costs before it starts, from the scene alone: an
// input can pass every check of its keys and still never finish, or fill
// the disk.
struct RunCost {
  double initial_dt = 0;    // the Courant step of the stiffest material at rest [s]
  double steps = 0;         // time.end / initial_dt: a lower bound, dt falls as the slide moves
  double frames = 0;        // time.end / time.output_interval + 1
  double output_bytes = 0;  // the frames uncompressed, with their profiles
  std::string stiffest;     // the material whose P-wave sets initial_dt
};
// `memory`: estimate_memory of the scene and the run's method, whose count
// sizes the frames.
RunCost estimate_cost(const Scene& scene, const MemoryEstimate& memory);

struct CostLimits {
  double max_steps = 1e8;                    // at a few M particle-steps/s, days of work
  double max_output_bytes = 16.0 * (1 << 30);  // a frame series a workstation keeps
  std::string steps_option = "--max-steps";  // how to raise each limit
  // What lifts the output bound: the option, or, where the disk's free
  // space is the bound, room on the disk.
  std::string output_remedy = "raise the limit with --max-output";
  std::string output_limit_is = "the limit";  // "the limit", or what else bounds it (a disk)
};

// The scene's text and the name its errors give it, for the line of a key.
struct SceneSource {
  std::string name;
  std::string text;
};

// require_memory(scene, method) with the refusal placed at the line of
// the key it names in source ("scene.toml:7: grid.cell_size: ..."), as the
// parser's errors are. Returns the estimate it passed, the run's one.
MemoryEstimate require_memory(const Scene& scene, Method method, const SceneSource& source);

// Throws SceneError when the MPM run needs more steps than
// limits.max_steps (naming time.end, the step and what sets it) or writes
// more than limits.max_output_bytes (naming time.output_interval, the
// frames and their size). The message gives the key's line in source, as
// the parser's errors do, unless an override set the key (line 0 then).
// `memory`: estimate_memory(scene, method).
void require_cost(const Scene& scene, Method method, const MemoryEstimate& memory,
                  const CostLimits& limits, const SceneSource& source = {});

// The bytes free to an unprivileged writer on the file system that holds
// path (its nearest existing folder); nullopt where statvfs fails.
std::optional<double> free_disk_bytes(const std::string& path);

}  // namespace runout
