#include "analyse_command.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <vector>

#include "option_checks.hpp"
#include "exit_codes.hpp"
#include "pvd_indexes.hpp"
#include "runout/analysis/analysis_files.hpp"
#include "runout/analysis/run_analysis.hpp"

namespace runout {

namespace fs = std::filesystem;

void add_analyse_command(CLI::App& app, AnalyseArgs& args, CLI::App*& command) {
  command = app.add_subcommand("analyse",
                               "Write the shear bands, blocks and morphology of every frame as "
                               "CSV and JSON into OUT_DIR/analysis, as the filters give them");
  command->add_option("out_dir", args.out_dir, "Output folder of a run")->required();
  args.bin_spacings = analysis::kProfileBinSpacings;
  command
      ->add_option("--bin-spacings", args.bin_spacings,
                   "Width of the profile bins along the base, in particle spacings (the "
                   "Runout Morphology filter's Bin Width In Spacings)")
      ->capture_default_str()
      ->check(cli::finite_between(analysis::kMinProfileBinSpacings,
                                  analysis::kMaxProfileBinSpacings));
}

int run_analyse(const AnalyseArgs& args) {
  const std::vector<std::string> indexes = cli::pvd_indexes(args.out_dir);
  if (indexes.empty()) {
    std::cerr << "runout: analyse: no .pvd index in " << args.out_dir << "\n";
    return cli::kNoScene;
  }
  if (indexes.size() > 1) {
    std::cerr << "runout: analyse: " << args.out_dir << " holds " << indexes.size()
              << " .pvd indexes; a run's output folder holds one\n";
    return cli::kUsage;
  }
  analysis::AnalysisParameters parameters;
  parameters.bin_spacings = args.bin_spacings;
  analysis::RunAnalysis run;
  try {
    run = analysis::analyse_run(indexes[0], parameters, [](const std::string& warning) {
      std::cerr << "runout: analyse: warning: " << warning << "\n";
    });
  } catch (const std::runtime_error& e) {
    std::cerr << "runout: analyse: " << e.what() << "\n";
    return cli::kNoScene;
  }
  const std::string out = (fs::path(args.out_dir) / analysis::kAnalysisFolder).string();
  try {
    analysis::write_analysis(out, run, parameters);
  } catch (const std::exception& e) {
    std::cerr << "runout: analyse: cannot write the analysis: " << e.what() << "\n";
    return cli::kCantCreate;
  }
  std::printf("%s: %zu frames analysed, %zu skipped\n", out.c_str(), run.frames.size(),
              run.skipped.size());
  return run.frames.empty() && !run.skipped.empty() ? cli::kSceneInvalid : cli::kOk;
}

}  // namespace runout
