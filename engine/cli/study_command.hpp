#pragma once
// `runout study`: runs a matrix of `runout run` child processes (one per
// combination of method, backend, shape, cell size, particles per cell,
// domain length and slope angle), in parallel where cores allow, and writes one CSV row per
// combination with its cost and its accuracy against a reference
// (docs/study.md).
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

namespace runout {

struct StudyArgs {
  std::string scene;  // empty: the built-in default scene
  std::vector<double> cells{0.8, 0.4};
  std::vector<int> ppc{2};
  std::vector<std::string> shapes{"gimp"}, methods{"mpm"}, backends{"cpu"};
  std::vector<double> domain_x_max;  // empty: the scene's own domain
  std::vector<double> slope_angles;  // [deg]; empty: the scene's own gravity
  std::vector<double> times;         // toe runout reported at these times [s]
  std::optional<double> end;
  std::string reference = "finest";  // or "analytic-block"
  std::string out;                   // default out/study/<scene name>
  int jobs = 0;                      // 0: cores / threads
  int threads = 1;                   // OpenMP threads per run
};

void add_study_command(CLI::App& app, StudyArgs& args, CLI::App*& command);

// Exit codes as runout's (sysexits): 0 when every run that applies ran, 70
// when one failed (its row says how), 73 when the study cannot be written.
int run_study(const StudyArgs& args);

}  // namespace runout
