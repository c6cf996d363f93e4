// summary.json (runout/output/run_summary_file.hpp): its JSON read back as
// written, its refusals, and what `runout run` writes into it for an MPM
// and a depth-averaged run, against the run's own history.csv and scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "cli_runner.hpp"
#include "runout/output/run_summary_file.hpp"
#include "runout/study/study.hpp"

using namespace runout;
namespace fs = std::filesystem;

namespace {

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

RunRecord sample_record() {
  RunRecord r;
  r.scene_hash = "0123456789abcdef";
  r.status = "blown_up";
  r.note = "particle 7: \"NaN\" velocity\tat step 3";
  r.method = "mpm";
  r.particles = 800;
  r.steps = 1234;
  r.end_time = 2.5;
  r.wall_seconds = 0.1 + 0.2;  // not a short decimal: needs all 17 digits
  r.peak_memory_mib = 6.5;
  r.runout = 12.345678901234567;
  r.runout_95 = 11.5;
  r.stop_time = std::nan("");
  r.peak_toe_velocity = 3.25;
  r.final_length = 70.5;
  r.mechanism = "elongation";
  return r;
}

}  // namespace

TEST(RunSummary, JsonReadsBackAsWritten) {
  const RunRecord r = sample_record();
  const RunRecord back = parse_run_record(to_json(r), "summary.json");
  EXPECT_EQ(back.scene_hash, r.scene_hash);
  EXPECT_EQ(back.status, r.status);
  EXPECT_EQ(back.note, r.note);
  EXPECT_EQ(back.method, r.method);
  EXPECT_EQ(back.particles, r.particles);
  EXPECT_EQ(back.steps, r.steps);
  EXPECT_EQ(back.wall_seconds, r.wall_seconds);
  EXPECT_EQ(back.runout, r.runout);
  EXPECT_EQ(back.runout_95, r.runout_95);
  EXPECT_TRUE(std::isnan(back.stop_time));  // null
  EXPECT_EQ(back.mechanism, "elongation");
  EXPECT_TRUE(back.finished());  // a blown-up run stands: not rerun
  RunRecord unclassified = r;
  unclassified.mechanism.clear();
  unclassified.status = "stopped";
  const std::string json = to_json(unclassified);
  EXPECT_NE(json.find("\"mechanism\": null"), std::string::npos) << json;
  EXPECT_FALSE(parse_run_record(json, "s").finished());
}

TEST(RunSummary, RefusalsNameTheKey) {
  std::string json = to_json(sample_record());
  const auto refused = [](const std::string& text, const std::string& expected) {
    try {
      parse_run_record(text, "run/summary.json");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  std::string no_steps = json;
  no_steps.erase(no_steps.find("  \"steps\""), no_steps.find("\n", no_steps.find("  \"steps\"")) -
                                                   no_steps.find("  \"steps\"") + 1);
  refused(no_steps, "run/summary.json: no \"steps\"");
  std::string string_runout = json;
  const std::size_t at = string_runout.find("12.345");
  string_runout.replace(at, string_runout.find(',', at) - at, "\"12.3\"");
  refused(string_runout, "\"runout\" is not a number");
  refused(json.substr(0, json.size() / 2), "run/summary.json: ");
  // A summary from before the mass front was recorded still reads, without it.
  std::string no_95 = json;
  no_95.erase(no_95.find("  \"runout_95\""),
              no_95.find("\n", no_95.find("  \"runout_95\"")) - no_95.find("  \"runout_95\"") + 1);
  EXPECT_TRUE(std::isnan(parse_run_record(no_95, "s").runout_95));
}

TEST(RunSummary, RunWritesItsSummary) {
  const fs::path out = fs::temp_directory_path() / ("runout_test_summary_" + std::to_string(getpid()));
  fs::remove_all(out);
  const cli_runner::Result mpm = cli_runner::run_cli(
      "run " + std::string(RUNOUT_SOURCE_DIR) + "/scenes/case1_elongation.toml --cell 1.6 --ppc 1 "
      "--end 6 --threads 1 --quiet --out " + (out / "mpm").string());
  ASSERT_EQ(mpm.code, 0) << mpm.output;
  const RunRecord rec = read_run_record((out / "mpm").string());
  EXPECT_EQ(rec.scene_hash, scene_hash_text(read_text(out / "mpm" / "scene.resolved.toml")));
  EXPECT_EQ(rec.method, "mpm");
  EXPECT_TRUE(rec.status == "completed" || rec.status == "at_rest") << rec.status;
  EXPECT_EQ(rec.status == "at_rest", std::isfinite(rec.stop_time));
  EXPECT_EQ(rec.end_time, 6.0);
  EXPECT_GT(rec.particles, 0);
  EXPECT_GT(rec.steps, 0);
  EXPECT_GT(rec.peak_memory_mib, 0.0);
  EXPECT_GT(rec.wall_seconds, 0.0);
  const study::History h = study::read_history((out / "mpm" / "history.csv").string());
  EXPECT_EQ(rec.runout, h.runout.back());
  ASSERT_EQ(h.runout_95.size(), h.runout.size());
  EXPECT_EQ(rec.runout_95, h.runout_95.back());
  // 95 % of the mass lies behind the toe, whose runout is the toe's.
  EXPECT_LT(h.runout_95.front(), 0.0);
  EXPECT_LT(rec.runout_95, rec.runout);
  EXPECT_EQ(rec.final_length, h.length.back());
  EXPECT_EQ(rec.peak_toe_velocity, *std::max_element(h.toe_velocity.begin(), h.toe_velocity.end()));
  // Case 1 lengthens: by 6 s at these cells it is well past the rule's
  // 1.15 times its length.
  EXPECT_EQ(rec.mechanism, "elongation");

  const cli_runner::Result dam = cli_runner::run_cli(
      "run " + std::string(RUNOUT_SOURCE_DIR) + "/scenes/case1_elongation.toml --method dam "
      "--cell 1.6 --end 3 --quiet --out " + (out / "dam").string());
  ASSERT_EQ(dam.code, 0) << dam.output;
  const RunRecord drec = read_run_record((out / "dam").string());
  EXPECT_EQ(drec.method, "dam");
  EXPECT_EQ(drec.mechanism, "");  // no particles to classify
  const study::History dh = study::read_history((out / "dam" / "history.csv").string());
  EXPECT_EQ(drec.runout, dh.runout.back());
  EXPECT_EQ(drec.runout_95, dh.runout_95.back());
  EXPECT_LT(drec.runout_95, drec.runout);

  fs::remove_all(out);
}
