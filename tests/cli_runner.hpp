#pragma once
// Running the `runout` binary from a test (its path comes from ctest's
// RUNOUT_CLI), and a small scene to run it on.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <string>

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
