// runout: the command line. Exit codes: exit_codes.hpp. `resume`: 66 no
// checkpoint in the folder, 65 one that is corrupt, of another version or
// of another run, 79 a folder that does not go with its checkpoint (a kept
// frame changed, history.csv too short), left as it was. A run stopped by
// SIGINT, SIGTERM or SIGHUP exits 128 + the signal's number (130, 143, 129),
// as a shell reports a process the signal killed.
#include <omp.h>
#include <signal.h>
#include <sys/resource.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "analyse_command.hpp"
#include "report_command.hpp"
#include "budget_check.hpp"
#include "exit_codes.hpp"
#include "option_checks.hpp"
#include "openmp_wait.hpp"
#include "progress.hpp"
#include "scene_loading.hpp"
#include "pvd_indexes.hpp"
#include "thread_count.hpp"
#include "study_command.hpp"
#include "runout/analysis/final_mechanism.hpp"
#include "runout/output/checkpoint.hpp"
#include "runout/run/device_info.hpp"
#include "runout/scene/materials.hpp"
#include "runout/run/memory_estimate.hpp"
#include "runout/output/atomic_file.hpp"
#include "runout/run/run.hpp"
#include "runout/run/run_control.hpp"
#include "runout/output/run_summary_file.hpp"
#include "runout/scene/scene_parser.hpp"
#include "runout/study/study.hpp"
#include "runout/mpm/nonlocal.hpp"
#include "runout/mpm/seeding.hpp"
#include "runout/mpm/simulation.hpp"
#include "runout/output/vtu_writer.hpp"
#ifdef RUNOUT_HAVE_CUDA
#include "runout/mpm/cuda_simulation.hpp"
#endif

namespace {

using namespace runout;

void on_stop_signal(int signal) { request_stop(signal); }

// The first SIGINT, SIGTERM or SIGHUP asks the run to stop at the next step
// and checkpoint (a study: passes it on to its runs); SA_RESETHAND lets a
// second one kill it at once.
void stop_on_signals() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND | SA_RESTART;
  for (const int signal : {SIGINT, SIGTERM, SIGHUP}) sigaction(signal, &action, nullptr);
}

// A run the stop request ended: what is kept and how to go on; the exit code.
int report_stop(const RunSummary& r, const RunOptions& opt, int signal) {
  std::cerr << "runout: stopped by SIG" << sigabbrev_np(signal) << " at t = " << r.end_time
            << " s; the " << r.frames << " frames written are kept in " << opt.out_dir << "\n";
  if (!r.checkpoint_path.empty())
    std::cerr << "runout: continue with: runout resume " << opt.out_dir << "\n";
  return cli::kSignalBase + signal;
}

struct SceneArgs {
  std::string path;  // empty: the built-in default scene
  cli::SceneOverrides overrides;
};

void add_scene_args(CLI::App* cmd, SceneArgs& a) {
  cli::SceneOverrides& o = a.overrides;
  cmd->add_option("scene", a.path, "Scene file (TOML); the built-in default scene if omitted");
  cmd->add_option("--cell", o.cell, "Override the cell size h [m]");
  cmd->add_option("--ppc", o.ppc, "Override the particles per cell per direction");
  cmd->add_option("--end", o.end, "Override the end time [s]");
  cmd->add_option("--method", o.method, "Override the method: mpm or dam (depth-averaged)");
  cmd->add_option("--shape", o.shape, "Override the MPM shape functions: gimp or linear");
  cmd->add_option("--shear-rate", o.shear_rate,
                  "Override the depth-averaged shear rate estimate: band (the default where the "
                  "slide's clay has band_thickness), linear or plug");
  cmd->add_option("--elements", o.elements,
                  "Override the depth-averaged element count (0: length / cell size)");
}

// The scene of the command line, and its text for the line of a key in a
// refusal after the parse.
struct LoadedScene {
  SceneSource source;
  Scene scene;
};

LoadedScene load(const SceneArgs& a) {
  SceneSource source = cli::scene_source(a.path);
  Scene scene = cli::load_scene(source, a.overrides);
  return {std::move(source), std::move(scene)};
}

// A step count as an integer while it is one, so that a scene far beyond
// any limit prints its count instead of an overflowed integer.
std::string step_count_text(double steps) {
  char buf[32];
  if (std::isfinite(steps) && steps < 1e15)
    std::snprintf(buf, sizeof buf, "%.0f", std::ceil(steps));
  else
    std::snprintf(buf, sizeof buf, "%.3g", steps);
  return buf;
}

// --max-steps and --max-output (GiB) of run, check and resume (with --end).
struct LimitArgs {
  double max_steps = CostLimits{}.max_steps;
  double max_output_gib = CostLimits{}.max_output_bytes / double(1 << 30);
};

void add_limit_args(CLI::App* cmd, LimitArgs& a) {
  cmd->add_option("--max-steps", a.max_steps,
                  "Refuse a run that needs more steps than this (estimated from the initial "
                  "Courant step)")
      ->capture_default_str()
      ->check(cli::finite_positive());
  cmd->add_option("--max-output", a.max_output_gib,
                  "Refuse a run whose frames, uncompressed, would exceed this many GiB")
      ->capture_default_str()
      ->check(cli::finite_positive());
}

// --threads, --quiet and --backend of run and resume.
struct RunArgs {
  int threads = 0;  // 0: by the scene's size (cli::use_default_threads)
  bool quiet = false;
  std::string backend = "cpu";
};

void add_run_args(CLI::App* cmd, RunArgs& a) {
  cmd->add_option("-t,--threads", a.threads,
                  "OpenMP threads (default: by the scene's size, at most all cores, then on the "
                  "CPU as many of those as its steps run fastest on; OMP_NUM_THREADS if set)")
      ->check(cli::whole_number_from(1));
  cmd->add_flag("-q,--quiet", a.quiet, "No progress output");
  cmd->add_option("--backend", a.backend, "cpu (OpenMP) or cuda (MPM on an NVIDIA GPU)")
      ->check(CLI::IsMember({"cpu", "cuda"}));
}

// The limits; a run is bounded by the free disk of its output folder too.
CostLimits limits_for(const LimitArgs& a, const std::string* out_dir) {
  CostLimits limits;
  limits.max_steps = a.max_steps;
  limits.max_output_bytes = a.max_output_gib * double(1 << 30);
  if (!out_dir) return limits;
  const std::optional<double> free = free_disk_bytes(*out_dir);
  if (free && *free < limits.max_output_bytes) {
    limits.max_output_bytes = *free;
    limits.output_limit_is = "the space free on the disk of " + *out_dir;
    limits.output_remedy = "free space on that disk, or write to another with --out";
  }
  return limits;
}

// A band's displacement is measured over l (nonlocal_length), which must be
// wide against the band the grid makes, a cell or two: a band as wide as l
// counts as diffuse yield and softens by its own strain, as the local law
// does, with the cell (docs/strength.md, "The averaging length"). One line
// per material whose l spans fewer than kRegularisationCells cells.
std::vector<std::string> coarse_averaging(const Scene& s) {
  std::vector<std::string> lines;
  if (s.method != Method::Mpm) return lines;
  const double h = s.grid.cell_size;
  for (const auto& m : s.materials) {
    const double l = m.nonlocal_length;
    if (m.band_thickness <= 0.0 || l <= 0.0 || l >= kRegularisationCells * h * (1.0 - 1e-9))
      continue;
    char text[400];
    std::snprintf(text, sizeof text,
                  "material '%s': nonlocal_length = %g m spans %.3g cells of %g m, under the %g "
                  "that measure a band's displacement; its bands soften as the local law's, "
                  "with the cell: use cells of %.3g m or less (docs/strength.md, \"The averaging "
                  "length\")",
                  m.name.c_str(), l, l / h, h, kRegularisationCells, l / kRegularisationCells);
    lines.emplace_back(text);
  }
  return lines;
}

// Wall time of the check's own measurement of the step.
constexpr double kWallEstimateSeconds = 0.1;

int check(const Scene& s, const SceneSource& source, const LimitArgs& limit_args) {
  // The more basic refusal comes first.
  const MemoryEstimate memory = require_memory(s, s.method, source);
  require_cost(s, s.method, memory, limits_for(limit_args, nullptr), source);
  // The threads a run of the scene would use, for the wall-time estimate.
  cli::use_default_threads(memory.items);
  const RunCost cost = estimate_cost(s, memory);
  // Seeded without estimating again: the estimate above is the MPM's own
  // where the scene runs the MPM.
  Simulation sim(s, seed_particles(s, s.method == Method::Mpm
                                          ? std::optional<MemoryEstimate>(memory)
                                          : std::nullopt));
  const double dt = sim.stable_dt();
  const int n = sim.particles().size();
  const double h = s.grid.cell_size;
  const long cells = std::lround((s.grid.max.x() - s.grid.min.x()) / h) *
                     std::lround((s.grid.max.y() - s.grid.min.y()) / h);
  const std::optional<double> available = available_memory();
  std::cout << to_toml(s) << "\n# particles:        " << n << "\n# domain cells:     " << cells
            << "\n# initial dt:       " << dt << " s (Courant " << s.time.courant << ")"
            << "\n# steps (about):    " << step_count_text(s.time.end / dt)
            << " (dt falls as the slide speeds up)"
            << "\n# frames:           " << step_count_text(cost.frames) << ", about "
            << byte_text(cost.output_bytes) << " uncompressed"
            << "\n# memory (about):   " << byte_text(memory.bytes()) << " ("
            << byte_text(memory.item_bytes) << " per "
            << (s.method == Method::Dam ? "element" : "particle") << ", "
            << byte_text(memory.node_bytes) << " per grid node), "
            << (available ? byte_text(*available) : std::string("unknown")) << " available\n";
  if (s.method == Method::Dam) return cli::kOk;
  // On a base that holds its nodes, a softening clay's basal layer crowds
  // with fewer than 4 x 4 particles per cell, and its slide stops short
  // (docs/validation.md, case 4); the clay's band at the base does not
  // (docs/strength.md, "The basal band").
  const double sensitivity = study::slide_size(s).sensitivity;  // its bodies' largest St
  if (sensitivity > 1.0 && s.grid.ppc < 4 && !s.base.clay_band) {
    std::cout << "# particles/cell:   " << s.grid.ppc << " x " << s.grid.ppc
              << ": a softening clay (St = " << sensitivity
              << ") crowds its basal layer with fewer than 4 x 4 and stops short "
                 "(docs/validation.md: case 4 converges with 4 x 4 or more); "
                 "[base] clay_band = true puts its band at the base instead "
                 "(docs/strength.md, \"The basal band\")\n";
  }
  for (const std::string& line : coarse_averaging(s)) std::cout << "# averaging length: " << line << "\n";
  // Measured on the scene itself, so "on this machine" and at its size.
  try {
    const double per_step = seconds_per_step(sim, kWallEstimateSeconds);
    char ms[32];
    std::snprintf(ms, sizeof ms, "%.3g", per_step * 1e3);
    std::cout << "# wall (about):     " << clock_text(per_step * (s.time.end / dt)) << " on "
              << omp_get_max_threads() << " thread(s) here (" << ms
              << " ms per step, measured)\n";
  } catch (const NumericalFailure& e) {
    std::cout << "# wall (about):     not measured, the first steps failed: " << e.what() << "\n";
  }
  return cli::kOk;
}

using Runner = RunSummary (*)(const Scene&, const RunOptions&);
using Resumer = RunSummary (*)(const RunOptions&);

// The MPM run and resume on the chosen backend, or nulls with the reason
// when that backend cannot run here.
struct MpmBackend {
  Runner run = nullptr;
  Resumer resume = nullptr;
};
MpmBackend mpm_backend(const std::string& backend, std::string& why_not) {
  if (backend == "cpu") return {run_scene, resume_scene};
#ifdef RUNOUT_HAVE_CUDA
  if (cuda_device_available(why_not)) return {run_scene_cuda, resume_scene_cuda};
#else
  why_not = "this build has no CUDA";
#endif
  return {};
}

// The run of the scene's method on the chosen backend, or null with the
// reason when that backend cannot run here.
Runner runner_for(const Scene& s, const std::string& backend, std::string& why_not) {
  if (s.method != Method::Dam) return mpm_backend(backend, why_not).run;
  if (backend == "cpu") return run_dam;
  why_not = "the depth-averaged model runs on the CPU only";
  return nullptr;
}

// summary.json of the run that just ended, with this process's peak
// memory and the mechanism of its last frame (the analysis library's rule,
// which the engine library does not link).
void write_summary(const RunSummary& r, const RunOptions& opt, bool depth_averaged) {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  std::string why;
  const std::string mechanism =
      depth_averaged ? std::string() : analysis::final_mechanism(r.pvd_path, why);
  write_run_record(opt.out_dir, make_run_record(r, opt.out_dir,
                                                depth_averaged ? Method::Dam : Method::Mpm,
                                                stopped_by(), usage.ru_maxrss / 1024.0, mechanism));
}

// Runs go (a run or a resume) with progress, writes its summary.json (at
// its end, while the run holds the folder) and prints its summary; the exit
// code.
int execute(const std::function<RunSummary(const RunOptions&)>& go, const RunOptions& opt,
            bool quiet, bool depth_averaged) {
  ProgressReporter progress;
  RunOptions with_progress = opt;
  if (!quiet) with_progress.on_progress = [&](const RunProgress& p) { progress.update(p); };
  with_progress.on_finished = [&](const RunSummary& ended) {
    write_summary(ended, opt, depth_averaged);
  };
  RunSummary r;
  try {
    r = go(with_progress);
  } catch (const SceneError&) {
    progress.finish();
    throw;  // a scene the method cannot run: main's exit code for it
  } catch (const ResumeRefused& e) {
    progress.finish();
    std::cerr << "runout: cannot resume: " << e.what() << "; the folder is left as it was\n";
    return cli::kResumeRefused;
  } catch (const CheckpointMissing& e) {
    progress.finish();
    std::cerr << "runout: cannot resume: " << e.what() << "\n";
    return cli::kNoScene;
  } catch (const CheckpointError& e) {
    progress.finish();
    std::cerr << "runout: cannot resume: " << e.what() << "\n";
    return cli::kSceneInvalid;
  } catch (const OutputFolderBusy& e) {
    progress.finish();
    std::cerr << "runout: " << e.what() << "\n";
    return cli::kFolderBusy;
  } catch (const std::exception& e) {
    progress.finish();
    std::cerr << "runout: cannot write the output: " << e.what() << "\n";
    return cli::kCantCreate;
  }
  progress.finish();
  const std::string name = std::filesystem::path(r.pvd_path).stem().string();
  const double rate = r.wall_seconds > 0 ? r.particles * double(r.steps_run) / r.wall_seconds : 0;
  if (r.resumed_from >= 0)
    std::printf("resumed from the checkpoint at t = %.6g s (step %ld)\n", r.resumed_from,
                r.steps - r.steps_run);
  if (depth_averaged)
    std::printf("%s (depth-averaged): %d elements, %ld steps to t = %.4g s in %.3f s\n",
                name.c_str(), r.particles, r.steps, r.end_time, r.wall_seconds);
  else
    std::printf("%s: %d particles, %ld steps to t = %.4g s in %.2f s (%.3g particle-steps/s, %d threads)\n",
                name.c_str(), r.particles, r.steps, r.end_time, r.wall_seconds, rate,
                omp_get_max_threads());
  if (r.at_rest) std::printf("the slide came to rest at t = %.4g s\n", r.end_time);
  std::printf("output: %s (%d frames)\n", r.pvd_path.c_str(), r.frames);
  if (r.failed) {
    std::cerr << "runout: run stopped: " << r.failure << "\nrunout: the " << r.frames
              << " frames written before it are kept in " << opt.out_dir << "\n";
    if (!r.checkpoint_path.empty())
      std::cerr << "runout: the last checkpoint, at t = " << r.checkpoint_time << " s, is kept: "
                << r.checkpoint_path << "\n";
    return cli::kBlowUp;
  }
  if (const int signal = stopped_by()) return report_stop(r, opt, signal);
  return cli::kOk;
}

int run(const Scene& s, const SceneSource& source, const std::string& out,
        const std::string& backend, bool quiet, double checkpoint_every,
        const LimitArgs& limit_args, bool default_threads) {
  if (checkpoint_every > 0 && s.method == Method::Dam) {
    std::cerr << "runout: --checkpoint-every: the depth-averaged model (method = dam) writes "
                 "no checkpoints\n";
    return cli::kUsage;
  }
  for (const std::string& line : coarse_averaging(s)) std::cerr << "runout: warning: " << line << "\n";
  std::string why_not;
  const Runner runner = runner_for(s, backend, why_not);
  if (!runner) {
    std::cerr << "runout: --backend " << backend << ": " << why_not << "\n";
    return cli::kUnavailable;
  }
  RunOptions opt;
  opt.out_dir = out.empty() ? "out/" + s.name : out;
  opt.checkpoint_every = checkpoint_every;
  // The run's one memory estimate; the more basic refusal comes first.
  opt.memory = require_memory(s, s.method, source);
  require_cost(s, s.method, *opt.memory, limits_for(limit_args, &opt.out_dir), source);
  if (default_threads) {
    cli::use_default_threads(opt.memory->items);
    if (backend == "cpu" && s.method == Method::Mpm) opt.adapt_threads = cli::adaptable_threads();
  }
  return execute([&](const RunOptions& o) { return runner(s, o); }, opt, quiet,
                 s.method == Method::Dam);
}

int resume(const std::string& dir, std::optional<double> end, const std::string& backend,
           bool quiet, bool default_threads, const LimitArgs& limit_args) {
  // The run's resolved scene; where it cannot be read the resume itself
  // says what is wrong with the folder.
  std::optional<Scene> s;
  try {
    s = load_scene_file((std::filesystem::path(dir) / kResolvedSceneFile).string());
  } catch (const std::exception&) {
  }
  // A later end costs what `runout run --end` would: the run to it, whole,
  // within the step and output limits. Whether the end itself may be taken
  // the resume checks against its checkpoint.
  if (s) {
    const MemoryEstimate memory = estimate_memory(*s, s->method);
    if (end) {
      s->time.end = *end;
      require_cost(*s, s->method, memory, limits_for(limit_args, &dir));
    }
    if (default_threads) cli::use_default_threads(memory.items);
  }
  std::string why_not;
  const Resumer resumer = mpm_backend(backend, why_not).resume;
  if (!resumer) {
    std::cerr << "runout: --backend " << backend << ": " << why_not << "\n";
    return cli::kUnavailable;
  }
  RunOptions opt;
  opt.out_dir = dir;
  opt.end = end;
  if (default_threads && backend == "cpu") opt.adapt_threads = cli::adaptable_threads();
  return execute(resumer, opt, quiet, false);
}

// Every frame the folder's index lists against its manifest: 0 when all
// are whole, 65 naming each bad one, 66 when there is no index to check.
int verify(const std::string& dir) {
  const std::vector<std::string> indexes = cli::pvd_indexes(dir);
  if (indexes.empty()) {
    std::cerr << "runout: verify: no .pvd index in " << dir << "\n";
    return cli::kNoScene;
  }
  int bad = 0;
  for (const std::string& pvd : indexes) {
    try {
      for (const std::string& problem : verify_frames(pvd)) {
        std::cerr << "runout: verify: " << problem << "\n";
        ++bad;
      }
    } catch (const std::exception& e) {
      std::cerr << "runout: verify: " << e.what() << "\n";
      ++bad;
    }
  }
  if (bad > 0) return cli::kSceneInvalid;
  std::printf("%s: every listed frame matches its manifest\n", dir.c_str());
  return cli::kOk;
}

int info() {
  const char* wait = std::getenv("OMP_WAIT_POLICY");
  const char* spins = std::getenv("GOMP_SPINCOUNT");
  std::printf("runout %s\nOpenMP threads: %d\nOpenMP wait policy: %s\nOpenMP spin count: %s\n",
              RUNOUT_VERSION, omp_get_max_threads(), wait ? wait : "(libgomp's default)",
              spins ? spins : "(the policy's)");
  std::string why;
  const auto devices = cuda_devices(why);
  if (devices.empty()) std::printf("CUDA devices: none (%s)\n", why.c_str());
  for (const auto& d : devices) std::printf("CUDA device %s\n", d.c_str());
  return cli::kOk;
}

}  // namespace

int main(int argc, char** argv) {
  runout::cli::use_short_openmp_wait(argv);
  CLI::App app{"Runout: submarine landslide runout with the material point method"};
  app.set_version_flag("--version", std::string("runout ") + RUNOUT_VERSION);
  app.require_subcommand(1);

  SceneArgs run_args, check_args;
  LimitArgs run_limits, check_limits, resume_limits;
  std::string out;
  RunArgs run_resume_args;  // shared by run and resume
  CLI::App* run_cmd = app.add_subcommand("run", "Run a scene and write its frames and history");
  add_scene_args(run_cmd, run_args);
  add_limit_args(run_cmd, run_limits);
  run_cmd->add_option("-o,--out", out, "Output folder (default out/<scene name>)")
      ->check(cli::non_empty_folder());
  add_run_args(run_cmd, run_resume_args);
  double checkpoint_every = 0;
  run_cmd->add_option("--checkpoint-every", checkpoint_every,
                      "Write checkpoint.bin every SECONDS of simulated time (rounded to "
                      "history rows), for `runout resume`")
      ->check(cli::finite_positive());
  std::string resume_dir;
  CLI::App* resume_cmd = app.add_subcommand(
      "resume", "Continue a run from the checkpoint.bin in its output folder");
  resume_cmd->add_option("out_dir", resume_dir, "Output folder of the run")
      ->required()
      ->check(cli::non_empty_folder());
  add_run_args(resume_cmd, run_resume_args);
  std::optional<double> resume_end;
  resume_cmd->add_option("--end", resume_end,
                         "Run on to this time [s] instead of the run's end time (a run that "
                         "ended still moving goes on from its last checkpoint)")
      ->check(cli::finite_positive());
  add_limit_args(resume_cmd, resume_limits);
  CLI::App* check_cmd =
      app.add_subcommand("check", "Validate a scene and print it resolved, with its sizes");
  add_scene_args(check_cmd, check_args);
  add_limit_args(check_cmd, check_limits);
  std::optional<double> budget;
  check_cmd->add_option("--budget", budget,
                        "Estimate the finest cell size per method that runs within SECONDS "
                        "here, and pick a method")
      ->check(cli::finite_positive());
  StudyArgs study_args;
  CLI::App* study_cmd = nullptr;
  add_study_command(app, study_args, study_cmd);
  std::string verify_dir;
  CLI::App* verify_cmd = app.add_subcommand(
      "verify", "Check every frame an output folder's index lists against its manifest");
  verify_cmd->add_option("out_dir", verify_dir, "Output folder of a run")->required();
  AnalyseArgs analyse_args;
  CLI::App* analyse_cmd = nullptr;
  add_analyse_command(app, analyse_args, analyse_cmd);
  ReportArgs report_args;
  CLI::App* report_cmd = nullptr;
  add_report_command(app, report_args, report_cmd);
  app.add_subcommand("info", "Version, threads and CUDA devices");

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return cli::kUsage;
  }
  const int threads = run_resume_args.threads;
  const std::string& backend = run_resume_args.backend;
  const bool quiet = run_resume_args.quiet;
  if (threads > 0) omp_set_num_threads(threads);
  if (*run_cmd || *resume_cmd || *study_cmd) stop_on_signals();
  try {
    if (*run_cmd) {
      const LoadedScene loaded = load(run_args);
      return run(loaded.scene, loaded.source, out, backend, quiet, checkpoint_every, run_limits,
                 threads <= 0);
    }
    if (*resume_cmd)
      return resume(resume_dir, resume_end, backend, quiet, threads <= 0, resume_limits);
    if (*check_cmd && budget) return budget_check(load(check_args).scene, *budget);
    if (*check_cmd) {
      const LoadedScene loaded = load(check_args);
      return check(loaded.scene, loaded.source, check_limits);
    }
    if (*study_cmd) return run_study(study_args);
    if (*verify_cmd) return verify(verify_dir);
    if (*analyse_cmd) return run_analyse(analyse_args);
    if (*report_cmd) return run_report(report_args);
    return info();
  } catch (const SceneFileError& e) {
    std::cerr << "runout: " << e.what() << "\n";
    return cli::kNoScene;
  } catch (const SceneError& e) {
    std::cerr << "runout: " << e.what() << "\n";
    return cli::kSceneInvalid;
  } catch (const NumericalFailure& e) {
    std::cerr << "runout: " << e.what() << "\n";
    return cli::kBlowUp;
  }
}
