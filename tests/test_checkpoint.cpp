// Checkpoint and resume (issue "long runs that cannot be lost"): the file
// keeps every array and counter exactly; a Simulation rebuilt from it
// continues bit for bit; `runout resume` rewinds a folder to its checkpoint
// and finishes the run exactly as an uninterrupted one (history, index and
// every frame byte for byte); damaged files are refused with a clear error.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>

#include "cli_runner.hpp"
#include "run_folder.hpp"
#include "runout/output/checkpoint.hpp"
#include "runout/mpm/simulation.hpp"
#include "scene_builders.hpp"

using namespace runout;
using namespace runout::cli_runner;
using namespace runout::run_folder;

namespace {

template <class T>
bool same_bits(const T& a, const T& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
}

void expect_same_particles(const Particles& a, const Particles& b) {
  const auto da = a.double_arrays(), db = b.double_arrays();
  for (std::size_t k = 0; k < da.size(); ++k) EXPECT_TRUE(same_bits(*da[k], *db[k])) << "array " << k;
  EXPECT_TRUE(same_bits(a.body, b.body));
  EXPECT_TRUE(same_bits(a.material, b.material));
  EXPECT_TRUE(same_bits(a.id, b.id));
}

void expect_same_counters(const StepCounters& a, const StepCounters& b) {
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.last_dt, b.last_dt);
  EXPECT_EQ(a.basal_shear_force, b.basal_shear_force);
  EXPECT_EQ(a.max_signal_speed, b.max_signal_speed);
  EXPECT_EQ(a.speed_limit, b.speed_limit);
}

// Every value with a full mantissa, so that any rounding on the way shows.
Particles random_particles(int n) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Particles P;
  P.resize(n);
  for (auto* a : P.double_arrays())
    for (double& v : *a) v = 1e3 * u(rng);
  for (int p = 0; p < n; ++p) {
    P.body[p] = p % 3;
    P.material[p] = p % 2;
    P.id[p] = (std::int64_t{1} << 40) + 3 * p;
  }
  return P;
}

CheckpointState sample_state() {
  CheckpointState s;
  s.scene_toml = "[scene]\nname = \"x\"\n";
  s.counters = StepCounters{0.123456789, 4321, 1.5e-4, -2.5e3, 17.25, 80.5};
  s.schedule.row = 37;
  s.schedule.checkpoint_rows = 5;
  s.schedule.frames = 2;
  s.schedule.pvd = {{0.0, "frame_00000.vtu"}, {0.1, "frame_00001.vtu"}};
  s.schedule.rest_peak = 12.5;
  s.schedule.rest_since = 0.05;
  s.schedule.initial_toe = 4.75;
  return s;
}

// A slab sliding down a 20-degree slope in the slope frame on a slip base:
// it moves and strains, so every array changes every step.
Scene sliding_slab() {
  Scene s = fixtures::block_scene({1.0, 0.0}, {5.0, 1.5}, {0.0, 0.0}, {16.0, 4.0}, 0.25, 2,
                                  1800.0, 2e6, 0.3);
  s.boundary.bottom = BoundaryKind::Slip;
  s.gravity.vector = {9.81 * std::sin(0.349), -9.81 * std::cos(0.349)};
  return s;
}

}  // namespace

TEST(Checkpoint, EncodeDecodeKeepsEveryArrayAndCounterExactly) {
  const Particles P = random_particles(257);
  const CheckpointState s = sample_state();
  const Checkpoint cp = decode_checkpoint(encode_checkpoint(s, P), "memory");
  expect_same_particles(cp.particles, P);
  expect_same_counters(cp.state.counters, s.counters);
  EXPECT_EQ(cp.state.scene_toml, s.scene_toml);
  EXPECT_EQ(cp.state.schedule.row, 37);
  EXPECT_EQ(cp.state.schedule.checkpoint_rows, 5);
  EXPECT_EQ(cp.state.schedule.frames, 2);
  EXPECT_EQ(cp.state.schedule.pvd, s.schedule.pvd);
  EXPECT_EQ(cp.state.schedule.rest_peak, 12.5);
  EXPECT_EQ(cp.state.schedule.rest_since, 0.05);
  EXPECT_EQ(cp.state.schedule.initial_toe, 4.75);
}

// The particles are reordered in memory every 50 steps, keyed on the step
// count: the checkpoint at step 73 sits between two reorders, and the
// continued run crosses the next one.
TEST(Checkpoint, RebuiltSimulationContinuesBitForBit) {
  const Scene scene = sliding_slab();
  Simulation straight(scene), first(scene);
  const double dt = 0.5 * first.stable_dt();
  for (int k = 0; k < 73; ++k) first.step(dt);
  ScheduleState schedule;
  schedule.checkpoint_rows = 1;
  const Checkpoint cp = decode_checkpoint(
      encode_checkpoint({"", first.counters(), schedule}, first.particles()), "memory");
  Simulation resumed(scene, cp.particles);
  resumed.restore(cp.state.counters);

  for (int k = 0; k < 73; ++k) straight.step(dt);
  for (int k = 0; k < 60; ++k) {
    straight.step(straight.stable_dt());
    resumed.step(resumed.stable_dt());
  }
  expect_same_particles(resumed.particles(), straight.particles());
  expect_same_counters(resumed.counters(), straight.counters());
  // The slab did move: the comparison is not between two resting states.
  const Particles& P = straight.particles();
  EXPECT_GT(std::fabs(P.x[0] - P.x0[0]), 1e-4);
}

TEST(Checkpoint, DamagedFilesAreRefusedWithTheReason) {
  const std::string good = encode_checkpoint(sample_state(), random_particles(20));
  const auto error_of = [](const std::string& bytes) -> std::string {
    try {
      decode_checkpoint(bytes, "cp.bin");
    } catch (const CheckpointError& e) {
      return e.what();
    }
    return "accepted";
  };
  std::string magic = good;
  magic[0] = 'X';
  EXPECT_NE(error_of(magic).find("not a Runout checkpoint"), std::string::npos) << error_of(magic);
  std::string version = good;
  version[8] = 9;
  EXPECT_NE(error_of(version).find("version 9"), std::string::npos) << error_of(version);
  for (const std::size_t keep : {std::size_t{10}, good.size() / 2, good.size() - 1})
    EXPECT_NE(error_of(good.substr(0, keep)).find("truncated"), std::string::npos)
        << keep << ": " << error_of(good.substr(0, keep));
  // A flipped bit anywhere after the header, the checksum's own included.
  for (const std::size_t at : {std::size_t{30}, good.size() / 2, good.size() - 1}) {
    std::string flipped = good;
    flipped[at] ^= 0x10;
    EXPECT_NE(error_of(flipped).find("checksum"), std::string::npos) << at << ": " << error_of(flipped);
  }
  EXPECT_THROW(read_checkpoint("/nonexistent/checkpoint.bin"), CheckpointMissing);
}

class CheckpointCli : public ::testing::Test {
 protected:
  ScratchFolder folder_;
  // kSmallScene to t = 0.4 s: 40 history rows, 5 frames.
  std::string scene_ = folder_.write("small.toml", kSmallScene);
  std::string run(const std::string& out, const std::string& extra = "") {
    const Result r = run_cli("run " + scene_ + " --end 0.4 -q -t 2 -o " +
                             (folder_.path() / out).string() + " " + extra);
    EXPECT_EQ(r.code, 0) << r.output;
    return (folder_.path() / out).string();
  }
  // kSmallScene to t = 0.2 s with its one checkpoint at 0.1 s: a run that
  // ended still moving, for `resume --end`.
  fs::path shorter(const std::string& out) {
    const fs::path dir = folder_.path() / out;
    const Result r = run_cli("run " + scene_ + " --end 0.2 --checkpoint-every 0.1 -q -t 2 -o " +
                             dir.string());
    EXPECT_EQ(r.code, 0) << r.output;
    return dir;
  }
};

TEST_F(CheckpointCli, ResumeFinishesTheRunAsIfNeverStopped) {
  const fs::path straight = run("straight");
  const fs::path stopped = run("stopped", "--checkpoint-every 0.2");

  // The checkpoint of row 20 (t = 0.2 s, frames 0..2), the only one: a run
  // that reaches its last row is done and writes none there.
  const Checkpoint cp = read_checkpoint((stopped / "checkpoint.bin").string());
  EXPECT_EQ(cp.state.schedule.row, 20);
  EXPECT_EQ(cp.state.schedule.frames, 3);
  EXPECT_NEAR(cp.state.counters.time, 0.2, 1e-12);

  // What a run killed after t = 0.3 s leaves, and worse: a torn history
  // row, a frame and a profile past the checkpoint, an interrupted write's
  // temporary.
  std::ofstream(stopped / "history.csv", std::ios::app) << "0.41,99,0.001,1.2";
  std::ofstream(stopped / "frame_00007.vtu") << "<VTKFile";
  std::ofstream(stopped / "profile_00007.csv") << "# time";
  std::ofstream(stopped / ".frame_00008.vtu.tmp.123.4") << "<VTK";

  const Result r = run_cli("resume " + stopped.string() + " -q -t 2");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("resumed from the checkpoint at t = 0.2"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(stopped / ".frame_00008.vtu.tmp.123.4"));
  expect_frames_in_sequence(stopped, stopped / "small.pvd");
  expect_same_run(straight, stopped, "small.pvd");
  EXPECT_EQ(pvd_files(stopped / "small.pvd").size(), 5u);
}

TEST_F(CheckpointCli, DamagedOrMissingCheckpointIsRefused) {
  const fs::path out = run("out", "--checkpoint-every 0.1");
  const Result missing = run_cli("resume " + (folder_.path() / "nowhere").string());
  EXPECT_EQ(missing.code, 66) << missing.output;
  EXPECT_NE(missing.output.find("cannot open checkpoint"), std::string::npos) << missing.output;

  std::string bytes = read_file(out / "checkpoint.bin");
  bytes[bytes.size() / 2] ^= 1;
  std::ofstream(out / "checkpoint.bin", std::ios::binary) << bytes;
  const std::string history = read_file(out / "history.csv");
  const Result corrupt = run_cli("resume " + out.string());
  EXPECT_EQ(corrupt.code, 65) << corrupt.output;
  EXPECT_NE(corrupt.output.find("checksum mismatch"), std::string::npos) << corrupt.output;
  EXPECT_EQ(read_file(out / "history.csv"), history) << "a refused resume leaves the folder";
}

TEST_F(CheckpointCli, DepthAveragedRunRefusesCheckpoints) {
  const Result r = run_cli("run " + scene_ + " --method dam --checkpoint-every 0.1 -q -o " +
                           (folder_.path() / "dam").string());
  EXPECT_EQ(r.code, 64) << r.output;
  EXPECT_NE(r.output.find("writes no checkpoints"), std::string::npos) << r.output;
}

// A new run in the folder of an earlier one removes its checkpoint with its
// frames: resume could otherwise bring back the earlier run.
TEST_F(CheckpointCli, AFreshRunRemovesAnEarlierCheckpoint) {
  const fs::path out = run("out", "--checkpoint-every 0.1");
  ASSERT_TRUE(fs::exists(out / "checkpoint.bin"));
  run("out");
  EXPECT_FALSE(fs::exists(out / "checkpoint.bin"));
  EXPECT_EQ(run_cli("resume " + out.string()).code, 66);
}

// A run that ended still moving goes on to a later end: `resume --end`
// from its last checkpoint makes the run that went to that end at once
// (history, index, every frame byte for byte), and the folder's scene and
// the checkpoints written on the way agree, so it can be resumed again.
TEST_F(CheckpointCli, ResumeWithALaterEndGoesOnAsOneRun) {
  const fs::path straight = run("straight");
  const fs::path out = shorter("shorter");
  ASSERT_TRUE(fs::exists(out / "checkpoint.bin"));

  const std::string history = read_file(out / "history.csv");
  const Result early = run_cli("resume " + out.string() + " --end 0.05 -q");
  EXPECT_EQ(early.code, 79) << early.output;
  EXPECT_NE(early.output.find("--end 0.05 s is not after the checkpoint's t = 0.1 s"),
            std::string::npos)
      << early.output;
  EXPECT_EQ(read_file(out / "history.csv"), history) << "a refused resume leaves the folder";

  // The later end is held to the limits `runout run --end` holds it to.
  const Result costly = run_cli("resume " + out.string() + " --end 0.4 --max-steps 10 -q");
  EXPECT_EQ(costly.code, 65) << costly.output;
  EXPECT_NE(costly.output.find("time.end: the run needs at least"), std::string::npos)
      << costly.output;
  EXPECT_NE(costly.output.find("--max-steps"), std::string::npos) << costly.output;
  const Result bulky = run_cli("resume " + out.string() + " --end 0.4 --max-output 1e-6 -q");
  EXPECT_EQ(bulky.code, 65) << bulky.output;
  EXPECT_NE(bulky.output.find("time.output_interval: the run writes about"), std::string::npos)
      << bulky.output;
  EXPECT_EQ(read_file(out / "history.csv"), history) << "a refused resume leaves the folder";

  const Result on = run_cli("resume " + out.string() + " --end 0.4 -q -t 2");
  ASSERT_EQ(on.code, 0) << on.output;
  EXPECT_NE(on.output.find("resumed from the checkpoint at t = 0.1"), std::string::npos)
      << on.output;
  expect_same_run(straight, out, "small.pvd");
  const std::string resolved = read_file(out / "scene.resolved.toml");
  EXPECT_NE(resolved.find("end = 0.4"), std::string::npos) << resolved;
  EXPECT_NE(resolved.find("\"time.end = 0.2\", \"time.end = 0.4\""), std::string::npos) << resolved;

  const Result again = run_cli("resume " + out.string() + " -q -t 2");
  ASSERT_EQ(again.code, 0) << again.output;
  EXPECT_NE(again.output.find("resumed from the checkpoint at t = 0.3"), std::string::npos)
      << again.output;
  expect_same_run(straight, out, "small.pvd");
}

// A `resume --end` writes the folder's scene with the new end before it runs
// on; stopped (SIGKILL) before its first checkpoint it leaves a folder whose
// checkpoint still holds the old end. That folder goes on to the new end; a
// scene changed in anything else is still another run's.
TEST_F(CheckpointCli, ResumeWithALaterEndStoppedBeforeItsCheckpointGoesOn) {
  const fs::path straight = run("straight");
  const fs::path out = shorter("stopped");
  ASSERT_TRUE(fs::exists(out / "checkpoint.bin"));
  // The scene a resume --end 0.4 writes, taken from a copy that went on.
  const fs::path copy = folder_.path() / "copy";
  fs::copy(out, copy, fs::copy_options::recursive);
  const Result on = run_cli("resume " + copy.string() + " --end 0.4 -q -t 2");
  ASSERT_EQ(on.code, 0) << on.output;
  const std::string extended = read_file(copy / "scene.resolved.toml");

  const std::string own = read_file(out / "scene.resolved.toml");
  std::ofstream(out / "scene.resolved.toml", std::ios::trunc) << own + "# another run\n";
  const Result other = run_cli("resume " + out.string() + " -q");
  EXPECT_EQ(other.code, 65) << other.output;
  EXPECT_NE(other.output.find("the checkpoint belongs to another run"), std::string::npos)
      << other.output;

  std::ofstream(out / "scene.resolved.toml", std::ios::trunc) << extended;
  const Result resumed = run_cli("resume " + out.string() + " -q -t 2");
  ASSERT_EQ(resumed.code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resumed from the checkpoint at t = 0.1"), std::string::npos)
      << resumed.output;
  expect_same_run(straight, out, "small.pvd");
  EXPECT_EQ(read_file(out / "scene.resolved.toml"), extended);
}

// Rows of this build's columns are not appended under another version's
// header: a folder whose history.csv has other columns is refused whole.
TEST_F(CheckpointCli, ResumeRefusesAHistoryOfOtherColumns) {
  const fs::path out = run("other", "--checkpoint-every 0.2");
  const std::string history = read_file(out / "history.csv");
  const std::string older = "time,step,dt,toe" + history.substr(history.find('\n'));
  std::ofstream(out / "history.csv", std::ios::trunc) << older;
  const Result r = run_cli("resume " + out.string() + " -q");
  EXPECT_EQ(r.code, 79) << r.output;
  EXPECT_NE(r.output.find("has another version's columns (time,step,dt,toe)"), std::string::npos)
      << r.output;
  EXPECT_EQ(read_file(out / "history.csv"), older) << "a refused resume leaves the folder";
}
