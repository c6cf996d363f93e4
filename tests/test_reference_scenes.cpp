// The reference scenes of scenes/ at a coarse resolution (2 x 2 particles
// per cell, cell 1 m; 0.5 m for case 4, whose bands are two cells wide and
// need the slide to be ten cells thick) show their mechanism (SCENES.md):
// - case 2 (no-slip base) stops advancing, and its run ends at rest although
//   grid-scale noise keeps more than the at-rest share of its total kinetic
//   energy (the criterion looks at the toe's and the mean velocity's speed);
// - case 3 (rate-stiffened strength) keeps its height much better than case
//   1 (elongation): at t = 20 s its maximum thickness, as a fraction of the
//   initial 5 m, is at least 1.5 times case 1's;
// - case 4 (sensitive clay) localises plastic strain into bands: the 99th
//   percentile of xi is at least 10 times its median when it stops (at 1 m
//   cells, 5 cells thick, the bands cannot form and it is about 3).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "csv_table.hpp"
#include "run_folder.hpp"
#include "runout/measure/diagnostics.hpp"
#include "runout/measure/morphology.hpp"
#include "runout/run/run.hpp"
#include "runout/scene/scene_parser.hpp"
#include "runout/mpm/simulation.hpp"

using namespace runout;

namespace {

Scene coarse(const std::string& name, double cell = 1.0) {
  Scene s = load_scene_file(std::string(RUNOUT_SOURCE_DIR) + "/scenes/" + name + ".toml");
  apply_overrides(s, cell, 2);
  return s;
}

double thickness_ratio_at(const std::string& name, double t) {
  Simulation sim(coarse(name));
  sim.advance_to(t);
  const SlideMorphology m =
      measure_slide(sim.particles(), sim.base().view(), sim.particle_spacing());
  return m.max_thickness / 5.0;
}

double quantile(std::vector<double> v, double q) {
  const auto k = static_cast<std::ptrdiff_t>(q * (v.size() - 1));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

}  // namespace

// The slide's flow ends: from 60 s to 120 s its toe advances at under 2 %
// of its peak speed. It does not stop dead. With no material damping and a
// transfer that no longer damps at a rate 1 / dt, the slide keeps the
// elastic ringing of its start and of its stop (the sloshing of the whole
// slide along the slope, period about 6.5 s) and FLIP's particle noise
// (single particles at 3.8 m/s in the resting slide at 0.25 m cells), and
// where they lift the stress to su it yields a little: at 1 m cells the
// toe creeps about 3 cm/s, at 0.25 m 1 cm/s, with the kinetic energy
// growing slowly (docs/convergence.md, "What is left"). Until 0c4c054 it
// stopped, held by the too-stiff basal shear zone of the flattened
// particle domains.
TEST(ReferenceScenes, Case2NoSlipFlowEnds) {
  const Scene s = coarse("case2_elongation_noslip");
  Simulation sim(s);
  const auto toe = [&] {
    return measure_slide(sim.particles(), sim.base().view(), sim.particle_spacing()).toe_s;
  };
  const double toe0 = toe();
  double peak = 0, last = toe0, at60 = 0;
  for (int t = 1; t <= 120; ++t) {
    sim.advance_to(t);
    const double now = toe();
    peak = std::max(peak, now - last);  // over one second: m/s
    last = now;
    if (t == 60) at60 = now;
  }
  const double creep = (last - at60) / 60.0;
  std::printf("case 2: runout %.3f m at 60 s, %.3f m at 120 s; peak toe speed %.3f m/s, "
              "creep %.4f m/s after 60 s\n",
              at60 - toe0, last - toe0, peak, creep);
  EXPECT_GT(at60 - toe0, 5.0);
  EXPECT_LT(creep, 0.02 * peak);
}

// The scene's at-rest test (rest_fraction 1e-3 for 2 s) ends the run once
// the flow has ended (at 11.8 s, 15.48 m, at 9776f13's engine and this
// criterion). Its total kinetic energy then still holds more than 1e-3 of
// the peak, in noise next to the base, so a criterion on the total energy
// would run to the end time; the toe has advanced under 3.2 % of its peak
// speed over the last 2 s.
TEST(ReferenceScenes, Case2RunEndsAtRestThroughItsNoise) {
  Scene s = coarse("case2_elongation_noslip");
  s.time.end = 60.0;
  run_folder::ScratchFolder folder;
  RunOptions options;
  options.out_dir = (folder.path() / "out").string();
  const RunSummary r = run_scene(s, options);
  ASSERT_TRUE(r.at_rest);
  const csv_table::Table h = csv_table::read_table(folder.path() / "out" / "history.csv");
  double peak_energy = 0, peak_toe_speed = 0;
  for (std::size_t k = 0; k < h.rows.size(); ++k) {
    peak_energy = std::max(peak_energy, h.number(k, "kinetic_energy"));
    peak_toe_speed = std::max(peak_toe_speed, std::abs(h.number(k, "toe_velocity")));
  }
  const std::size_t last = h.rows.size() - 1;
  const double t_end = h.number(last, "time");
  std::size_t before = last;  // the row rest_duration before the end
  while (before > 0 && h.number(before, "time") > t_end - s.time.rest_duration) --before;
  const double advance = h.number(last, "runout") - h.number(before, "runout");
  std::printf("case 2: at rest at %.2f s, runout %.3f m; kinetic energy there %.2f %% of its "
              "peak; the toe advanced %.3f m over the last %.1f s (peak toe speed %.2f m/s)\n",
              t_end, h.number(last, "runout"), 100.0 * h.number(last, "kinetic_energy") / peak_energy,
              advance, t_end - h.number(before, "time"), peak_toe_speed);
  EXPECT_LT(t_end, 20.0);
  EXPECT_GT(h.number(last, "kinetic_energy"), 1e-3 * peak_energy);
  EXPECT_LT(advance / (t_end - h.number(before, "time")),
            std::sqrt(s.time.rest_fraction) * peak_toe_speed);
}

TEST(ReferenceScenes, Case3BlockKeepsItsHeightBetterThanCase1) {
  const double elongation = thickness_ratio_at("case1_elongation", 20.0);
  const double block = thickness_ratio_at("case3_block_sliding", 20.0);
  std::printf("thickness / 5 m at t = 20 s: case 1 %.3g, case 3 %.3g\n", elongation, block);
  EXPECT_GT(block, 1.5 * elongation);
}

// At 0.25 m (measured: median 10.2, 99th percentile 427). At 0.5 m the
// regularisation's l is 1.5 m, a third of the slide's height, and the
// slide remoulds as a whole (median 50.6, 99th percentile 469) and
// elongates instead of spreading: too coarse for case 4 (docs/validation.md).
TEST(ReferenceScenes, Case4LocalisesPlasticStrainIntoBands) {
  Simulation sim(coarse("case4_spreading", 0.25));
  sim.advance_to(16.0);
  const std::vector<double> xi(sim.particles().xi.begin(), sim.particles().xi.end());
  const double median = quantile(xi, 0.5), high = quantile(xi, 0.99);
  std::printf("case 4: xi median %.3g, 99th percentile %.3g\n", median, high);
  EXPECT_GT(high, 10.0 * median);
}
