// What the CLI reads before it runs anything: a scene path that is not a
// regular file (a folder, a device, a pipe) or is larger than a scene may
// be is refused with exit 66 before it is read; a numeric option that is
// not a finite number ("nan", "inf") is refused with exit 64 instead of
// switching its limit off, and a range error prints its bound short; an
// empty --out is refused; a refusal by the disk's free space says what
// lifts it. And history.csv under a failing disk: a row is in the file
// whole or not at all, and the error gives the reason.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <stdexcept>
#include <string>

#include "cli_runner.hpp"
#include "run_folder.hpp"
#include "runout/output/history.hpp"
#include "runout/scene/scene_parser.hpp"

using namespace runout;
using namespace runout::run_folder;
using runout::cli_runner::run_cli;

TEST(SceneFile, AFolderIsRefusedBeforeReading) {
  ScratchFolder folder;
  for (const char* command : {"check ", "run "}) {
    const cli_runner::Result r = run_cli(command + folder.path().string());
    EXPECT_EQ(r.code, 66) << r.output;
    EXPECT_NE(r.output.find("is not a regular file"), std::string::npos) << r.output;
  }
}

TEST(SceneFile, ADeviceOrAPipeIsRefusedBeforeReading) {
  ScratchFolder folder;
  const fs::path fifo = folder.path() / "scene.fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  for (const std::string& path : {std::string("/dev/zero"), fifo.string()}) {
    const cli_runner::Result r = run_cli("check " + path);
    EXPECT_EQ(r.code, 66) << r.output;
    EXPECT_NE(r.output.find("is not a regular file"), std::string::npos) << r.output;
  }
}

TEST(SceneFile, AFileLargerThanASceneMayBeIsRefused) {
  ScratchFolder folder;
  const std::string path = folder.write("huge.toml", cli_runner::kSmallScene);
  fs::resize_file(path, kMaxSceneBytes + 1);  // sparse: no disk used
  const cli_runner::Result r = run_cli("check " + path);
  EXPECT_EQ(r.code, 66) << r.output;
  EXPECT_NE(r.output.find("more than a scene may be (16777216 bytes, 16 MiB)"), std::string::npos)
      << r.output;
}

TEST(NumericOptions, NotFiniteNumbersAreRefused) {
  ScratchFolder folder;
  const std::string scene = folder.write("small.toml", cli_runner::kSmallScene);
  const std::string out = " -q -o " + (folder.path() / "out").string();
  for (const std::string option :
       {"run --max-steps nan", "run --max-output nan", "run --checkpoint-every nan",
        "run --checkpoint-every inf", "check --max-steps inf", "check --budget nan"}) {
    SCOPED_TRACE(option);
    const bool run = option.rfind("run", 0) == 0;
    const cli_runner::Result r = run_cli(option + " " + scene + (run ? out : ""));
    EXPECT_EQ(r.code, 64) << r.output;
    EXPECT_NE(r.output.find("must be a finite number above 0"), std::string::npos) << r.output;
  }
  const cli_runner::Result bins =
      run_cli("analyse " + folder.path().string() + " --bin-spacings nan");
  EXPECT_EQ(bins.code, 64) << bins.output;
  EXPECT_NE(bins.output.find("--bin-spacings: must be a finite number in ["), std::string::npos)
      << bins.output;
  EXPECT_FALSE(fs::exists(folder.path() / "out"));
}

TEST(NumericOptions, ARangeErrorPrintsItsBoundShort) {
  ScratchFolder folder;
  const std::string scene = folder.write("small.toml", cli_runner::kSmallScene);
  const cli_runner::Result r = run_cli("run " + scene + " --checkpoint-every -1");
  EXPECT_EQ(r.code, 64) << r.output;
  EXPECT_NE(r.output.find("must be a finite number above 0, not '-1'"), std::string::npos)
      << r.output;
  EXPECT_LT(r.output.size(), 200u) << r.output;  // not the largest double in 309 digits
  for (const std::string& count :
       {"run " + scene + " --threads -1", "study " + scene + " --sample 0",
        "study " + scene + " --max-resubmits -1"}) {
    const cli_runner::Result c = run_cli(count);
    EXPECT_EQ(c.code, 64) << c.output;
    EXPECT_NE(c.output.find("must be a whole number from "), std::string::npos) << c.output;
    EXPECT_LT(c.output.size(), 200u) << c.output;
  }
}

TEST(FolderOptions, AnEmptyFolderNameIsRefused) {
  ScratchFolder folder;
  const std::string scene = folder.write("small.toml", cli_runner::kSmallScene);
  for (const std::string& command : {"run " + scene + " -q --out ''", std::string("resume ''"),
                                    "study " + scene + " --out ''"}) {
    const cli_runner::Result r = run_cli(command);
    EXPECT_EQ(r.code, 64) << command << "\n" << r.output;
    EXPECT_NE(r.output.find("must name a folder, not be empty"), std::string::npos) << r.output;
  }
}

// A million particles written a million times (about 200 TB): beyond the
// free space of any disk the test runs on, with both options raised far
// past it, so that the disk is what refuses the run.
TEST(Messages, AFreeSpaceRefusalSaysWhatLiftsIt) {
  ScratchFolder folder;
  const std::string scene = folder.write(
      "huge.toml", cli_runner::edited(cli_runner::kSmallScene,
                                      {{"max = [20.0, 5.0]", "max = [300.0, 300.0]"},
                                       {"end = 0.2", "end = 1000.0"},
                                       {"output_interval = 0.1", "output_interval = 0.001"},
                                       {"max = [5.0, 2.0]", "max = [251.0, 250.0]"}}));
  const cli_runner::Result r =
      run_cli("run " + scene + " --max-steps 1e15 --max-output 1e9 -o " +
              (folder.path() / "out").string());
  EXPECT_EQ(r.code, 65) << r.output;
  EXPECT_NE(r.output.find("more than the space free on the disk of"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("free space on that disk, or write to another with --out"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("--max-output"), std::string::npos) << r.output;
}

// A child process whose files may not grow past 1000 bytes (RLIMIT_FSIZE:
// a full disk on demand, EFBIG for ENOSPC) appends rows until a write
// fails; its exit code says whether the failure came with its reason.
TEST(History, AFailedWriteLeavesWholeRowsAndSaysWhy) {
  ScratchFolder folder;
  const std::string path = (folder.path() / "history.csv").string();
  const pid_t child = ::fork();
  if (child == 0) {
    ::signal(SIGXFSZ, SIG_IGN);  // the write then fails with EFBIG
    const rlimit limit{1000, 1000};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    try {
      HistoryWriter history(path);
      HistoryRow row;
      for (int k = 0; k < 100; ++k) {
        row.time = 0.1 * k + 1.0 / 3.0;
        row.step = k;
        history.append(row);
      }
    } catch (const std::runtime_error& e) {
      ::_exit(std::string(e.what()).find("File too large") != std::string::npos ? 0 : 2);
    }
    ::_exit(1);  // no write failed
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "1: no write failed, 2: the error gave no reason";
  const std::string text = read_file(path);
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n') << "a torn last row: ..." << text.substr(text.size() - 40);
}
