#include "report_command.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <vector>

#include "exit_codes.hpp"
#include "pvd_indexes.hpp"
#include "html_page.hpp"
#include "runout/analysis/result_columns.hpp"
#include "runout/analysis/run_analysis.hpp"
#include "runout/output/atomic_file.hpp"
#include "runout/output/file_text.hpp"
#include "runout/output/run_summary_file.hpp"
#include "runout/scene/scene_parser.hpp"
#include "runout/study/study.hpp"

namespace runout {

namespace fs = std::filesystem;

namespace {

constexpr const char* kReportFile = "report.html";

std::string chart_image(const std::string& alt, const std::string& svg) {
  return "<img class=\"chart\" alt=\"" + html::escape(alt) + "\" src=\"" +
         html::data_uri("image/svg+xml", svg) + "\">\n";
}

std::string result_section(const RunRecord& r, const Scene& scene) {
  const std::string stop = std::isnan(r.stop_time) ? "not at rest" : html::number(r.stop_time) + " s";
  const std::vector<std::vector<std::string>> rows = {
      {"status", r.status + (r.note.empty() ? "" : " (" + r.note + ")")},
      {"method", r.method},
      {"cell size", html::number(scene.grid.cell_size) + " m"},
      {r.method == "dam" ? "elements" : "particles",
       std::to_string(r.particles) +
           (r.method == "dam" ? "" : ", " + std::to_string(scene.grid.ppc) + " x " +
                                         std::to_string(scene.grid.ppc) + " per cell")},
      {"simulated time", html::number(r.end_time) + " s"},
      {"at rest at", stop},
      {"runout", html::number(r.runout) + " m"},
      {"runout of 95 % of the mass", html::number(r.runout_95) + " m"},
      {"peak toe velocity", html::number(r.peak_toe_velocity) + " m/s"},
      {"final length", html::number(r.final_length) + " m"},
      {"mechanism", r.mechanism.empty() ? "not classified" : r.mechanism},
      {"steps", std::to_string(r.steps)},
      {"wall time", html::number(r.wall_seconds) + " s"},
      {"peak memory", html::number(r.peak_memory_mib) + " MiB"},
  };
  return "<h2>Result</h2>\n" + html::table({"quantity", "value"}, rows);
}

std::string motion_section(const study::History& h) {
  return "<h2>Motion</h2>\n" +
         chart_image("runout and length against time",
                     html::line_chart_svg("Runout and main-body length", "time [s]", "distance [m]",
                                          {{"runout", h.time, h.runout},
                                           {"length", h.time, h.length}})) +
         chart_image("toe velocity against time",
                     html::line_chart_svg("Toe velocity", "time [s]", "velocity [m/s]",
                                          {{"toe velocity", h.time, h.toe_velocity}}));
}

// The values of `columns` named in `names`, for one item ("-" for a name
// no column has, so that a row always fills its header).
template <class Item>
std::vector<std::string> cells(const std::vector<analysis::Column<Item>>& columns,
                               const std::vector<std::string>& names, const Item& item) {
  std::vector<std::string> row;
  for (const std::string& name : names) {
    const auto c = std::find_if(columns.begin(), columns.end(),
                                [&](const auto& column) { return name == column.name; });
    row.push_back(c == columns.end()                         ? "-"
                  : c->kind == analysis::Column<Item>::String ? c->text(item)
                                                              : html::number(c->number(item)));
  }
  return row;
}

template <class Item>
std::string item_table(const std::vector<analysis::Column<Item>>& columns,
                       const std::vector<Item>& items, const char* none) {
  if (items.empty()) return std::string("<p>") + none + "</p>\n";
  std::vector<std::string> names;
  for (const auto& c : columns) names.push_back(c.name);
  std::vector<std::vector<std::string>> rows;
  for (const Item& item : items) rows.push_back(cells(columns, names, item));
  return html::table(names, rows);
}

std::string mechanism_section(const std::string& pvd_path) {
  const analysis::RunAnalysis run =
      analysis::analyse_run(pvd_path, analysis::AnalysisParameters{}, [](const std::string& w) {
        std::cerr << "runout: report: warning: " << w << "\n";
      });
  if (run.frames.empty()) return "<h2>Mechanism</h2>\n<p>No frame could be analysed.</p>\n";
  const std::vector<std::string> names = {"runout", "length", "max_thickness", "length_ratio",
                                          "late_stretch", "troughs", "mechanism"};
  std::vector<std::string> header = {"time [s]"};
  header.insert(header.end(), names.begin(), names.end());
  std::vector<std::vector<std::string>> rows;
  for (const analysis::FrameAnalysis& f : run.frames) {
    std::vector<std::string> row = {html::number(f.time)};
    const auto values = cells(analysis::morphology_columns(), names, f.morphology);
    row.insert(row.end(), values.begin(), values.end());
    rows.push_back(row);
  }
  const analysis::FrameAnalysis& last = run.frames.back();
  return "<h2>Mechanism, frame by frame</h2>\n"
         "<p>The class of each frame from its profile and the travel up to it "
         "(docs/filters.md, \"Mechanism class\").</p>\n" +
         html::table(header, rows) + "<h2>Shear bands at t = " + html::number(last.time) +
         " s</h2>\n" + item_table(analysis::band_columns(), last.bands, "No shear band.") +
         "<h2>Blocks at t = " + html::number(last.time) + " s</h2>\n" +
         item_table(analysis::block_columns(), last.blocks, "No block.");
}

std::string figures_section(const fs::path& out_dir) {
  std::vector<fs::path> pngs;
  std::error_code error;
  for (const auto& e : fs::directory_iterator(out_dir / "figures", error))
    if (e.path().extension() == ".png") pngs.push_back(e.path());
  std::sort(pngs.begin(), pngs.end());
  std::string out = "<h2>Figures</h2>\n";
  if (pngs.empty())
    return out + "<p>None: <code>scripts/figures " + html::escape(out_dir.string()) +
           "</code> renders them, then run the report again.</p>\n";
  for (const fs::path& png : pngs) {
    const std::string bytes = file_text_or_throw(png, "cannot read " + png.string());
    out += "<figure><img alt=\"" + html::escape(png.filename().string()) + "\" src=\"" +
           html::data_uri("image/png", bytes) + "\"><figcaption>" +
           html::escape(png.filename().string()) + "</figcaption></figure>\n";
  }
  return out;
}

// Marks the body with how many of its images loaded (data-images="N/M"),
// for a reader, or a test, to check the page whole.
constexpr const char* kImageCheck = R"(<script>
window.addEventListener('load', function () {
  var images = document.images, loaded = 0;
  for (var i = 0; i < images.length; ++i)
    if (images[i].complete && images[i].naturalWidth > 0) ++loaded;
  document.body.setAttribute('data-images', loaded + '/' + images.length);
});
</script>
)";

constexpr const char* kStyle = R"(<style>
body { font-family: sans-serif; max-width: 70em; margin: 2em auto; color: #222; }
table { border-collapse: collapse; margin: 0.5em 0 1.5em; font-size: 0.9em; }
th, td { border: 1px solid #ccc; padding: 0.2em 0.6em; text-align: right; }
th { background: #f0f0f0; }
img { max-width: 100%; }
img.chart { margin: 0.5em 1em 0.5em 0; }
figure { margin: 1em 0; }
pre { background: #f7f7f7; padding: 1em; overflow-x: auto; }
</style>
)";

std::string page(const fs::path& out_dir) {
  const RunRecord record = read_run_record(out_dir.string());
  const std::string scene_path = (out_dir / kResolvedSceneFile).string();
  const std::string scene_text = read_scene_text(scene_path);
  const Scene scene = parse_scene(scene_text, scene_path);
  const study::History history = study::read_history((out_dir / "history.csv").string());
  std::string body = "<h1>" + html::escape(scene.name) + "</h1>\n<p>" +
                     html::escape(scene.description) + "</p>\n" + result_section(record, scene) +
                     motion_section(history);
  if (record.method == "mpm") {
    const std::vector<std::string> indexes = cli::pvd_indexes(out_dir.string());
    body += indexes.size() == 1
                ? mechanism_section(indexes[0])
                : "<h2>Mechanism</h2>\n<p>The folder has no single .pvd index to analyse.</p>\n";
  }
  body += figures_section(out_dir) + "<h2>Scene</h2>\n<pre>" + html::escape(scene_text) + "</pre>\n";
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>Runout: " +
         html::escape(scene.name) + "</title>\n" + kStyle + "</head>\n<body>\n" + body +
         kImageCheck + "</body>\n</html>\n";
}

}  // namespace

void add_report_command(CLI::App& app, ReportArgs& args, CLI::App*& command) {
  command = app.add_subcommand(
      "report", "Write OUT_DIR/report.html: one self-contained page of a finished run (summary, "
                "charts, mechanism, bands and blocks, figures, scene)");
  command->add_option("out_dir", args.out_dir, "Output folder of a finished run")->required();
}

int run_report(const ReportArgs& args) {
  const fs::path out_dir(args.out_dir);
  std::string text;
  try {
    text = page(out_dir);
  } catch (const std::exception& e) {
    std::cerr << "runout: report: " << args.out_dir << ": " << e.what() << "\n";
    return cli::kNoScene;
  }
  const fs::path path = out_dir / kReportFile;
  try {
    write_file_atomically(path.string(), text);
  } catch (const std::exception& e) {
    std::cerr << "runout: report: cannot write " << path.string() << ": " << e.what() << "\n";
    return cli::kCantCreate;
  }
  std::printf("%s\n", path.string().c_str());
  return cli::kOk;
}

}  // namespace runout
