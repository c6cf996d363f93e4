// The numerical guards of the step (guards.hpp), each forced: a non-finite
// stress, a particle put outside the domain, one given a speed far above
// any physical one, an inverted and a collapsed volume, and a time step far
// above the CFL limit. Each stops the step with a NumericalFailure naming
// the particle by id; a run stopped so keeps its earlier frames and its
// last checkpoint, and no file it wrote holds a non-finite number.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>

#include "cli_runner.hpp"
#include "run_folder.hpp"
#include "runout/output/checkpoint.hpp"
#include "runout/run/run.hpp"
#include "runout/mpm/simulation.hpp"
#include "scene_builders.hpp"
#include "vtu_text.hpp"

using namespace runout;
using namespace runout::run_folder;

namespace {

// A slab on a slip base under gravity, 16 m x 4 m domain, h = 0.25 m.
Scene slab() {
  Scene s = fixtures::block_scene({1.0, 0.0}, {5.0, 1.5}, {0.0, 0.0}, {16.0, 4.0}, 0.25, 2,
                                  1800.0, 2e6, 0.3);
  s.boundary.bottom = BoundaryKind::Slip;
  s.gravity.vector = {0.0, -9.81};
  return s;
}

constexpr std::int64_t kVictim = 117;  // a particle inside the slab

int index_of(const Particles& P, std::int64_t id) {
  for (int p = 0; p < P.size(); ++p)
    if (P.id[p] == id) return p;
  return -1;
}

// The failure of the step after harm(P, p) is done to the victim p: its
// message ("" when no step fails) and the particles as the step left them.
struct Outcome {
  std::string what;
  Particles after;
};
Outcome outcome_of(const std::function<void(Particles&, int)>& harm) {
  Simulation sim(slab());
  const double dt = sim.stable_dt();
  harm(sim.particles(), index_of(sim.particles(), kVictim));
  try {
    sim.step(dt);
  } catch (const NumericalFailure& e) {
    return {e.what(), sim.particles()};
  }
  return {"", sim.particles()};
}

std::string failure_after(const std::function<void(Particles&, int)>& harm) {
  return outcome_of(harm).what;
}

void expect_names_the_victim(const std::string& what, const std::string& kind) {
  EXPECT_NE(what.find(kind), std::string::npos) << what;
  EXPECT_NE(what.find("particle id " + std::to_string(kVictim) + " at ("), std::string::npos)
      << what;
  EXPECT_NE(what.find("at step 0 (t = 0 s"), std::string::npos) << what;
}

// Every Float64 array of an uncompressed frame, decoded, is finite.
void expect_finite_frame(const std::string& xml, const std::string& name) {
  const std::string key = "<DataArray type=\"Float64\" Name=\"";
  int arrays = 0;
  for (auto at = xml.find(key); at != std::string::npos; at = xml.find(key, at + 1)) {
    const auto begin = at + key.size();
    const std::string array = xml.substr(begin, xml.find('"', begin) - begin);
    const auto values =
        vtu_text::as_values<double>(vtu_text::decode_raw(vtu_text::array_text(xml, array)));
    for (const double v : values) ASSERT_TRUE(std::isfinite(v)) << name << " " << array;
    ++arrays;
  }
  EXPECT_GT(arrays, 10) << name;
}

// No file of the folder holds a non-finite number: frames decoded, text
// files searched for the way printf writes one.
void expect_no_non_finite_output(const fs::path& dir) {
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    const std::string text = read_file(e.path());
    if (e.path().extension() == ".vtu") {
      expect_finite_frame(text, name);
    } else if (e.path().extension() != ".bin") {
      for (const char* bad : {"nan", "inf", "NAN", "INF"})
        EXPECT_EQ(text.find(bad), std::string::npos) << name << " holds " << bad;
    }
  }
}

}  // namespace

// A NaN stress reaches every node the particle touches within the step,
// and through them its neighbours: the particle named is the lowest id of
// those whose state the step left non-finite, and they are many.
TEST(Guards, NonFiniteStressIsCaught) {
  const Outcome o = outcome_of([](Particles& P, int p) {
    P.sxx[p] = std::numeric_limits<double>::quiet_NaN();
  });
  EXPECT_NE(o.what.find("numerical blow-up at step 0 (t = 0 s"), std::string::npos) << o.what;
  Particles after = o.after;
  const ParticleView P = after.view();
  std::int64_t lowest = -1;
  int count = 0;
  for (int p = 0; p < P.n; ++p) {
    if (finite_state(P, p)) continue;
    ++count;
    if (lowest < 0 || P.id[p] < lowest) lowest = P.id[p];
  }
  EXPECT_GT(count, 1);
  EXPECT_NE(o.what.find("particle id " + std::to_string(lowest) + " at ("), std::string::npos)
      << o.what;
  EXPECT_NE(o.what.find(std::to_string(count) + " particle(s) at fault"), std::string::npos)
      << o.what;
}

TEST(Guards, ParticleOutsideTheDomainIsCaught) {
  const std::string what = failure_after([](Particles& P, int p) { P.x[p] = 16.0 + 0.75; });
  expect_names_the_victim(what, "particles left the grid domain");
  EXPECT_NE(what.find("16.75"), std::string::npos) << what;
}

// The bound for the slab: 2 (sqrt(2 g L) + c_p) = 2 (18.0 + 38.7) m/s,
// L = 16.49 m the domain diagonal, c_p = sqrt(M / rho) with M = E (1 - nu)
// / ((1 + nu)(1 - 2 nu)) = 2.69 MPa and rho = 1800 kg/m3. 500 m/s moves the
// particle by a metre in the step, so it stays in the domain.
TEST(Guards, RunawayVelocityIsCaught) {
  const Simulation probe(slab());
  const double M = 2e6 * 0.7 / (1.3 * 0.4);
  const double bound = 2.0 * (std::sqrt(2 * 9.81 * std::hypot(16.0, 4.0)) + std::sqrt(M / 1800.0));
  EXPECT_NEAR(probe.limits().max_speed, bound, 1e-9 * bound);

  const std::string what = failure_after([](Particles& P, int p) { P.vx[p] = 500.0; });
  expect_names_the_victim(what, "runaway velocity");
  // The slab under gravity alone stays far below the bound.
  const std::string calm = failure_after([](Particles&, int) {});
  EXPECT_EQ(calm, "");
}

TEST(Guards, InvertedVolumeIsCaught) {
  const std::string what = failure_after([](Particles& P, int p) { P.vol[p] = -P.vol[p]; });
  expect_names_the_victim(what, "inverted or collapsed volume");
  EXPECT_NE(what.find("J = vol / vol0 = -0.99"), std::string::npos) << what;
}

TEST(Guards, CollapsedVolumeIsCaught) {
  const std::string what = failure_after([](Particles& P, int p) { P.vol[p] *= 1e-3; });
  expect_names_the_victim(what, "inverted or collapsed volume");
}

TEST(Guards, StepFarAboveTheCflLimitStopsTheRunWithCleanOutput) {
  ScratchFolder folder;
  Scene s = slab();
  s.time.courant = 20.0;  // the parser allows (0, 1]; built in code to force it
  s.time.end = 5.0;
  s.time.output_interval = 0.5;
  s.output.compress = false;
  RunOptions options;
  options.out_dir = folder.path().string();
  const RunSummary r = run_scene(s, options);
  ASSERT_TRUE(r.failed) << r.steps << " steps";
  EXPECT_NE(r.failure.find("particle id "), std::string::npos) << r.failure;
  EXPECT_GE(r.frames, 1);
  expect_no_non_finite_output(folder.path());
}

// A block shot to the right at 20 m/s through a free right side leaves the
// grid in about 0.75 s; checkpoints every 0.2 s. The CLI names the particle
// and the last checkpoint, which stays readable, and every file is clean.
TEST(Guards, RunStoppedByAGuardKeepsFramesAndTheLastCheckpoint) {
  ScratchFolder folder;
  std::string scene = cli_runner::kSmallScene;
  scene.replace(scene.find("[gravity]"), 0,
                "[output]\ncompress = false\n");
  scene.replace(scene.find("bottom = \"slip\""), 0, "right = \"free\"\n");
  scene += "velocity = [20.0, 0.0]\n";
  const std::string path = folder.write("shot.toml", scene);
  const fs::path out = folder.path() / "out";
  const cli_runner::Result r = cli_runner::run_cli("run " + path + " --end 2 -q -t 2 -o " +
                                                   out.string() + " --checkpoint-every 0.2");
  EXPECT_EQ(r.code, 70) << r.output;
  EXPECT_NE(r.output.find("particles left the grid domain"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("particle id "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("the last checkpoint, at t = 0.6 s, is kept: " +
                          (out / "checkpoint.bin").string()),
            std::string::npos)
      << r.output;
  const Checkpoint cp = read_checkpoint((out / "checkpoint.bin").string());
  EXPECT_NEAR(cp.state.counters.time, 0.6, 1e-12);
  expect_frames_in_sequence(out, out / "small.pvd");
  expect_no_non_finite_output(out);
}
