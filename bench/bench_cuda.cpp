// Particle-steps per second of the full MPM step on the GPU (CudaSimulation)
// and, from the same build, on the CPU (Simulation), for case-3-like scenes
// (scenes/case3_block_sliding.toml, 4 x 4 particles per cell) refined to
// about 0.3 M, 1 M and 4 M particles. Without a usable CUDA device the GPU
// benchmarks report the reason (SkipWithError) and the CPU ones still run.
// Run with --benchmark_counters_tabular=true; --benchmark_filter=Cuda for the
// GPU alone. No GPU figure has been measured in this project yet.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "runout/mpm/cuda_simulation.hpp"
#include "runout/scene/scene_parser.hpp"
#include "runout/mpm/seeding.hpp"
#include "runout/mpm/simulation.hpp"

namespace {

constexpr int kPpc = 4;

// The slide's area is fixed, so n scales as 1 / h^2: seed once at h = 1 m
// and pick h for the particles asked for.
runout::Scene case3_with(double particles) {
  runout::Scene s = runout::load_scene_file(std::string(RUNOUT_SOURCE_DIR) +
                                            "/scenes/case3_block_sliding.toml");
  runout::apply_overrides(s, 1.0, kPpc);
  const double n1 = runout::seed_particles(s).size();
  runout::apply_overrides(s, std::sqrt(n1 / particles), kPpc);
  return s;
}

template <class Sim>
void run_steps(benchmark::State& state, Sim& sim, int particles) {
  for (int k = 0; k < 10; ++k) sim.step(sim.stable_dt());  // past start-up transients
  for (auto _ : state) sim.step(sim.stable_dt());
  state.counters["particles"] = particles;
  state.counters["particle_steps_per_s"] =
      benchmark::Counter(static_cast<double>(particles) * state.iterations(),
                         benchmark::Counter::kIsRate);
}

void BM_CudaStep(benchmark::State& state) {
  std::string why_not;
  if (!runout::cuda_device_available(why_not)) {
    state.SkipWithError(why_not.c_str());
    return;
  }
  runout::CudaSimulation sim(case3_with(static_cast<double>(state.range(0))));
  run_steps(state, sim, sim.size());
}

void BM_CpuStep(benchmark::State& state) {
  runout::Simulation sim(case3_with(static_cast<double>(state.range(0))));
  run_steps(state, sim, sim.particles().size());
}

}  // namespace

BENCHMARK(BM_CudaStep)->Arg(300000)->Arg(1000000)->Arg(4000000)
    ->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CpuStep)->Arg(300000)->Arg(1000000)->Arg(4000000)
    ->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
