#pragma once
// The explicit MPM step on a GPU: the one driver of driver.hpp over the
// CUDA backend (engine/cuda/backend_cuda.cuh), one thread per particle or
// node, with the state kept on the device between steps. This header has no CUDA types, so plain
// C++ (the CLI, the tests) can include it; it exists, and the library behind
// it (runout_cuda) links, only in a build with CUDA (RUNOUT_HAVE_CUDA).
// See docs/cuda.md.
#include <memory>
#include <string>
#include <vector>

#include "runout/mpm/base.hpp"
#include "runout/mpm/material.hpp"
#include "runout/mpm/particles.hpp"
#include "runout/run/run.hpp"
#include "runout/scene/scene.hpp"
#include "runout/mpm/driver.hpp"  // NumericalFailure, StepCounters, StepConfig

namespace runout {

// Whether a CUDA device can be used; the reason in why_not when not (no
// driver, no device).
bool cuda_device_available(std::string& why_not);

class CudaSimulation {
 public:
  // Seeds on the host (seed_particles) and uploads. Throws std::runtime_error
  // when no device can be used.
  explicit CudaSimulation(const Scene& scene);
  CudaSimulation(const Scene& scene, const Particles& particles);  // given particles
  ~CudaSimulation();
  CudaSimulation(CudaSimulation&&) noexcept;
  CudaSimulation& operator=(CudaSimulation&&) noexcept;
  CudaSimulation(const CudaSimulation&) = delete;
  CudaSimulation& operator=(const CudaSimulation&) = delete;

  // As Simulation: dt = C h / max_p (c_p + |v_p|) of the last step.
  double stable_dt() const;
  // One step of size dt. Throws NumericalFailure.
  void step(double dt);
  // Steps with the CFL dt, shortening the last one to land on t exactly.
  void advance_to(double t);

  // As Simulation: the counters, and a driver continuing from them.
  StepCounters counters() const;
  void restore(const StepCounters& counters);

  double time() const;
  long steps() const;
  double last_dt() const;
  double basal_shear_force() const;
  const Base& base() const;
  double particle_spacing() const;
  const std::vector<MaterialParams>& materials() const;
  const StepConfig& config() const;  // its base view points at host arrays
  int size() const;                  // number of particles

  // Copies the particles back to the host, in the order they were given
  // (the device keeps them sorted by cell). Only for frames and history.
  void download(Particles& out) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// run_scene on the GPU (engine/cuda/run_cuda.cpp): the same folder, frames
// and history.
RunSummary run_scene_cuda(const Scene& scene, const RunOptions& options);
// resume_scene on the GPU. The device sums in no fixed order, so a resumed
// run matches an uninterrupted one to rounding, not bit for bit.
RunSummary resume_scene_cuda(const RunOptions& options);

}  // namespace runout
