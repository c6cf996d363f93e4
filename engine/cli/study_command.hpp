#pragma once
// `runout study`: runs a matrix of `runout run` children (one per
// combination of scene settings or samples, method, backend, shape, cell
// size, particles per cell, domain length and slope angle), here in
// parallel where cores allow or as a Slurm job array, and writes one CSV
// row per combination from its summary.json, with its cost and its
// accuracy against a reference (docs/study.md).
#include <CLI/CLI.hpp>
#include <cstdint>
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
  std::vector<std::string> settings;  // --set KEY=V1,V2,...
  std::vector<std::string> vary;      // --vary KEY=DISTRIBUTION
  int samples = 0;                    // --sample N
  std::uint64_t seed = 1;
  std::string design = "lhs";         // or "mc"
  std::string launcher = "local";     // or "slurm"
  int max_resubmits = 2;              // Slurm: submissions after the first
  std::vector<std::string> sbatch_args;
  std::string collect;                // --collect DIR: the CSV of a study's runs, none run
};

void add_study_command(CLI::App& app, StudyArgs& args, CLI::App*& command);

// Exit codes (exit_codes.hpp): 0 when every run that applies ran, 70
// when one failed (its row says how), 65 for a key, value or distribution
// the scene refuses (nothing run), 69 when sbatch cannot be run, 73 when
// the study cannot be written.
int run_study(const StudyArgs& args);

}  // namespace runout
