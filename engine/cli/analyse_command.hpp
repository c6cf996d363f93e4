#pragma once
// `runout analyse OUT_DIR`: the shear bands, blocks and morphology of every
// frame of a run, as the ParaView filters give them, written as CSV and
// JSON into OUT_DIR/analysis/ on a machine without ParaView
// (docs/analyse.md).
#include <CLI/CLI.hpp>
#include <string>

namespace runout {

struct AnalyseArgs {
  std::string out_dir;
  double bin_spacings = 0;  // set to the filters' default by add_analyse_command
};

void add_analyse_command(CLI::App& app, AnalyseArgs& args, CLI::App*& command);

// Exit codes (exit_codes.hpp): 0 when the analysis is written (frames
// that could not be read are skipped with a warning), 65 when every listed
// frame was skipped, 64 for a folder with more than one index, 66 for one
// with none (or none readable), 73 when the analysis cannot be written.
int run_analyse(const AnalyseArgs& args);

}  // namespace runout
