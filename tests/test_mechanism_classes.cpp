// The mechanism class a run's summary.json gives for the four cases of the
// reference study (SCENES.md: elongation, elongation, block sliding,
// spreading), each scene as shipped on coarse cells with 2 x 2 particles:
// 1 m for cases 1 to 3, 0.25 m for case 4, whose horsts and grabens need
// the slide ten cells thick. The class reads the slide's travel after its
// start (morphology_rules.hpp, the late stretch), so case 3, whose faces
// slump over its first 10 s before it slides on as a block, is block
// sliding. Runs end once the mechanism shows (case 2 stops by itself).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "cli_runner.hpp"
#include "run_folder.hpp"
#include "runout/output/run_summary_file.hpp"

namespace {

std::string mechanism_of(const std::string& scene, const std::string& options) {
  const runout::run_folder::ScratchFolder folder;
  const std::string out = (folder.path() / "run").string();
  const runout::cli_runner::Result r = runout::cli_runner::run_cli(
      "run " + std::string(RUNOUT_SOURCE_DIR) + "/scenes/" + scene + ".toml " + options +
      " --ppc 2 --threads 1 --quiet --out " + out);
  EXPECT_EQ(r.code, 0) << r.output;
  const runout::RunRecord rec = runout::read_run_record(out);
  std::printf("%s %s: %s, runout %.2f m at %.1f s\n", scene.c_str(), options.c_str(),
              rec.mechanism.c_str(), rec.runout, rec.end_time);
  return rec.mechanism;
}

}  // namespace

TEST(MechanismClasses, Case1Elongates) {
  EXPECT_EQ(mechanism_of("case1_elongation", "--cell 1.0 --end 12"), "elongation");
}

TEST(MechanismClasses, Case2ElongatesOnItsNoSlipBase) {
  EXPECT_EQ(mechanism_of("case2_elongation_noslip", "--cell 1.0"), "elongation");
}

TEST(MechanismClasses, Case3SlidesAsABlockAfterItsFacesSlump) {
  EXPECT_EQ(mechanism_of("case3_block_sliding", "--cell 1.0 --end 20"), "block sliding");
}

TEST(MechanismClasses, Case4Spreads) {
  EXPECT_EQ(mechanism_of("case4_spreading", "--cell 0.25 --end 8"), "spreading");
}
