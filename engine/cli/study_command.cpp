#include "study_command.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <thread>

#include "exit_codes.hpp"
#include "runout/output/atomic_file.hpp"
#include "runout/run/device_info.hpp"
#include "runout/run/memory_estimate.hpp"
#include "runout/run/run_control.hpp"
#include "runout/output/run_summary_file.hpp"
#include "runout/scene/scene_parser.hpp"
#include "runout/study/study.hpp"
#include "child_process.hpp"
#include "option_checks.hpp"
#include "scene_loading.hpp"
#include "study_parameters.hpp"
#include "study_slurm.hpp"

namespace runout {
namespace {

namespace fs = std::filesystem;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The study's own arguments, kept beside its runs for `--collect DIR`.
constexpr const char* kArgsFile = "study.args";

// One scene of the study: a point of the scene settings, the domain's far
// end and the slope angle (--domain-x-max, --slope-angle), and the study's
// copy of it that the children read.
struct Variant {
  Scene scene;
  std::string file;
  std::size_t point = 0;               // index into StudyParameters::points
  std::vector<SceneSetting> settings;  // that point's values
  double domain_x_max = 0;
  std::optional<double> slope_angle;  // empty: the scene's own gravity
  std::optional<study::RigidBlock> block;  // --reference analytic-block: on this slope

  // The runs of one variant are measured against each other.
  bool same_place(const Variant& o) const {
    return point == o.point && domain_x_max == o.domain_x_max && slope_angle == o.slope_angle;
  }
};

// One combination of the matrix.
struct RunSpec {
  std::string id, method, backend, shape;  // shape empty for the depth-averaged model
  double cell = 0;
  int ppc = 0;                             // 0 for the depth-averaged model
  const Variant* variant = nullptr;
  std::string skip;                        // why it is not run; empty: it runs
  std::string scene_hash;                  // of the scene the run resolves
};

// What a run's summary.json says, with its cost.
struct RunResult {
  std::string status = "skipped", note;
  double wall = kNaN, peak_mib = kNaN, end_time = kNaN, stop_time = kNaN;
  long particles = 0, steps = 0;
  std::string mechanism;
  study::Metrics metrics;
  bool measured = false;  // summary.json read
};

std::string format(double v, const char* fmt = "%.6g") {
  if (!std::isfinite(v)) return "";
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

// What tells a variant's runs and files apart: "_p<point>" when the study
// sets or samples scene keys, "_x<far end>" when it has several domains,
// "_a<angle>" when it sets the slope.
std::string variant_suffix(const StudyArgs& a, std::size_t points, const Variant& v) {
  std::string suffix;
  if (points > 1) suffix += "_p" + std::to_string(v.point);
  if (a.domain_x_max.size() > 1) suffix += "_x" + format(v.domain_x_max);
  if (v.slope_angle) suffix += "_a" + format(*v.slope_angle);
  return suffix;
}

std::string run_id(const RunSpec& r, const std::string& suffix) {
  std::string id = r.method + "_" + r.backend;
  if (!r.shape.empty()) id += "_" + r.shape;
  id += "_h" + format(r.cell);
  if (r.ppc > 0) id += "_ppc" + std::to_string(r.ppc);
  return id + suffix;
}

// The scene as the study runs it, once per point of the scene settings,
// far end of the domain and slope angle (--end applied), with its rigid
// block when that is the reference. Throws SceneError for a setting, a
// slope or a reference the scene cannot take, before anything is written.
std::vector<Variant> variants(const StudyArgs& a, const SceneSource& base,
                              const StudyParameters& params) {
  std::vector<Variant> out;
  for (std::size_t p = 0; p < params.points.size(); ++p) {
    Scene scene = scene_with_settings(base.text, base.name, params.points[p]);
    apply_overrides(scene, std::nullopt, std::nullopt, a.end);
    std::vector<double> ends = a.domain_x_max;
    if (ends.empty()) ends.push_back(scene.grid.max.x());
    std::vector<std::optional<double>> angles(a.slope_angles.begin(), a.slope_angles.end());
    if (angles.empty()) angles.emplace_back();
    for (double x : ends)
      for (const std::optional<double>& angle : angles) {
        Variant v{scene, "", p, params.points[p], x, angle, std::nullopt};
        v.scene.grid.max.x() = x;
        if (angle) study::set_slope_angle(v.scene, *angle);
        if (a.reference == "analytic-block") v.block = study::rigid_block(v.scene);
        out.push_back(std::move(v));
      }
  }
  return out;
}

// Each variant's scene written beside the runs, so that every child reads
// the same file.
void write_scenes(const StudyArgs& a, std::size_t points, std::vector<Variant>& variants,
                  const fs::path& dir) {
  for (Variant& v : variants) {
    v.file = (dir / ("scene" + variant_suffix(a, points, v) + ".toml")).string();
    write_file_atomically(v.file, to_toml(v.scene));
  }
}

// The scene the child resolves from child_args, as `runout run` loads it:
// the hash its summary.json records, and its size.
Scene child_scene(const RunSpec& r) {
  const bool mpm = r.method == "mpm";
  cli::SceneOverrides overrides;
  overrides.cell = r.cell;
  if (mpm) overrides.ppc = r.ppc;
  overrides.method = r.method;
  if (mpm) overrides.shape = r.shape;
  return cli::load_scene(cli::scene_source(r.variant->file), overrides);
}

// The rows expand_matrix gives, counted before any scene is parsed: an
// MPM method runs each shape and ppc, the depth-averaged one once per cell.
double matrix_runs(const StudyArgs& a, std::size_t points) {
  double per_cell = 0;
  for (const std::string& method : a.methods)
    per_cell += method == "dam" ? 1.0 : double(a.shapes.size()) * double(a.ppc.size());
  return double(points) * double(std::max<std::size_t>(1, a.domain_x_max.size())) *
         double(std::max<std::size_t>(1, a.slope_angles.size())) * double(a.backends.size()) *
         double(a.cells.size()) * per_cell;
}

std::vector<RunSpec> expand_matrix(const StudyArgs& a, std::size_t points,
                                   const std::vector<Variant>& variants) {
  std::string no_cuda;
  const bool cuda = !cuda_devices(no_cuda).empty();
  std::vector<RunSpec> runs;
  for (const Variant& v : variants)
    for (const std::string& method : a.methods)
      for (const std::string& backend : a.backends)
        for (double cell : a.cells) {
          RunSpec r{"", method, backend, "", cell, 0, &v, "", ""};
          if (method == "dam") {  // no shape functions, no particles: one run per cell size
            if (backend == "cuda") r.skip = "the depth-averaged model runs on the CPU only";
            runs.push_back(r);
            continue;
          }
          for (const std::string& shape : a.shapes)
            for (int ppc : a.ppc) {
              r.shape = shape;
              r.ppc = ppc;
              if (backend == "cuda" && !cuda) r.skip = "no CUDA device: " + no_cuda;
              runs.push_back(r);
            }
        }
  for (RunSpec& r : runs) {
    r.id = run_id(r, variant_suffix(a, points, *r.variant));
    if (r.skip.empty()) r.scene_hash = scene_hash_text(to_toml(child_scene(r)));
  }
  return runs;
}

// `runout run` of one combination; argv[0] is this binary. Paths are
// absolute: a Slurm element may start in another folder.
std::vector<std::string> child_args(const RunSpec& r, const fs::path& run_dir, int threads) {
  std::vector<std::string> v{fs::read_symlink("/proc/self/exe").string(), "run",
                             fs::absolute(r.variant->file).string(), "--method", r.method,
                             "--backend", r.backend, "--cell", format(r.cell, "%.17g"),
                             "--out", fs::absolute(run_dir).string(), "--quiet",
                             "--threads", std::to_string(threads)};
  if (r.method == "mpm") {
    v.insert(v.end(), {"--shape", r.shape, "--ppc", std::to_string(r.ppc)});
  }
  return v;
}

// A run whose folder holds a finished summary of this very scene: done,
// not run again when the study is resumed.
bool finished_run(const fs::path& dir, const std::string& scene_hash) {
  try {
    const RunRecord rec = read_run_record(dir.string());
    return rec.finished() && rec.scene_hash == scene_hash;
  } catch (const std::exception&) {
    return false;
  }
}

// The last "runout: " line of a child's log: why it wrote no summary.
std::string log_reason(const fs::path& log) {
  std::ifstream in(log);
  std::string reason;
  for (std::string line; std::getline(in, line);)
    if (line.rfind("runout: ", 0) == 0) reason = line.substr(8);
  return reason;
}

// The row of a run from its summary.json, with its toe runout at the
// study's times from its history.csv; `no_summary` says why when there is
// none.
RunResult read_result(const fs::path& dir, const std::string& scene_hash,
                      const std::vector<double>& times, const std::string& no_summary) {
  RunResult r;
  RunRecord rec;
  try {
    rec = read_run_record(dir.string());
  } catch (const std::exception& e) {
    r.status = "error";
    r.note = no_summary.empty() ? e.what() : no_summary;
    return r;
  }
  if (rec.scene_hash != scene_hash) {
    r.status = "error";
    r.note = "its summary.json is of another scene (hash " + rec.scene_hash + ")";
    return r;
  }
  r.status = rec.status == "blown_up" ? "failed" : rec.finished() ? "ok" : "error";
  r.note = rec.note;
  r.wall = rec.wall_seconds;
  r.peak_mib = rec.peak_memory_mib;
  r.end_time = rec.end_time;
  r.stop_time = rec.stop_time;
  r.particles = rec.particles;
  r.steps = rec.steps;
  r.mechanism = rec.mechanism;
  r.metrics.runout_end = rec.runout;
  r.metrics.peak_toe_velocity = rec.peak_toe_velocity;
  r.metrics.final_length = rec.final_length;
  r.measured = true;
  try {
    const study::History h = study::read_history((dir / "history.csv").string());
    r.metrics.runout_at = study::run_metrics(h, times, rec.status == "at_rest").runout_at;
  } catch (const std::exception& e) {
    r.metrics.runout_at.assign(times.size(), kNaN);
    if (r.note.empty()) r.note = e.what();
  }
  return r;
}

// Runs the combinations `todo` here, at most `jobs` at a time; each
// child's exit, where it wrote no summary, into `why`.
void run_local(const std::vector<std::size_t>& todo, const std::vector<RunSpec>& runs,
               const StudyArgs& a, const fs::path& runs_dir, int jobs,
               std::vector<std::string>& why) {
  std::map<pid_t, std::size_t> running;
  std::size_t next = 0, done = 0;
  // After a stop request no run starts; the running ones get the signal
  // (wait_passing_stop) and stop at a step with a checkpoint to resume.
  const auto launch_more = [&] {
    for (; !stop_requested() && next < todo.size() && static_cast<int>(running.size()) < jobs;
         ++next) {
      const RunSpec& r = runs[todo[next]];
      const fs::path dir = runs_dir / r.id;
      fs::create_directories(dir);
      const pid_t pid = spawn(child_args(r, dir, a.threads), dir / "run.log", true);
      if (pid < 0) throw std::runtime_error("cannot start a run: fork failed");
      running[pid] = todo[next];
    }
  };
  bool passed_on = false;
  for (launch_more(); !running.empty(); launch_more()) {
    std::vector<pid_t> pids;
    for (const auto& entry : running) pids.push_back(entry.first);
    int status = 0;
    const pid_t pid = wait_passing_stop(pids, passed_on, status);
    if (pid < 0) throw std::runtime_error("lost the study's runs: waitpid failed");
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const std::size_t k = it->second;
    running.erase(it);
    const int code = exit_code(status);
    const std::string reason = log_reason(runs_dir / runs[k].id / "run.log");
    why[k] = "exit " + std::to_string(code) + (reason.empty() ? "" : ": " + reason);
    std::fprintf(stderr, "runout study: [%zu/%zu] %s exit %d\n", ++done, todo.size(),
                 runs[k].id.c_str(), code);
  }
}

// The Slurm request for these runs: the largest one's memory (the engine's
// estimate, doubled for what it leaves out, plus the process) and time
// (the cost estimate's steps, doubled as the step falls while the slide
// speeds up, at a tenth of the throughput docs/study.md measures on one
// thread), with a floor for start-up and queueing of the output.
SlurmRequest slurm_request(const std::vector<std::size_t>& todo, const std::vector<RunSpec>& runs,
                           const StudyArgs& a) {
  constexpr double kMiB = 1024.0 * 1024.0, kBaseMiB = 64.0, kMinMinutes = 5.0;
  constexpr double kParticleStepsPerSecond = 2e5;  // per thread
  SlurmRequest req;
  req.cpus = a.threads;
  req.max_resubmits = a.max_resubmits;
  req.sbatch_args = a.sbatch_args;
  req.minutes = kMinMinutes;
  for (std::size_t k : todo) {
    const Scene s = child_scene(runs[k]);
    const MemoryEstimate m = estimate_memory(s, s.method);
    req.memory_mib = std::max(req.memory_mib, kBaseMiB + 2.0 * m.bytes() / kMiB);
    const double seconds = 2.0 * estimate_cost(s, m).steps * m.items /
                           (kParticleStepsPerSecond * a.threads);
    req.minutes = std::max(req.minutes, kMinMinutes + seconds / 60.0);
  }
  return req;
}

// Runs what is not done yet with the study's launcher; `why` gets, per
// run, what to say when it leaves no summary. Returns 0, or 69 when the
// Slurm launcher cannot submit.
int launch(const std::vector<RunSpec>& runs, const StudyArgs& a, const fs::path& dir, int jobs,
           std::vector<std::string>& why) {
  std::vector<std::size_t> todo;
  std::size_t done = 0;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    if (!runs[k].skip.empty()) continue;
    if (finished_run(dir / "runs" / runs[k].id, runs[k].scene_hash))
      ++done;
    else
      todo.push_back(k);
  }
  std::fprintf(stderr, "runout study: %zu runs, %zu done before, %zu to run%s\n", runs.size(),
               done, todo.size(), a.collect.empty() ? "" : " (--collect: none run)");
  if (!a.collect.empty() || todo.empty()) {
    for (std::size_t k : todo) why[k] = "no finished summary.json: not run or not to its end";
    return cli::kOk;
  }
  if (a.launcher == "local") {
    run_local(todo, runs, a, dir / "runs", jobs, why);
    return cli::kOk;
  }
  std::vector<SlurmElement> elements;
  for (std::size_t k : todo) {
    const fs::path run_dir = dir / "runs" / runs[k].id;
    fs::create_directories(run_dir);
    fs::remove(run_dir / kSummaryFile);  // an unfinished run's: not this submission's result
    elements.push_back({child_args(runs[k], run_dir, a.threads), run_dir / "run.log"});
  }
  try {
    const int submissions = run_on_slurm(
        dir, elements, slurm_request(todo, runs, a),
        [&](std::size_t e) { return finished_run(dir / "runs" / runs[todo[e]].id,
                                                  runs[todo[e]].scene_hash); });
    for (std::size_t k : todo)
      why[k] = "no finished summary.json after " + std::to_string(submissions) +
               " submission(s); see " + (dir / "slurm").string();
  } catch (const std::runtime_error& e) {
    std::cerr << "runout study: --launcher slurm: " << e.what() << "\n";
    return cli::kUnavailable;
  }
  return cli::kOk;
}

// The finest successful MPM run to measure row k against: same scene
// point, domain and slope, the same shape where there is one, the CPU
// before CUDA, then the smallest cell and the most particles per cell. -1
// when there is none.
int finest_reference(const std::vector<RunSpec>& runs, const std::vector<RunResult>& res,
                     std::size_t k) {
  int best = -1;
  auto key = [&](std::size_t j) {
    const bool other_shape = !runs[k].shape.empty() ? runs[j].shape != runs[k].shape
                                                    : runs[j].shape != "gimp";
    return std::make_tuple(other_shape, runs[j].backend != "cpu", runs[j].cell, -runs[j].ppc);
  };
  for (std::size_t j = 0; j < runs.size(); ++j) {
    if (runs[j].method != "mpm" || !res[j].measured || res[j].status != "ok") continue;
    if (!runs[j].variant->same_place(*runs[k].variant)) continue;
    if (best < 0 || key(j) < key(best)) best = static_cast<int>(j);
  }
  return best;
}

std::string csv_header(const std::vector<double>& times, const std::vector<std::string>& keys) {
  std::string h = "id,method,backend,shape,cell,ppc,domain_x_max,slope_angle";
  for (const std::string& key : keys) h += "," + key;
  h += ",scene,status,note,particles,steps,end_time,stop_time,mechanism,"
       "wall_s,particle_steps_per_s,peak_memory_mib";
  const auto metric_names = [&](const std::string& prefix) {
    for (double t : times) h += "," + prefix + "runout_t" + format(t);
    h += "," + prefix + "runout_end," + prefix + "peak_toe_velocity," + prefix + "final_length";
  };
  metric_names("");
  metric_names("err_");
  return h + ",pareto,observed_order,reference\n";
}

// A note may hold commas or quotes: quoted as RFC 4180 says.
std::string csv_text(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
  return q + "\"";
}

std::string csv_row(const RunSpec& s, const RunResult& r, const std::vector<double>& errors,
                    bool pareto, double order, const std::string& reference) {
  std::ostringstream o;
  const double rate = r.particles * double(r.steps) / r.wall;
  o << s.id << ',' << s.method << ',' << s.backend << ',' << s.shape << ',' << format(s.cell)
    << ',' << (s.ppc > 0 ? std::to_string(s.ppc) : "") << ',' << format(s.variant->domain_x_max)
    << ',' << (s.variant->slope_angle ? format(*s.variant->slope_angle) : "");
  for (const SceneSetting& setting : s.variant->settings) o << ',' << csv_text(setting.value);
  o << ',' << fs::path(s.variant->file).filename().string() << ',' << r.status << ','
    << csv_text(r.note) << ',' << (r.particles ? std::to_string(r.particles) : "") << ','
    << (r.steps ? std::to_string(r.steps) : "") << ',' << format(r.end_time) << ','
    << format(r.stop_time) << ',' << csv_text(r.mechanism) << ',' << format(r.wall, "%.4g")
    << ',' << (r.steps ? format(rate, "%.4g") : "") << ',' << format(r.peak_mib, "%.4g");
  const study::Metrics& m = r.metrics;
  if (r.measured) {
    for (double v : m.runout_at) o << ',' << format(v);
    o << ',' << format(m.runout_end) << ',' << format(m.peak_toe_velocity) << ','
      << format(m.final_length);
  } else {
    for (std::size_t k = 0; k < errors.size(); ++k) o << ',';
  }
  for (double e : errors) o << ',' << format(e);
  o << ',' << (pareto ? 1 : 0) << ',' << format(order, "%.4g") << ',' << reference << '\n';
  return o.str();
}

// The study's arguments as the command line that gives them back, the
// scene's path absolute: what `--collect DIR` parses again.
std::vector<std::string> args_words(const StudyArgs& a) {
  std::vector<std::string> w;
  if (!a.scene.empty()) w.push_back(fs::absolute(a.scene).string());
  const auto list = [&](const char* option, const auto& values, auto text) {
    if (values.empty()) return;
    std::string joined;
    for (const auto& v : values) joined += (joined.empty() ? "" : ",") + text(v);
    w.insert(w.end(), {option, joined});
  };
  const auto number = [](double v) { return format(v, "%.17g"); };
  const auto word = [](const std::string& v) { return v; };
  list("--cells", a.cells, number);
  list("--ppc", a.ppc, [](int v) { return std::to_string(v); });
  list("--shape", a.shapes, word);
  list("--method", a.methods, word);
  list("--backend", a.backends, word);
  list("--domain-x-max", a.domain_x_max, number);
  list("--slope-angle", a.slope_angles, number);
  list("--times", a.times, number);
  if (a.end) w.insert(w.end(), {"--end", number(*a.end)});
  w.insert(w.end(), {"--reference", a.reference, "--threads", std::to_string(a.threads)});
  for (const std::string& s : a.settings) w.insert(w.end(), {"--set", s});
  for (const std::string& v : a.vary) w.insert(w.end(), {"--vary", v});
  if (a.samples > 0)
    w.insert(w.end(), {"--sample", std::to_string(a.samples), "--seed", std::to_string(a.seed),
                       "--design", a.design});
  return w;
}

// The arguments of the study in `dir`, from its study.args.
StudyArgs collected_args(const std::string& dir) {
  const fs::path path = fs::path(dir) / kArgsFile;
  std::ifstream in(path);
  if (!in) throw std::runtime_error("--collect: no " + path.string() + ": not a study folder");
  std::vector<std::string> words;
  for (std::string line; std::getline(in, line);) words.push_back(line);
  CLI::App app;
  StudyArgs a;
  CLI::App* cmd = nullptr;
  add_study_command(app, a, cmd);
  words.insert(words.begin(), "study");
  std::reverse(words.begin(), words.end());  // CLI11 takes them last first
  app.parse(words);
  a.out = dir;
  a.collect = dir;
  return a;
}

// The study's arguments: those given, or, with --collect DIR, those of the
// study in DIR; nullopt, having said why, where DIR holds none.
std::optional<StudyArgs> study_args(const StudyArgs& given) {
  try {
    return given.collect.empty() ? given : collected_args(given.collect);
  } catch (const std::exception& e) {  // CLI11's parse errors are std::exceptions too
    std::cerr << "runout study: " << e.what() << "\n";
    return std::nullopt;
  }
}

// The study folder made and locked for this process: one study per folder,
// as a second would run the first's runs again and overwrite its
// study.csv. 0, or (having said why) the exit code of a folder that is
// busy or cannot be made.
int lock_study_folder(const fs::path& dir) {
  try {
    fs::create_directories(dir / "runs");
    lock_output_folder(dir.string());
  } catch (const OutputFolderBusy& e) {
    std::cerr << "runout study: " << e.what() << "\n";
    return cli::kFolderBusy;
  } catch (const std::exception& e) {
    std::cerr << "runout study: " << e.what() << "\n";
    return cli::kCantCreate;
  }
  return cli::kOk;
}

// The rows of the study: the runs of its matrix and what each gave.
struct StudyRows {
  std::vector<RunSpec> runs;
  std::vector<RunResult> results;
};

// The study's arguments (unless collected) and its scenes, written beside
// the runs.
void write_inputs(const StudyArgs& a, std::size_t points, std::vector<Variant>& scenes,
                  const fs::path& dir) {
  if (a.collect.empty()) {
    std::string words;
    for (const std::string& w : args_words(a)) words += w + "\n";
    write_file_atomically((dir / kArgsFile).string(), words);
  }
  write_scenes(a, points, scenes, dir);
}

// Each run's result; a skipped run's says why it was skipped.
std::vector<RunResult> read_results(const std::vector<RunSpec>& runs, const fs::path& dir,
                                    const std::vector<double>& times,
                                    const std::vector<std::string>& why) {
  std::vector<RunResult> results(runs.size());
  for (std::size_t k = 0; k < runs.size(); ++k) {
    if (runs[k].skip.empty())
      results[k] = read_result(dir / "runs" / runs[k].id, runs[k].scene_hash, times, why[k]);
    else
      results[k].note = runs[k].skip;
  }
  return results;
}

// Writes the study's inputs into dir, runs what is not done yet and reads
// every run's result into rows. 0, launch's exit code, or 73 (having said
// why) where the folder cannot take them; a scene the study cannot take
// throws SceneError, for main's exit code.
int run_rows(const StudyArgs& a, const StudyParameters& params, std::vector<Variant>& scenes,
             const fs::path& dir, StudyRows& rows) {
  const int cores = std::max(1u, std::thread::hardware_concurrency());
  const int jobs = a.jobs > 0 ? a.jobs : std::max(1, cores / a.threads);
  try {
    write_inputs(a, params.points.size(), scenes, dir);
    rows.runs = expand_matrix(a, params.points.size(), scenes);
    std::vector<std::string> why(rows.runs.size());
    std::fprintf(stderr, "runout study: %d at a time, %d thread(s) each, into %s\n", jobs,
                 a.threads, dir.c_str());
    if (const int code = launch(rows.runs, a, dir, jobs, why); code != 0) return code;
    rows.results = read_results(rows.runs, dir, a.times, why);
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {
    std::cerr << "runout study: " << e.what() << "\n";
    return cli::kCantCreate;
  }
  return cli::kOk;
}

// What the study makes of its rows: each row's errors against its
// reference and the reference's id, whether it is on the Pareto front of
// wall time against the end-runout error over all rows, and the observed
// order of that error in its series (rows that differ only by cell size).
struct RowAnalysis {
  std::vector<std::vector<double>> errors;  // study::metric_errors; NaN: no reference
  std::vector<std::string> reference;       // a run's id or "analytic-block"; empty: none
  std::vector<bool> on_front;
  std::vector<double> order;
};

// Each measured row's reference, the rigid block on its slope or the
// finest MPM run of its place, and its errors against it.
void row_errors(const StudyRows& rows, const std::vector<double>& times, RowAnalysis& out) {
  const std::size_t n = rows.runs.size();
  out.errors.assign(n, std::vector<double>(times.size() + 3, kNaN));
  out.reference.assign(n, "");
  for (std::size_t k = 0; k < n; ++k) {
    const RunResult& r = rows.results[k];
    if (!r.measured) continue;
    if (const std::optional<study::RigidBlock>& block = rows.runs[k].variant->block) {
      out.reference[k] = "analytic-block";
      out.errors[k] = study::metric_errors(
          r.metrics, study::rigid_block_metrics(*block, times, r.end_time));
    } else if (const int j = finest_reference(rows.runs, rows.results, k); j >= 0) {
      out.reference[k] = rows.runs[j].id;
      out.errors[k] = study::metric_errors(r.metrics, rows.results[j].metrics);
    }
  }
}

// Whether row k takes part in the front and the orders: a run that ended
// well, measured against another. A finest run is its own reference, with
// no error to show.
bool compared(const StudyRows& rows, const RowAnalysis& a, std::size_t k) {
  return rows.results[k].status == "ok" && a.reference[k] != rows.runs[k].id;
}

// The end-runout error of each row that is compared; NaN for the others.
std::vector<double> end_runout_errors(const StudyRows& rows, const RowAnalysis& a,
                                      std::size_t end_error) {
  std::vector<double> error(rows.runs.size(), kNaN);
  for (std::size_t k = 0; k < error.size(); ++k)
    if (compared(rows, a, k)) error[k] = a.errors[k][end_error];
  return error;
}

// The rows on the Pareto front of wall time against `error`.
std::vector<bool> pareto_rows(const StudyRows& rows, const RowAnalysis& a,
                              const std::vector<double>& error) {
  std::vector<double> cost(rows.runs.size(), kNaN);
  for (std::size_t k = 0; k < cost.size(); ++k)
    if (compared(rows, a, k)) cost[k] = rows.results[k].wall;
  std::vector<bool> on_front(cost.size(), false);
  for (int k : study::pareto_front(cost, error)) on_front[k] = true;
  return on_front;
}

// The observed order of `error` in each row's series: the rows that differ
// from it only by cell size.
std::vector<double> observed_orders(const std::vector<RunSpec>& runs,
                                    const std::vector<double>& error) {
  const auto series = [&](std::size_t k) {
    return std::make_tuple(runs[k].method, runs[k].backend, runs[k].shape, runs[k].ppc,
                           runs[k].variant->point, runs[k].variant->domain_x_max,
                           runs[k].variant->slope_angle);
  };
  std::vector<double> order(runs.size(), kNaN);
  for (std::size_t k = 0; k < runs.size(); ++k) {
    std::vector<double> h, e;
    for (std::size_t j = 0; j < runs.size(); ++j)
      if (series(j) == series(k)) {
        h.push_back(runs[j].cell);
        e.push_back(error[j]);
      }
    order[k] = study::observed_order(h, e);
  }
  return order;
}

RowAnalysis analyse_rows(const StudyRows& rows, const std::vector<double>& times) {
  RowAnalysis a;
  row_errors(rows, times, a);
  const std::vector<double> error = end_runout_errors(rows, a, times.size());
  a.on_front = pareto_rows(rows, a, error);
  a.order = observed_orders(rows.runs, error);
  return a;
}

// study.csv: its header and a row per run.
std::string study_csv(const std::vector<double>& times, const std::vector<std::string>& keys,
                      const StudyRows& rows, const RowAnalysis& a) {
  std::string csv = csv_header(times, keys);
  for (std::size_t k = 0; k < rows.runs.size(); ++k)
    csv += csv_row(rows.runs[k], rows.results[k], a.errors[k], a.on_front[k], a.order[k],
                   a.reference[k]);
  return csv;
}

// Writes study.csv into dir and names it; false, having said why, where it
// cannot be written.
bool write_study_csv(const fs::path& dir, const std::string& csv, std::size_t rows) {
  const std::string csv_path = (dir / "study.csv").string();
  try {
    write_file_atomically(csv_path, csv);
  } catch (const std::exception& e) {
    std::cerr << "runout study: " << e.what() << "\n";
    return false;
  }
  std::printf("study: %s (%zu rows)\n", csv_path.c_str(), rows);
  return true;
}

// Names each row that did not end well; the study's exit code: as `runout
// run` where a stop request ended it, 70 where a run failed.
int study_exit(const StudyRows& rows) {
  bool all_ran = true;
  for (std::size_t k = 0; k < rows.runs.size(); ++k) {
    const RunResult& r = rows.results[k];
    all_ran = all_ran && (r.status == "ok" || r.status == "skipped");
    if (r.status != "ok")
      std::printf("  %s: %s: %s\n", rows.runs[k].id.c_str(), r.status.c_str(), r.note.c_str());
  }
  if (const int signal = stop_requested()) return cli::kSignalBase + signal;
  return all_ran ? cli::kOk : cli::kBlowUp;
}

}  // namespace

void add_study_command(CLI::App& app, StudyArgs& a, CLI::App*& cmd) {
  cmd = app.add_subcommand("study",
                           "Run a matrix of scene settings or samples, resolutions and methods, "
                           "here or on Slurm; one CSV row per run with its result, its cost and "
                           "its error against the finest run or the analytic answer");
  cmd->add_option("scene", a.scene, "Scene file (TOML); the built-in default scene if omitted");
  cmd->add_option("--cells", a.cells, "Cell sizes h [m]")
      ->delimiter(',')
      ->check(cli::finite_positive());
  cmd->add_option("--ppc", a.ppc, "Particles per cell per direction")->delimiter(',');
  cmd->add_option("--shape", a.shapes, "Shape functions: gimp, linear")
      ->delimiter(',')->check(CLI::IsMember({"gimp", "linear"}));
  cmd->add_option("--method", a.methods, "Methods: mpm, dam")
      ->delimiter(',')->check(CLI::IsMember({"mpm", "dam"}));
  cmd->add_option("--backend", a.backends, "Backends: cpu, cuda")
      ->delimiter(',')->check(CLI::IsMember({"cpu", "cuda"}));
  cmd->add_option("--domain-x-max", a.domain_x_max,
                  "Far ends of the domain along x [m]: the same slide on longer paths")
      ->delimiter(',')
      ->check(cli::finite_positive());
  cmd->add_option("--slope-angle", a.slope_angles,
                  "Slope angles [deg] of a planar-slope scene: the same slide on steeper bases")
      ->delimiter(',');
  cmd->add_option("--times", a.times, "Report the toe runout at these times [s]")
      ->delimiter(',')->check(cli::finite_non_negative());
  cmd->add_option("--end", a.end, "Override the end time [s]");
  cmd->add_option("--reference", a.reference,
                  "finest (the finest MPM run) or analytic-block (a rigid block on the base)")
      ->check(CLI::IsMember({"finest", "analytic-block"}));
  cmd->add_option("--set", a.settings,
                  "KEY=V1,V2,...: a scene key by its table path (material.clay.su0), one run "
                  "per value, crossed with the other keys (repeatable)");
  cmd->add_option("--vary", a.vary,
                  "KEY=DIST: draw the key from uniform(lo,hi), normal(mean,sd[,lo,hi]) or "
                  "lognormal(median,sigma[,lo,hi]) (repeatable; with --sample)");
  cmd->add_option("--sample", a.samples, "Samples of the --vary keys")
      ->check(cli::whole_number_from(1));
  cmd->add_option("--seed", a.seed, "Seed of the samples");
  cmd->add_option("--design", a.design, "lhs (Latin hypercube) or mc (Monte Carlo)")
      ->check(CLI::IsMember({"lhs", "mc"}));
  cmd->add_option("--launcher", a.launcher, "local (here, --jobs at once) or slurm (a job array)")
      ->check(CLI::IsMember({"local", "slurm"}));
  cmd->add_option("--max-resubmits", a.max_resubmits,
                  "Slurm: submit unfinished elements again at most this many times")
      ->check(cli::whole_number_from(0));
  cmd->add_option("--sbatch-arg", a.sbatch_args,
                  "Slurm: an argument for sbatch, e.g. --sbatch-arg=--partition=long (repeatable)");
  cmd->add_option("--collect", a.collect,
                  "The CSV of the study in DIR from its runs' summaries; nothing is run");
  cmd->add_option("-o,--out", a.out, "Study folder (default out/study/<scene name>)")
      ->check(cli::non_empty_folder());
  cmd->add_option("-j,--jobs", a.jobs, "Runs at once (default: cores / threads)")
      ->check(cli::whole_number_from(1));
  cmd->add_option("-t,--threads", a.threads, "OpenMP threads per run")
      ->check(cli::whole_number_from(1));
}

int run_study(const StudyArgs& given) {
  const std::optional<StudyArgs> args = study_args(given);
  if (!args) return cli::kNoScene;
  const StudyArgs& a = *args;
  const SceneSource base = cli::scene_source(a.scene);
  parse_scene(base.text, base.name);  // the scene's own refusals before the settings'
  const StudyParameters params =
      study_parameters(a.settings, a.vary, a.samples, a.seed, a.design);
  require_study_size(matrix_runs(a, params.points.size()),
                     "the matrix (scene points x domains x slopes x methods x backends x cells "
                     "x shapes x ppc)");
  // Every point's scene parsed before anything is written or run.
  std::vector<Variant> scenes = variants(a, base, params);

  const fs::path dir = a.out.empty() ? fs::path("out/study") / scenes[0].scene.name : fs::path(a.out);
  if (const int code = lock_study_folder(dir); code != cli::kOk) return code;
  const AdoptedFolderLock lock(dir.string());
  StudyRows rows;
  if (const int code = run_rows(a, params, scenes, dir, rows); code != cli::kOk) return code;
  const RowAnalysis analysis = analyse_rows(rows, a.times);
  if (!write_study_csv(dir, study_csv(a.times, params.keys, rows, analysis), rows.runs.size()))
    return cli::kCantCreate;
  return study_exit(rows);
}

}  // namespace runout
