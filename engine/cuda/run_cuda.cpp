// `runout run --backend cuda`: the MPM run of run.cpp over the CUDA driver.
// The particles come back to the host for frames and history rows only.
#include "../src/run_schedule.hpp"
#include "runout/cuda_simulation.hpp"

namespace runout {

RunSummary run_scene_cuda(const Scene& scene, const RunOptions& options) {
  const auto start = run_detail::Clock::now();
  CudaSimulation sim(scene);
  Particles host;
  return run_detail::run_mpm(scene, options, start, sim, [&]() -> const Particles& {
    sim.download(host);
    return host;
  });
}

}  // namespace runout
