// `runout analyse OUT_DIR` end to end, without VTK: on a short real run it
// writes a morphology row, band and block tables and a profile for every
// frame, whose numbers are the run's own (history.csv, the engine's
// profiles); a frame spoilt, missing or unreadable is skipped with a warning
// naming it and the others kept; a folder without an index, or whose frames
// are all unreadable, is refused. That the numbers are the VTK filters' is
// test_analyse_filters.cpp, where ParaView is available.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "csv_table.hpp"
#include "run_folder.hpp"
#include "runout/analysis/result_columns.hpp"

namespace fs = std::filesystem;
using runout::cli_runner::Result;
using runout::cli_runner::run_cli;
using runout::csv_table::read_table;
using runout::csv_table::Table;
using runout::run_folder::read_file;
using runout::run_folder::ScratchFolder;

namespace {

// A coarse run to t = 3 s (four frames), once for the suite, each test
// working on a copy.
class Analyse : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { run_ = new runout::cli_runner::CoarseRun("runout_analyse_run", 3); }
  static void TearDownTestSuite() { delete run_; }

  // A copy of the run to spoil, in the test's own folder.
  fs::path copy_of_run() const {
    const fs::path dir = scratch_.path() / "run";
    fs::copy(run_->dir(), dir, fs::copy_options::recursive);
    return dir;
  }
  static Result analyse(const fs::path& dir, const std::string& options = "") {
    return run_cli("analyse " + dir.string() + options);
  }

  static runout::cli_runner::CoarseRun* run_;
  ScratchFolder scratch_;
};
runout::cli_runner::CoarseRun* Analyse::run_ = nullptr;

const char* const kPvd = "default.pvd";

// The frame files of the run, in order.
std::vector<std::string> frames_of(const fs::path& dir) {
  return runout::run_folder::pvd_files(dir / kPvd);
}

std::string numbered(const char* stem, int k) {
  char name[32];
  std::snprintf(name, sizeof name, "%s_%05d.csv", stem, k);
  return name;
}

// Changes one base64 character of the frame's positions: the file keeps
// its size, loses its CRC-32.
void spoil(const fs::path& frame) {
  std::string text = read_file(frame);
  const auto at = text.find('>', text.find("Name=\"Points\"")) + 40;
  text[at] = text[at] == 'A' ? 'B' : 'A';
  std::ofstream(frame, std::ios::binary) << text;
}

std::vector<std::string> column_names_after(const char* first, const char* second,
                                            const std::vector<std::string>& rest) {
  std::vector<std::string> names{first};
  if (second) names.push_back(second);
  names.insert(names.end(), rest.begin(), rest.end());
  return names;
}

template <class Item>
std::vector<std::string> names_of(const std::vector<runout::analysis::Column<Item>>& columns) {
  std::vector<std::string> names;
  for (const auto& c : columns) names.push_back(c.name);
  return names;
}

}  // namespace

TEST_F(Analyse, EveryFrameWithTheRunsOwnNumbers) {
  const fs::path dir = copy_of_run();
  const Result r = analyse(dir);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("4 frames analysed, 0 skipped"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
  const fs::path out = dir / "analysis";

  const Table morphology = read_table(out / "morphology.csv");
  EXPECT_EQ(morphology.header, column_names_after("frame", "Time",
                                                  names_of(runout::analysis::morphology_columns())));
  ASSERT_EQ(morphology.rows.size(), 4u);
  // Each row against the history row of the frame's time: the same
  // measure_slide of the same doubles, to the last digit.
  const Table history = read_table(dir / "history.csv");
  for (std::size_t k = 0; k < 4; ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(morphology.cell(k, "frame"), std::to_string(k));
    std::size_t row = 0;
    while (row < history.rows.size() && history.cell(row, "time") != morphology.cell(k, "Time"))
      ++row;
    ASSERT_LT(row, history.rows.size()) << "no history row at t = " << morphology.cell(k, "Time");
    for (const char* name : {"toe", "rear", "length", "max_thickness", "runout", "toe_velocity",
                             "centroid_x", "centroid_y", "centroid_s", "centroid_velocity",
                             "outside_mass"})
      EXPECT_EQ(morphology.cell(k, name), history.cell(row, name)) << name;
  }
  EXPECT_EQ(morphology.cell(0, "mechanism"), "undetermined");  // not moved yet at t = 0
  EXPECT_EQ(morphology.cell(3, "mechanism"), "elongation");    // case 1 elongates

  int bands = 0;
  for (int k = 0; k < 4; ++k) {
    SCOPED_TRACE(k);
    // The engine's profiles are in cells of 2 particle spacings (ppc 2):
    // the analysis' default bins, so the files are the same.
    EXPECT_EQ(read_file(out / numbered("profile", k)), read_file(dir / numbered("profile", k)));
    const Table band = read_table(out / numbered("bands", k));
    EXPECT_EQ(band.header, column_names_after("band_id", nullptr,
                                              names_of(runout::analysis::band_columns())));
    bands += static_cast<int>(band.rows.size());
    for (std::size_t b = 0; b < band.rows.size(); ++b) {
      EXPECT_EQ(band.cell(b, "band_id"), std::to_string(b));
      EXPECT_GT(band.number(b, "particle_count"), 9);  // the default smallest band is 10
      EXPECT_GT(band.number(b, "length"), 0);
    }
    const Table block = read_table(out / numbered("blocks", k));
    EXPECT_EQ(block.header, column_names_after("block_id", nullptr,
                                               names_of(runout::analysis::block_columns())));
    EXPECT_NE(read_file(out / numbered("bands", k)).find("# time = " + morphology.cell(k, "Time")),
              std::string::npos);
  }
  EXPECT_GT(bands, 0) << "a Tresca slide moving for 3 s has shear bands";

  const std::string json = read_file(out / "analysis.json");
  EXPECT_NE(json.find("\"index\": \"default.pvd\""), std::string::npos);
  EXPECT_NE(json.find("\"manifest_checked\": true"), std::string::npos);
  EXPECT_NE(json.find("\"percentile\": 90"), std::string::npos);  // the filters' defaults
  EXPECT_NE(json.find("\"bin_spacings\": 2"), std::string::npos);
  for (const std::string& frame : frames_of(dir))
    EXPECT_NE(json.find("\"file\": \"" + frame + "\""), std::string::npos) << frame;
  EXPECT_NE(json.find("\"skeleton\": [["), std::string::npos);
  EXPECT_NE(json.find("\"skipped\": []"), std::string::npos);
}

TEST_F(Analyse, BinSpacingsSetTheProfileAlone) {
  const fs::path dir = copy_of_run();
  ASSERT_EQ(analyse(dir).code, 0);
  const std::string morphology = read_file(dir / "analysis" / "morphology.csv");
  const Result r = analyse(dir, " --bin-spacings 4");
  ASSERT_EQ(r.code, 0) << r.output;
  // Twice as wide: about half the bins; the mechanism's own bins are fixed.
  const std::size_t fine = read_table(dir / numbered("profile", 3)).rows.size();
  const std::size_t coarse = read_table(dir / "analysis" / numbered("profile", 3)).rows.size();
  EXPECT_NEAR(static_cast<double>(coarse), fine / 2.0, 1.0);
  EXPECT_EQ(read_file(dir / "analysis" / "morphology.csv"), morphology);
  EXPECT_NE(read_file(dir / "analysis" / "analysis.json").find("\"bin_spacings\": 4"),
            std::string::npos);
  // The filter's range.
  EXPECT_EQ(analyse(dir, " --bin-spacings 0.1").code, 64);
  EXPECT_EQ(analyse(dir, " --bin-spacings 2000").code, 64);
}

TEST_F(Analyse, SpoiltAndMissingFramesAreSkippedWithAWarningTheRestKept) {
  const fs::path dir = copy_of_run();
  const std::vector<std::string> frames = frames_of(dir);
  ASSERT_EQ(frames.size(), 4u);
  spoil(dir / frames[1]);
  fs::remove(dir / frames[2]);
  const Result r = analyse(dir);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("warning: frame_00001.vtu: does not match the manifest: CRC-32"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("warning: frame_00002.vtu: missing; skipped"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("2 frames analysed, 2 skipped"), std::string::npos) << r.output;
  const fs::path out = dir / "analysis";
  const Table morphology = read_table(out / "morphology.csv");
  ASSERT_EQ(morphology.rows.size(), 2u);
  EXPECT_EQ(morphology.cell(0, "frame"), "0");
  EXPECT_EQ(morphology.cell(1, "frame"), "3");
  for (const char* stem : {"bands", "blocks", "profile"}) {
    EXPECT_TRUE(fs::exists(out / numbered(stem, 0))) << stem;
    EXPECT_FALSE(fs::exists(out / numbered(stem, 1))) << stem;
    EXPECT_FALSE(fs::exists(out / numbered(stem, 2))) << stem;
    EXPECT_TRUE(fs::exists(out / numbered(stem, 3))) << stem;
  }
  const std::string json = read_file(out / "analysis.json");
  EXPECT_NE(json.find("{\"frame\": 1, \"file\": \"frame_00001.vtu\", \"reason\": \"does not match"),
            std::string::npos)
      << json;
  EXPECT_NE(json.find("{\"frame\": 2, \"file\": \"frame_00002.vtu\", \"reason\": \"missing\"}"),
            std::string::npos)
      << json;
}

TEST_F(Analyse, AgainAfterAFrameIsLostKeepsNothingOfIt) {
  const fs::path dir = copy_of_run();
  ASSERT_EQ(analyse(dir).code, 0);
  ASSERT_TRUE(fs::exists(dir / "analysis" / numbered("bands", 3)));
  spoil(dir / frames_of(dir)[3]);
  ASSERT_EQ(analyse(dir).code, 0);
  for (const char* stem : {"bands", "blocks", "profile"})
    EXPECT_FALSE(fs::exists(dir / "analysis" / numbered(stem, 3))) << stem;
  EXPECT_EQ(read_table(dir / "analysis" / "morphology.csv").rows.size(), 3u);
}

TEST_F(Analyse, ANewRunIntoTheFolderRemovesTheOldAnalysis) {
  const fs::path dir = copy_of_run();
  ASSERT_EQ(analyse(dir).code, 0);
  ASSERT_TRUE(fs::exists(dir / "analysis" / "morphology.csv"));
  const Result again = run_cli("run " + (dir / "scene.resolved.toml").string() + " --end 1 --out " +
                               dir.string() + " --quiet");
  ASSERT_EQ(again.code, 0) << again.output;
  EXPECT_FALSE(fs::exists(dir / "analysis"));
}

TEST_F(Analyse, WithoutAManifestFramesAreReadUncheckedAndUnreadableOnesSkipped) {
  const fs::path dir = copy_of_run();
  fs::remove(dir / (std::string(kPvd) + ".manifest"));
  // Not base64 any more: the reader refuses it.
  std::string text = read_file(dir / frames_of(dir)[2]);
  const auto at = text.find('>', text.find("Name=\"mass\"")) + 12;
  text[at] = '*';
  std::ofstream(dir / frames_of(dir)[2], std::ios::binary) << text;
  const Result r = analyse(dir);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("warning: no manifest default.pvd.manifest"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("warning: frame_00002.vtu: the array \"mass\" cannot be decoded"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(read_table(dir / "analysis" / "morphology.csv").rows.size(), 3u);
  EXPECT_NE(read_file(dir / "analysis" / "analysis.json").find("\"manifest_checked\": false"),
            std::string::npos);
}

TEST_F(Analyse, EveryFrameUnreadableIs65) {
  const fs::path dir = copy_of_run();
  for (const std::string& frame : frames_of(dir)) fs::resize_file(dir / frame, 100);
  const Result r = analyse(dir);
  EXPECT_EQ(r.code, 65) << r.output;
  EXPECT_NE(r.output.find("0 frames analysed, 4 skipped"), std::string::npos) << r.output;
}

TEST_F(Analyse, DepthAveragedFramesAreRefusedSayingWhy) {
  const fs::path dir = scratch_.path() / "dam";
  ASSERT_EQ(run_cli("run --method dam --end 1 --quiet --out " + dir.string()).code, 0);
  const Result r = analyse(dir);
  EXPECT_EQ(r.code, 65) << r.output;
  EXPECT_NE(r.output.find("frame_00000.vtp: a VTK PolyData file, not a particle frame"),
            std::string::npos)
      << r.output;
}

TEST_F(Analyse, FolderWithoutOneIndexIsRefused) {
  EXPECT_EQ(analyse(scratch_.path()).code, 66);  // empty
  const Result missing = analyse(scratch_.path() / "none");
  EXPECT_EQ(missing.code, 66);
  EXPECT_NE(missing.output.find("no .pvd index"), std::string::npos) << missing.output;
  const fs::path dir = copy_of_run();
  fs::copy_file(dir / kPvd, dir / "other.pvd");
  EXPECT_EQ(analyse(dir).code, 64);
  EXPECT_EQ(run_cli("analyse").code, 64);
}
