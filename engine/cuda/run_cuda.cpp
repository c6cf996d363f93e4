// `runout run --backend cuda`: the MPM run of run.cpp over the CUDA driver.
// The particles come back to the host for frames and history rows only.
#include "../src/run/run_schedule.hpp"
#include "runout/mpm/cuda_simulation.hpp"
#include "runout/mpm/seeding.hpp"

namespace runout {

namespace {

// The particles copied back for a frame, history row or checkpoint.
auto host_copy(const CudaSimulation& sim, Particles& host) {
  return [&sim, &host]() -> const Particles& {
    sim.download(host);
    return host;
  };
}

}  // namespace

RunSummary run_scene_cuda(const Scene& scene, const RunOptions& options) {
  const auto start = run_detail::Clock::now();
  CudaSimulation sim(scene, seed_particles(scene, options.memory));
  Particles host;
  return run_detail::run_mpm(scene, options, start, sim, host_copy(sim, host));
}

RunSummary resume_scene_cuda(const RunOptions& options) {
  const auto start = run_detail::Clock::now();
  Scene scene;
  const Checkpoint cp = run_detail::load_for_resume(options, scene);
  CudaSimulation sim(scene, cp.particles);
  sim.restore(cp.state.counters);
  Particles host;
  return run_detail::run_mpm(scene, options, start, sim, host_copy(sim, host),
                             &cp.state.schedule);
}

}  // namespace runout
