#pragma once
// `runout report OUT_DIR`: one self-contained HTML page of a finished run
// (docs/report.md), OUT_DIR/report.html: the scene and what the run came
// to (summary.json), charts of its runout, length and toe velocity against
// time (history.csv), its mechanism frame by frame and the shear bands and
// blocks of its last frame (the analysis of `runout analyse`, done here),
// the figures of scripts/figures (OUT_DIR/figures/*.png) and the resolved
// scene. Every image is inline, so the page opens anywhere, offline.
#include <CLI/CLI.hpp>
#include <string>

namespace runout {

struct ReportArgs {
  std::string out_dir;
};

void add_report_command(CLI::App& app, ReportArgs& args, CLI::App*& command);

// Exit codes (exit_codes.hpp): 0 when the page is written, 66 when
// the folder has no summary.json, history.csv or scene.resolved.toml (not
// a finished run) or they cannot be read, 73 when the page cannot be
// written.
int run_report(const ReportArgs& args);

}  // namespace runout
