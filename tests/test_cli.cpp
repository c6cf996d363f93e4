// The runout command line, end to end: exit codes of each error class, no
// output folder left behind by a bad scene, and a small run's outputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <utility>

#include "cli_runner.hpp"
#include "run_folder.hpp"

namespace fs = std::filesystem;
using namespace runout::cli_runner;

namespace {

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("runout_cli_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }
  fs::path dir_;
};


}  // namespace

TEST_F(Cli, VersionAndHelp) {
  EXPECT_EQ(run_cli("--version").code, 0);
  const Result help = run_cli("--help");
  EXPECT_EQ(help.code, 0);
  EXPECT_NE(help.output.find("run"), std::string::npos);
  EXPECT_NE(help.output.find("check"), std::string::npos);
}

// OpenMP threads spin briefly at barriers, then sleep, unless the user
// chose otherwise: spinning ones made two threads half as fast as one
// beside another busy process, sleeping at once cost an idle run 7 % (docs/performance.md,
// "Runs under load").
TEST_F(Cli, OpenMpWaitsBrieflyUnlessTheUserSetsThePolicyOrTheSpins) {
  const auto saved = [](const char* name) {
    const char* value = std::getenv(name);
    return std::make_pair(value != nullptr, std::string(value ? value : ""));
  };
  const auto restore = [](const char* name, const std::pair<bool, std::string>& value) {
    if (value.first) setenv(name, value.second.c_str(), 1); else unsetenv(name);
  };
  const auto policy = saved("OMP_WAIT_POLICY"), spins = saved("GOMP_SPINCOUNT");
  unsetenv("OMP_WAIT_POLICY");
  unsetenv("GOMP_SPINCOUNT");
  const Result brief = run_cli("info");
  setenv("OMP_WAIT_POLICY", "active", 1);
  const Result active = run_cli("info");
  unsetenv("OMP_WAIT_POLICY");
  setenv("GOMP_SPINCOUNT", "20", 1);
  const Result user_spins = run_cli("info");
  restore("OMP_WAIT_POLICY", policy);
  restore("GOMP_SPINCOUNT", spins);
  EXPECT_EQ(brief.code, 0) << brief.output;
  EXPECT_NE(brief.output.find("OpenMP wait policy: PASSIVE\nOpenMP spin count: 1000"),
            std::string::npos)
      << brief.output;
  EXPECT_NE(active.output.find("OpenMP wait policy: active\nOpenMP spin count: (the policy's)"),
            std::string::npos)
      << active.output;
  EXPECT_NE(user_spins.output.find("OpenMP wait policy: (libgomp's default)\nOpenMP spin count: 20"),
            std::string::npos)
      << user_spins.output;
}

TEST_F(Cli, UsageErrorIs64) {
  EXPECT_EQ(run_cli("run --no-such-flag").code, 64);
  EXPECT_EQ(run_cli("").code, 64);
}

TEST_F(Cli, MissingSceneFileIs66) {
  const Result r = run_cli("check " + (dir_ / "nope.toml").string());
  EXPECT_EQ(r.code, 66);
  EXPECT_NE(r.output.find("nope.toml"), std::string::npos);
}

TEST_F(Cli, InvalidSceneIs65AndLeavesNoOutput) {
  std::string bad = kSmallScene;
  bad.replace(bad.find("cell_size = 0.5"), 15, "cell_size = -0.5");
  const std::string scene = write("bad.toml", bad);
  const fs::path out = dir_ / "out";
  const Result r = run_cli("run " + scene + " --out " + out.string());
  EXPECT_EQ(r.code, 65);
  EXPECT_NE(r.output.find("grid.cell_size"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(":5:"), std::string::npos) << r.output;  // the line of the key
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(Cli, CheckPrintsTheResolvedSceneAndSizes) {
  const Result r = run_cli("check " + write("small.toml", kSmallScene) + " --cell 0.25 --ppc 1");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("# particles:        128"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("grid.cell_size = 0.25"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("initial dt"), std::string::npos);
}

// On a held base (case 4 without its basal band) the runout needs 4 x 4
// particles per cell or more; with fewer the basal layer crowds and the
// slide stops short (docs/validation.md), so check says so for a softening
// clay, and only for one, and not where the clay's band is at the base.
TEST_F(Cli, CheckSaysASofteningClayNeedsFourByFourParticles) {
  const std::string case4 = RUNOUT_SOURCE_DIR "/scenes/case4_spreading.toml";
  std::string held = runout::run_folder::read_file(case4);
  const std::string band = "clay_band = true";
  ASSERT_NE(held.find(band), std::string::npos);
  held.replace(held.find(band), band.size(), "clay_band = false");
  const std::string held_scene = write("held.toml", held);
  const Result two = run_cli("check " + held_scene + " --cell 1.0 --ppc 2");
  ASSERT_EQ(two.code, 0) << two.output;
  EXPECT_NE(two.output.find("# particles/cell:   2 x 2: a softening clay (St = 40)"),
            std::string::npos)
      << two.output;
  const Result four = run_cli("check " + held_scene + " --cell 1.0 --ppc 4");
  ASSERT_EQ(four.code, 0) << four.output;
  EXPECT_EQ(four.output.find("# particles/cell:"), std::string::npos) << four.output;
  const Result insensitive = run_cli("check " + write("small.toml", kSmallScene) + " --ppc 2");
  ASSERT_EQ(insensitive.code, 0) << insensitive.output;
  EXPECT_EQ(insensitive.output.find("# particles/cell:"), std::string::npos);
  // Case 4 as shipped, its band at the base: 2 x 2 particles suffice.
  const Result banded = run_cli("check " + case4 + " --cell 1.0 --ppc 2");
  ASSERT_EQ(banded.code, 0) << banded.output;
  EXPECT_EQ(banded.output.find("# particles/cell:"), std::string::npos) << banded.output;
}

// A band's displacement is measured over nonlocal_length, which must span
// three cells (docs/strength.md, "The averaging length"): check says so
// where a cell is too coarse for the escarpment's l = 3 m, and not at 1 m.
TEST_F(Cli, CheckSaysAnAveragingLengthUnderThreeCellsIsTooShort) {
  const std::string escarpment = RUNOUT_SOURCE_DIR "/scenes/escarpment.toml";
  const Result coarse = run_cli("check " + escarpment + " --cell 2.0 --ppc 1");
  ASSERT_EQ(coarse.code, 0) << coarse.output;
  EXPECT_NE(coarse.output.find("# averaging length: material 'clay': nonlocal_length = 3 m spans "
                               "1.5 cells of 2 m"),
            std::string::npos)
      << coarse.output;
  EXPECT_NE(coarse.output.find("use cells of 1 m or less"), std::string::npos) << coarse.output;
  const Result fine = run_cli("check " + escarpment + " --cell 1.0 --ppc 1");
  ASSERT_EQ(fine.code, 0) << fine.output;
  EXPECT_EQ(fine.output.find("# averaging length:"), std::string::npos) << fine.output;
}

// Without --threads a run takes one thread per 10 000 particles (at most
// every core): on small scenes a second thread cost more than it brought
// (engine/cli/thread_count.hpp). OMP_NUM_THREADS, where set, stands.
TEST_F(Cli, ThreadsFollowTheSceneSizeUnlessTheUserSays) {
  const char* user = std::getenv("OMP_NUM_THREADS");
  const std::string saved = user ? user : "";
  unsetenv("OMP_NUM_THREADS");
  const std::string small = write("small.toml", kSmallScene);
  const Result by_size = run_cli("run " + small + " --out " + (dir_ / "a").string());
  const Result given = run_cli("run " + small + " --threads 2 --out " + (dir_ / "b").string());
  // The default scene at 0.1 m cells: 80 000 particles, eight threads' worth.
  const Result large = run_cli("check --cell 0.1");
  setenv("OMP_NUM_THREADS", "2", 1);
  const Result from_env = run_cli("run " + small + " --out " + (dir_ / "c").string());
  if (user) setenv("OMP_NUM_THREADS", saved.c_str(), 1); else unsetenv("OMP_NUM_THREADS");
  ASSERT_EQ(by_size.code, 0) << by_size.output;
  EXPECT_NE(by_size.output.find(", 1 threads)"), std::string::npos) << by_size.output;
  EXPECT_NE(given.output.find(", 2 threads)"), std::string::npos) << given.output;
  EXPECT_NE(from_env.output.find(", 2 threads)"), std::string::npos) << from_env.output;
  ASSERT_EQ(large.code, 0) << large.output;
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const std::string expected = "on " + std::to_string(std::min(8, cores)) + " thread(s) here";
  EXPECT_NE(large.output.find(expected), std::string::npos) << large.output;
}

TEST_F(Cli, RunWritesFramesIndexHistoryAndResolvedScene) {
  const fs::path out = dir_ / "out";
  const Result r = run_cli("run " + write("small.toml", kSmallScene) + " --out " + out.string() +
                           " --threads 2");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(fs::exists(out / "frame_00000.vtu"));
  EXPECT_TRUE(fs::exists(out / "frame_00002.vtu"));
  EXPECT_FALSE(fs::exists(out / "frame_00003.vtu"));
  EXPECT_TRUE(fs::exists(out / "small.pvd"));
  EXPECT_TRUE(fs::exists(out / "scene.resolved.toml"));
  std::ifstream history(out / "history.csv");
  std::string line;
  int rows = 0;
  while (std::getline(history, line)) ++rows;
  EXPECT_EQ(rows, 1 + 21);  // header, t = 0 and 20 rows
  for (const auto& e : fs::directory_iterator(out))
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << "temporary file left";
}

// Regularised softening runs in the one driver (driver.hpp), so on either
// backend: where the cuda backend is refused it is for want of a device,
// never for the scene.
TEST_F(Cli, NonlocalSofteningRunsOnEitherBackend) {
  std::string text = kSmallScene;
  const std::string elastic = "poisson_ratio = 0.3\n";
  text.replace(text.find(elastic), elastic.size(),
               elastic + "model = \"tresca\"\nsu0 = 5000.0\nband_thickness = 0.2\nnonlocal_length = 1.5\n");
  const std::string scene = write("small.toml", text);
  const Result cuda = run_cli("run " + scene + " --backend cuda -q --out " + (dir_ / "gpu").string());
  EXPECT_TRUE(cuda.code == 0 || cuda.code == 69) << cuda.output;
  EXPECT_EQ(cuda.output.find("nonlocal_length"), std::string::npos) << cuda.output;
  const Result cpu = run_cli("run " + scene + " -q --out " + (dir_ / "cpu").string());
  EXPECT_EQ(cpu.code, 0) << cpu.output;
}

TEST_F(Cli, BackendIsCheckedBeforeAnyOutput) {
  const std::string scene = write("small.toml", kSmallScene);
  EXPECT_EQ(run_cli("run " + scene + " --backend gpu").code, 64);
  // Without a usable device (or CUDA in the build) the cuda backend is
  // refused with 69 and leaves no folder; with one it runs.
  const fs::path out = dir_ / "out";
  const Result r = run_cli("run " + scene + " --backend cuda -q --out " + out.string());
  if (r.code == 69) {
    EXPECT_NE(r.output.find("--backend cuda"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out));
  } else {
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(fs::exists(out / "small.pvd"));
  }
}

// A step count far beyond any int: check prints it (a lround of it printed
// -9223372036854775808), and only a raised limit lets check get that far.
TEST_F(Cli, CheckPrintsAStepCountBeyondAnyInteger) {
  std::string scene = kSmallScene;
  scene.replace(scene.find("youngs_modulus = 1.0e5"), 22, "youngs_modulus = 1.0e300");
  const std::string path = write("stiff.toml", scene);
  const Result refused = run_cli("check " + path);
  EXPECT_EQ(refused.code, 65) << refused.output;
  EXPECT_NE(refused.output.find("raise the limit with --max-steps"), std::string::npos)
      << refused.output;
  const Result r = run_cli("check " + path + " --max-steps 1e300");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("# steps (about):    9.47e+148 "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("# wall (about):     "), std::string::npos) << r.output;
}

// check measures the step on the scene itself: the whole run's wall time
// on this machine, from its own milliseconds per step.
TEST_F(Cli, CheckEstimatesTheWallTimeFromTheStepMeasuredHere) {
  const Result r = run_cli("check " + write("small.toml", kSmallScene));
  ASSERT_EQ(r.code, 0) << r.output;
  const auto at = r.output.find("# wall (about):     ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const std::string line = r.output.substr(at, r.output.find('\n', at) - at);
  EXPECT_NE(line.find(":"), std::string::npos) << line;
  EXPECT_NE(line.find(" ms per step, measured)"), std::string::npos) << line;
}

// The limits are options: a run within a raised limit goes ahead.
TEST_F(Cli, ARunBeyondALimitGoesAheadWhenTheLimitIsRaised) {
  const std::string path = write("small.toml", kSmallScene);
  const Result refused = run_cli("run -q " + path + " --max-steps 5 -o " + (dir_ / "a").string());
  EXPECT_EQ(refused.code, 65) << refused.output;
  EXPECT_NE(refused.output.find("more than the limit of 5;"), std::string::npos) << refused.output;
  EXPECT_FALSE(fs::exists(dir_ / "a"));
  const Result tight = run_cli("run -q " + path + " --max-output 1e-6 -o " + (dir_ / "b").string());
  EXPECT_EQ(tight.code, 65) << tight.output;
  EXPECT_NE(tight.output.find("time.output_interval: the run writes about 3 frames"),
            std::string::npos)
      << tight.output;
  EXPECT_EQ(run_cli("run -q " + path + " --max-steps 1e4 -o " + (dir_ / "c").string()).code, 0);
}
