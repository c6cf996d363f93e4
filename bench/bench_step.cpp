// Particle-steps per second of the full MPM step (grid refit, binning, both
// scatters, grid update with Geo-contact, G2P, volumetric smoothing, stress
// update):
// - on the built-in default scene refined to about 1e5 and 1e6 particles,
//   with its material made linear elastic (the foundation's figure) and as
//   it is, Tresca;
// - on the escarpment as shipped (softening, the rate term, the regularised
//   band along its base: the step a sensitive clay's whole run takes) and
//   with its softening local on a held base, at 0.25 m with 2 x 2
//   particles (89 664) and at its reference resolution, 0.2 m with 4 x 4
//   (560 640): the regularisation's cost per step.
// Run with --benchmark_counters_tabular=true; OMP_NUM_THREADS picks the
// cores.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <string>

#include "runout/scene/scene_parser.hpp"
#include "runout/mpm/simulation.hpp"

namespace {

// The default slide has 200 m2; ppc^2 particles per h^2 gives the h for n.
runout::Scene default_scene_with(double particles, runout::MaterialModel model) {
  runout::Scene s = runout::parse_scene(runout::default_scene_toml(), "default.toml");
  const double ppc = s.grid.ppc;
  runout::apply_overrides(s, ppc * std::sqrt(200.0 / particles), std::nullopt);
  s.materials[0].model = model;
  return s;
}

void time_steps(benchmark::State& state, runout::Simulation& sim) {
  sim.advance_to(10 * sim.stable_dt());  // past start-up transients
  for (auto _ : state) sim.step(sim.stable_dt());
  const double n = sim.particles().size();
  state.counters["particles"] = n;
  state.counters["threads"] = omp_get_max_threads();
  state.counters["particle_steps_per_s"] =
      benchmark::Counter(n * state.iterations(), benchmark::Counter::kIsRate);
}

void run_steps(benchmark::State& state, runout::MaterialModel model) {
  runout::Simulation sim(default_scene_with(static_cast<double>(state.range(0)), model));
  time_steps(state, sim);
}

void BM_ElasticStep(benchmark::State& state) { run_steps(state, runout::MaterialModel::Elastic); }
void BM_TrescaStep(benchmark::State& state) { run_steps(state, runout::MaterialModel::Tresca); }

// Args: the cell in centimetres, the particles per cell per direction, and
// 1 for the escarpment as shipped, 0 for its local softening on a held base.
void BM_EscarpmentStep(benchmark::State& state) {
  runout::Scene s =
      runout::load_scene_file(std::string(RUNOUT_SOURCE_DIR) + "/scenes/escarpment.toml");
  runout::apply_overrides(s, 0.01 * static_cast<double>(state.range(0)),
                          static_cast<int>(state.range(1)));
  if (state.range(2) == 0) {
    s.base.clay_band = false;
    for (auto& m : s.materials) m.band_thickness = 0.0;
  }
  runout::Simulation sim(s);
  time_steps(state, sim);
}

}  // namespace

BENCHMARK(BM_ElasticStep)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_TrescaStep)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_EscarpmentStep)
    ->ArgNames({"cell_cm", "ppc", "regularised"})
    ->Args({25, 2, 0})
    ->Args({25, 2, 1})
    ->Args({20, 4, 0})
    ->Args({20, 4, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_MAIN();
