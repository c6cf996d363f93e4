#pragma once
// Running the `runout` binary from a test (its path comes from ctest's
// RUNOUT_CLI), and a small scene to run it on.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace runout::cli_runner {

struct Result {
  int code;
  std::string output;  // stdout and stderr
};

inline Result run_cli(const std::string& args) {
  const char* cli = std::getenv("RUNOUT_CLI");
  EXPECT_NE(cli, nullptr) << "RUNOUT_CLI is set by ctest";
  const std::string cmd = std::string(cli) + " " + args + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  while (std::fgets(buf, sizeof buf, pipe)) out += buf;
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

// The built-in scene (case 1, a Tresca slide) run coarse (1 m cells, 2 x 2
// particles: 800) to `end` seconds, one frame a second, into a temporary
// folder named `name` that goes with it: a real run's frames, shear bands
// from t = 1 s on, in a fraction of a second.
class CoarseRun {
 public:
  CoarseRun(const std::string& name, double end)
      : dir_(std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(dir_);
    const Result r = run_cli("run --cell 1.0 --ppc 2 --end " + std::to_string(end) +
                             " --threads 1 --quiet --out " + dir_.string());
    EXPECT_EQ(r.code, 0) << r.output;
  }
  ~CoarseRun() { std::filesystem::remove_all(dir_); }
  CoarseRun(const CoarseRun&) = delete;
  CoarseRun& operator=(const CoarseRun&) = delete;
  const std::filesystem::path& dir() const { return dir_; }
  std::filesystem::path pvd() const { return dir_ / "default.pvd"; }

 private:
  std::filesystem::path dir_;
};

// The scene text with each `from` replaced by its `to`; a `from` the text
// lacks fails the test.
inline std::string edited(std::string scene,
                          const std::vector<std::pair<std::string, std::string>>& edits) {
  for (const auto& [from, to] : edits) {
    const auto at = scene.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) scene.replace(at, from.size(), to);
  }
  return scene;
}

// An elastic block on a 10-degree slope, no [base]: a fraction of a second.
inline const char* const kSmallScene = R"(
[scene]
name = "small"
[grid]
cell_size = 0.5
min = [0.0, 0.0]
max = [20.0, 5.0]
[boundary]
bottom = "slip"
[time]
end = 0.2
output_interval = 0.1
[gravity]
slope_angle = 10.0
[[material]]
name = "clay"
density = 600.0
youngs_modulus = 1.0e5
poisson_ratio = 0.3
[[body]]
name = "block"
material = "clay"
type = "rectangle"
min = [1.0, 0.0]
max = [5.0, 2.0]
)";

}  // namespace runout::cli_runner
