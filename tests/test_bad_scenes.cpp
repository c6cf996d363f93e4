// Every file of tests/bad_scenes/ run through `runout run` and `runout
// check`: the exit code and a part of the message its first line names,
//   # expect: <exit code> <substring of the message>
// and no output: a new --out folder is not created, and an existing one,
// holding an earlier run's files, is left as it was. Adding a case is adding
// a file. A second line
//   # out: <folder>
// runs `runout run` alone with that --out, where {file} is a regular file
// and {read_only} a folder without write permission (that case needs a
// user that permissions bind: not root).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace fs = std::filesystem;
using namespace runout::cli_runner;

namespace {

const fs::path kCases = fs::path(RUNOUT_SOURCE_DIR) / "tests" / "bad_scenes";

struct Case {
  fs::path file;
  int code = -1;
  std::string message;  // a part of what runout prints
  std::string out;      // the # out: folder, "" for the default runs
};

// The header lines of a case; a malformed header fails the test.
Case read_case(const fs::path& file) {
  Case c;
  c.file = file;
  std::ifstream in(file, std::ios::binary);
  std::string line;
  std::getline(in, line);
  std::istringstream expect(line);
  std::string hash, tag;
  expect >> hash >> tag >> c.code;
  std::getline(expect >> std::ws, c.message);
  EXPECT_TRUE(hash == "#" && tag == "expect:" && c.code > 0 && !c.message.empty())
      << file << ": the first line must be '# expect: <code> <message part>'";
  if (std::getline(in, line) && line.rfind("# out: ", 0) == 0) c.out = line.substr(7);
  return c;
}

std::vector<Case> all_cases() {
  std::vector<Case> cases;
  for (const auto& entry : fs::directory_iterator(kCases))
    if (entry.path().extension() == ".toml") cases.push_back(read_case(entry.path()));
  std::sort(cases.begin(), cases.end(),
            [](const Case& a, const Case& b) { return a.file < b.file; });
  return cases;
}

// Every entry under dir: a file with its contents, a folder as "/".
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> entries;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    std::string& contents = entries[fs::relative(entry.path(), dir).string()];
    if (entry.is_directory()) {
      contents = "/";
      continue;
    }
    std::ifstream in(entry.path(), std::ios::binary);
    contents.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  return entries;
}

std::string shell_quoted(const fs::path& p) { return "'" + p.string() + "'"; }

void replace_all(std::string& text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at))
    text.replace(at, from.size(), to), at += to.size();
}

class BadScenes : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("runout_bad_scenes_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    fs::permissions(dir_ / "read_only", fs::perms::owner_all, fs::perm_options::add,
                    ignored_);
    fs::remove_all(dir_);
  }

  void expect_result(const Case& c, const Result& r, const std::string& command) {
    EXPECT_EQ(r.code, c.code) << command << "\n" << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos)
        << command << ": expected \"" << c.message << "\" in:\n" << r.output;
  }

  // The default runs: a new folder stays absent, an earlier run's folder
  // keeps its files, and `runout check` fails the same way.
  void run_default(const Case& c) {
    const fs::path fresh = dir_ / "fresh";
    const fs::path earlier = dir_ / "earlier";
    fs::create_directories(earlier);
    std::ofstream(earlier / "bad.pvd") << "an earlier run's index";
    std::ofstream(earlier / "frame_00000.vtu") << "an earlier run's frame";
    const auto before = snapshot(earlier);
    for (const fs::path& out : {fresh, earlier}) {
      const std::string command = "run -q " + shell_quoted(c.file) + " --out " + shell_quoted(out);
      expect_result(c, run_cli(command), command);
    }
    EXPECT_FALSE(fs::exists(fresh)) << c.file << " created its --out folder";
    EXPECT_EQ(snapshot(earlier), before) << c.file << " changed an earlier run's folder";
    expect_result(c, run_cli("check " + shell_quoted(c.file)), "check");
    fs::remove_all(earlier);
  }

  // A # out: case: an output folder that cannot be written.
  void run_unwritable(const Case& c) {
    std::ofstream(dir_ / "file") << "a regular file";
    fs::create_directories(dir_ / "read_only");
    fs::permissions(dir_ / "read_only", fs::perms::owner_read | fs::perms::owner_exec);
    if (c.out.find("{read_only}") != std::string::npos && geteuid() == 0) {
      std::cout << c.file.filename() << ": skipped, root writes in a read-only folder\n";
      return;
    }
    std::string out = c.out;
    replace_all(out, "{file}", (dir_ / "file").string());
    replace_all(out, "{read_only}", (dir_ / "read_only").string());
    const auto before = snapshot(dir_);
    const std::string command = "run -q " + shell_quoted(c.file) + " --out " + shell_quoted(out);
    expect_result(c, run_cli(command), command);
    EXPECT_EQ(snapshot(dir_), before) << c.file << " wrote something";
  }

  fs::path dir_;
  std::error_code ignored_;
};

TEST_F(BadScenes, EachFileFailsAsItsHeaderSaysAndWritesNothing) {
  const std::vector<Case> cases = all_cases();
  EXPECT_GE(cases.size(), 30u);
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file.filename().string());
    if (c.out.empty())
      run_default(c);
    else
      run_unwritable(c);
  }
}

}  // namespace
