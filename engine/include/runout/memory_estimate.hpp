#pragma once
// How much memory a run of a scene takes, estimated from the scene alone
// before anything is allocated, and the refusal of a scene that would not
// fit in this machine's available memory or whose counts overflow an int
// (particles, grid nodes and elements are indexed by int). seed_particles
// and DamSolver call require_memory first, so every run, check and study
// is refused before it allocates; `runout check` prints the estimate.
#include <optional>
#include <string>

#include "runout/scene.hpp"

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

// Throws SceneError (line 0) when a count overflows int, or when
// available_bytes is given and the estimate exceeds it; the message gives
// the estimate, the memory available and the keys that drive it.
void require_memory(const Scene& scene, Method method, std::optional<double> available_bytes);

// require_memory against available_memory().
void require_memory(const Scene& scene, Method method);

// "1.5 GiB", for messages.
std::string byte_text(double bytes);

}  // namespace runout
