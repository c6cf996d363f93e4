#include "study_command.hpp"

#include <sys/resource.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <map>
#include <regex>
#include <sstream>
#include <thread>

#include "runout/atomic_file.hpp"
#include "runout/device_info.hpp"
#include "runout/scene_parser.hpp"
#include "runout/study.hpp"

namespace runout {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// One scene of the study: the domain's far end and the slope angle
// (--domain-x-max, --slope-angle), and the study's copy of it that the
// children read.
struct Variant {
  Scene scene;
  std::string file;
  double domain_x_max = 0;
  std::optional<double> slope_angle;  // empty: the scene's own gravity
  std::optional<study::RigidBlock> block;  // --reference analytic-block: on this slope

  // The runs of one variant are measured against each other.
  bool same_place(const Variant& o) const {
    return domain_x_max == o.domain_x_max && slope_angle == o.slope_angle;
  }
};

// One combination of the matrix.
struct RunSpec {
  std::string id, method, backend, shape;  // shape empty for the depth-averaged model
  double cell = 0;
  int ppc = 0;                             // 0 for the depth-averaged model
  const Variant* variant = nullptr;
  std::string skip;                        // why it is not run; empty: it runs
};

// What a finished child left: its exit, its cost, and what its log says.
struct RunResult {
  std::string status = "skipped", note;
  double wall = kNaN, peak_mib = kNaN, end_time = kNaN;
  long particles = 0, steps = 0;
  bool at_rest = false;
  study::Metrics metrics;
  bool measured = false;  // history.csv read
};

std::string format(double v, const char* fmt = "%.6g") {
  if (!std::isfinite(v)) return "";
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

// What tells a variant's runs and files apart: "_x<far end>" when the
// study has several domains, "_a<angle>" when it sets the slope.
std::string variant_suffix(const StudyArgs& a, const Variant& v) {
  std::string suffix;
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

// The scene as the study runs it (--end applied), once per far end of the
// domain and slope angle, with its rigid block when that is the reference.
// Throws SceneError for a slope or a reference the scene cannot take,
// before anything is written.
std::vector<Variant> variants(const StudyArgs& a, const Scene& base) {
  std::vector<double> ends = a.domain_x_max;
  if (ends.empty()) ends.push_back(base.grid.max.x());
  std::vector<std::optional<double>> angles(a.slope_angles.begin(), a.slope_angles.end());
  if (angles.empty()) angles.emplace_back();
  std::vector<Variant> out;
  for (double x : ends)
    for (const std::optional<double>& angle : angles) {
      Variant v{base, "", x, angle, std::nullopt};
      v.scene.grid.max.x() = x;
      if (angle) study::set_slope_angle(v.scene, *angle);
      if (a.reference == "analytic-block") v.block = study::rigid_block(v.scene);
      out.push_back(std::move(v));
    }
  return out;
}

// Each variant's scene written beside the runs, so that every child reads
// the same file.
void write_scenes(const StudyArgs& a, std::vector<Variant>& variants, const fs::path& dir) {
  for (Variant& v : variants) {
    v.file = (dir / ("scene" + variant_suffix(a, v) + ".toml")).string();
    write_file_atomically(v.file, to_toml(v.scene));
  }
}

std::vector<RunSpec> expand_matrix(const StudyArgs& a, const std::vector<Variant>& variants) {
  std::string no_cuda;
  const bool cuda = !cuda_devices(no_cuda).empty();
  std::vector<RunSpec> runs;
  for (const Variant& v : variants)
    for (const std::string& method : a.methods)
      for (const std::string& backend : a.backends)
        for (double cell : a.cells) {
          RunSpec r{"", method, backend, "", cell, 0, &v, ""};
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
  for (RunSpec& r : runs) r.id = run_id(r, variant_suffix(a, *r.variant));
  return runs;
}

std::vector<std::string> child_args(const RunSpec& r, const fs::path& run_dir, int threads) {
  std::vector<std::string> v{"runout", "run", r.variant->file, "--method", r.method,
                             "--backend", r.backend, "--cell", format(r.cell, "%.17g"),
                             "--out", run_dir.string(), "--quiet",
                             "--threads", std::to_string(threads)};
  if (r.method == "mpm") {
    v.insert(v.end(), {"--shape", r.shape, "--ppc", std::to_string(r.ppc)});
  }
  return v;
}

// fork + exec of this same binary, its output into run.log.
pid_t spawn(const std::vector<std::string>& args, const fs::path& log) {
  std::vector<char*> argv;
  for (const std::string& s : args) argv.push_back(const_cast<char*>(s.c_str()));
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid != 0) return pid;
  const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd >= 0) {
    dup2(fd, STDOUT_FILENO);
    dup2(fd, STDERR_FILENO);
  }
  execv("/proc/self/exe", argv.data());
  std::perror("runout study: exec");
  _exit(127);
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The child's summary line ("N particles, S steps to t = T s", or
// "N elements, ..." for the depth-averaged model), whether it came to
// rest, and its last "runout:" message when it did not finish.
void read_log(const std::string& log, RunResult& r) {
  static const std::regex summary(R"((\d+) (?:particles|elements), (\d+) steps to t = (\S+) s)");
  std::smatch m;
  if (std::regex_search(log, m, summary)) {
    r.particles = std::stol(m[1]);
    r.steps = std::stol(m[2]);
    r.end_time = std::stod(m[3]);
  }
  r.at_rest = log.find("came to rest") != std::string::npos;
  std::istringstream in(log);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("runout: ", 0) == 0 && r.note.empty()) r.note = line.substr(8);
}

RunResult finish(const fs::path& dir, int status, const rusage& usage,
                 double wall, const std::vector<double>& times) {
  RunResult r;
  r.wall = wall;
  r.peak_mib = usage.ru_maxrss / 1024.0;  // Linux: ru_maxrss in KiB
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.status = code == 0 ? "ok" : code == 70 ? "failed" : "error";
  read_log(read_text(dir / "run.log"), r);
  if (code != 0 && r.note.empty()) r.note = "exit " + std::to_string(code);
  try {
    const study::History h = study::read_history((dir / "history.csv").string());
    r.metrics = study::run_metrics(h, times, r.at_rest);
    r.measured = !h.time.empty();
    if (r.measured && !std::isfinite(r.end_time)) r.end_time = h.time.back();
  } catch (const std::exception& e) {
    if (r.note.empty()) r.note = e.what();
  }
  return r;
}

// Runs every combination that applies, at most `jobs` at a time, and reaps
// each child with wait4 so its peak resident memory is its own.
std::vector<RunResult> run_all(const std::vector<RunSpec>& runs, const StudyArgs& a,
                               const fs::path& runs_dir, int jobs) {
  std::vector<RunResult> results(runs.size());
  struct Running {
    std::size_t index;
    Clock::time_point start;
  };
  std::map<pid_t, Running> running;
  std::size_t next = 0, done = 0, total = 0;
  for (const RunSpec& r : runs) total += r.skip.empty();
  const auto launch_more = [&] {
    for (; next < runs.size() && static_cast<int>(running.size()) < jobs; ++next) {
      if (!runs[next].skip.empty()) continue;
      const fs::path dir = runs_dir / runs[next].id;
      fs::create_directories(dir);
      const pid_t pid = spawn(child_args(runs[next], dir, a.threads), dir / "run.log");
      if (pid < 0) throw std::runtime_error("cannot start a run: fork failed");
      running[pid] = {next, Clock::now()};
    }
  };
  for (launch_more(); !running.empty(); launch_more()) {
    int status = 0;
    rusage usage{};
    const pid_t pid = wait4(-1, &status, 0, &usage);
    if (pid < 0) throw std::runtime_error("lost the study's runs: wait4 failed");
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const std::size_t k = it->second.index;
    const double wall = std::chrono::duration<double>(Clock::now() - it->second.start).count();
    results[k] = finish(runs_dir / runs[k].id, status, usage, wall, a.times);
    running.erase(it);
    std::fprintf(stderr, "runout study: [%zu/%zu] %s %s (%.3g s)\n", ++done, total,
                 runs[k].id.c_str(), results[k].status.c_str(), wall);
  }
  for (std::size_t k = 0; k < runs.size(); ++k)
    if (!runs[k].skip.empty()) results[k].note = runs[k].skip;
  return results;
}

// The finest successful MPM run to measure row k against: same domain and
// slope, the same shape where there is one, the CPU before CUDA, then the
// smallest cell and the most particles per cell. -1 when there is none.
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

std::string csv_header(const std::vector<double>& times) {
  std::string h =
      "id,method,backend,shape,cell,ppc,domain_x_max,slope_angle,status,note,particles,steps,end_time,"
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
    << ',' << (s.variant->slope_angle ? format(*s.variant->slope_angle) : "") << ',' << r.status << ',' << csv_text(r.note) << ',' << (r.particles ? std::to_string(r.particles) : "")
    << ',' << (r.steps ? std::to_string(r.steps) : "") << ',' << format(r.end_time) << ','
    << format(r.wall, "%.4g") << ',' << (r.steps ? format(rate, "%.4g") : "") << ','
    << format(r.peak_mib, "%.4g");
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

}  // namespace

void add_study_command(CLI::App& app, StudyArgs& a, CLI::App*& cmd) {
  cmd = app.add_subcommand("study",
                           "Run a matrix of resolutions and methods; one CSV row per run with its "
                           "cost and its error against the finest run or the analytic answer");
  cmd->add_option("scene", a.scene, "Scene file (TOML); the built-in default scene if omitted");
  cmd->add_option("--cells", a.cells, "Cell sizes h [m]")->delimiter(',')->check(CLI::PositiveNumber);
  cmd->add_option("--ppc", a.ppc, "Particles per cell per direction")->delimiter(',');
  cmd->add_option("--shape", a.shapes, "Shape functions: gimp, linear")
      ->delimiter(',')->check(CLI::IsMember({"gimp", "linear"}));
  cmd->add_option("--method", a.methods, "Methods: mpm, dam")
      ->delimiter(',')->check(CLI::IsMember({"mpm", "dam"}));
  cmd->add_option("--backend", a.backends, "Backends: cpu, cuda")
      ->delimiter(',')->check(CLI::IsMember({"cpu", "cuda"}));
  cmd->add_option("--domain-x-max", a.domain_x_max,
                  "Far ends of the domain along x [m]: the same slide on longer paths")
      ->delimiter(',');
  cmd->add_option("--slope-angle", a.slope_angles,
                  "Slope angles [deg] of a planar-slope scene: the same slide on steeper bases")
      ->delimiter(',');
  cmd->add_option("--times", a.times, "Report the toe runout at these times [s]")
      ->delimiter(',')->check(CLI::NonNegativeNumber);
  cmd->add_option("--end", a.end, "Override the end time [s]");
  cmd->add_option("--reference", a.reference,
                  "finest (the finest MPM run) or analytic-block (a rigid block on the base)")
      ->check(CLI::IsMember({"finest", "analytic-block"}));
  cmd->add_option("-o,--out", a.out, "Study folder (default out/study/<scene name>)");
  cmd->add_option("-j,--jobs", a.jobs, "Runs at once (default: cores / threads)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("-t,--threads", a.threads, "OpenMP threads per run")->check(CLI::PositiveNumber);
}

int run_study(const StudyArgs& a) {
  Scene scene = a.scene.empty() ? parse_scene(default_scene_toml(), "default.toml")
                                : load_scene_file(a.scene);
  apply_overrides(scene, std::nullopt, std::nullopt, a.end);

  const fs::path dir = a.out.empty() ? fs::path("out/study") / scene.name : fs::path(a.out);
  const int cores = std::max(1u, std::thread::hardware_concurrency());
  const int jobs = a.jobs > 0 ? a.jobs : std::max(1, cores / a.threads);
  std::vector<Variant> scenes = variants(a, scene);
  std::vector<RunSpec> runs;
  std::vector<RunResult> results;
  try {
    fs::create_directories(dir / "runs");
    write_scenes(a, scenes, dir);
    runs = expand_matrix(a, scenes);
    std::fprintf(stderr, "runout study: %zu runs, %d at a time, %d thread(s) each, into %s\n",
                 runs.size(), jobs, a.threads, dir.c_str());
    results = run_all(runs, a, dir / "runs", jobs);
  } catch (const std::exception& e) {
    std::cerr << "runout study: " << e.what() << "\n";
    return 73;
  }

  // Each row's errors and reference, then the Pareto front of wall time
  // against the end-runout error over all rows, and the observed order of
  // that error per series (rows that differ only by cell size). A finest
  // run is its own reference, with no error to show: it takes no part.
  const std::size_t n = runs.size(), end_error = a.times.size();
  std::vector<std::vector<double>> errors(n, std::vector<double>(a.times.size() + 3, kNaN));
  std::vector<std::string> reference(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (!results[k].measured) continue;
    if (const std::optional<study::RigidBlock>& block = runs[k].variant->block) {
      reference[k] = "analytic-block";
      errors[k] = study::metric_errors(
          results[k].metrics, study::rigid_block_metrics(*block, a.times, results[k].end_time));
    } else if (const int j = finest_reference(runs, results, k); j >= 0) {
      reference[k] = runs[j].id;
      errors[k] = study::metric_errors(results[k].metrics, results[j].metrics);
    }
  }
  std::vector<double> cost(n, kNaN), error(n, kNaN);
  for (std::size_t k = 0; k < n; ++k)
    if (results[k].status == "ok" && reference[k] != runs[k].id) {
      cost[k] = results[k].wall;
      error[k] = errors[k][end_error];
    }
  std::vector<bool> on_front(n, false);
  for (int k : study::pareto_front(cost, error)) on_front[k] = true;
  std::vector<double> order(n, kNaN);
  const auto series = [&](std::size_t k) {
    return std::make_tuple(runs[k].method, runs[k].backend, runs[k].shape, runs[k].ppc,
                           runs[k].variant->domain_x_max, runs[k].variant->slope_angle);
  };
  for (std::size_t k = 0; k < n; ++k) {
    std::vector<double> h, e;
    for (std::size_t j = 0; j < n; ++j)
      if (series(j) == series(k)) {
        h.push_back(runs[j].cell);
        e.push_back(error[j]);
      }
    order[k] = study::observed_order(h, e);
  }

  std::string csv = csv_header(a.times);
  bool all_ran = true;
  for (std::size_t k = 0; k < n; ++k) {
    all_ran = all_ran && (results[k].status == "ok" || results[k].status == "skipped");
    csv += csv_row(runs[k], results[k], errors[k], on_front[k], order[k], reference[k]);
  }
  const std::string csv_path = (dir / "study.csv").string();
  try {
    write_file_atomically(csv_path, csv);
  } catch (const std::exception& e) {
    std::cerr << "runout study: " << e.what() << "\n";
    return 73;
  }
  std::printf("study: %s (%zu rows)\n", csv_path.c_str(), runs.size());
  for (std::size_t k = 0; k < runs.size(); ++k)
    if (results[k].status != "ok")
      std::printf("  %s: %s: %s\n", runs[k].id.c_str(), results[k].status.c_str(),
                  results[k].note.c_str());
  return all_ran ? 0 : 70;
}

}  // namespace runout
