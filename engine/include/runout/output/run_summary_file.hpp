#pragma once
// summary.json: what one run came to, as a file in its output folder
// (docs/output.md), so that `runout study` and anything else reads a run's
// result without parsing its log. Written atomically once the run has
// ended (completed, at rest, blown up or stopped by a signal).
#include <string>
#include <string_view>

#include "runout/run/run.hpp"

namespace runout {

inline constexpr const char* kSummaryFile = "summary.json";
// The scene a run goes on with, in its folder: what `resume` checks a
// checkpoint's scene against, and what the summary's scene_hash hashes.
inline constexpr const char* kResolvedSceneFile = "scene.resolved.toml";

struct RunRecord {
  std::string scene_hash;  // FNV-1a of scene.resolved.toml (checkpoint.hpp), 16 hex digits
  std::string status;      // completed, at_rest, blown_up or stopped
  std::string note;        // why it blew up or which signal stopped it; empty otherwise
  std::string method;      // mpm or dam
  long particles = 0;      // elements for the depth-averaged model
  long steps = 0;
  double end_time = 0;          // [s] simulated time reached
  double wall_seconds = 0;      // [s] of the run itself, output included
  double peak_memory_mib = 0;   // the process's peak resident memory (ru_maxrss)
  double runout = 0;            // [m] toe runout at the end (history.csv)
  double runout_95 = 0;         // [m] the mass front's runout at the end; NaN: not recorded
  double stop_time = 0;         // [s] when it came to rest; NaN when it did not
  double peak_toe_velocity = 0; // [m/s] largest toe velocity of history.csv
  double final_length = 0;      // [m] main body length at the end
  std::string mechanism;        // of the last frame (runout analyse's rule); empty: not classified

  // A run whose result stands: not rerun by a resumed study. A blown-up run
  // stands too: the same scene blows up again.
  bool finished() const { return status == "completed" || status == "at_rest" || status == "blown_up"; }
};

// The record of a run that just ended in out_dir: its summary, the
// stop signal (0: none), the process's peak memory [MiB], the mechanism
// of its last frame, and what its history.csv and scene.resolved.toml say.
// Throws std::runtime_error when those cannot be read.
RunRecord make_run_record(const RunSummary& summary, const std::string& out_dir, Method method,
                          int stop_signal, double peak_memory_mib, const std::string& mechanism);

// JSON of one flat object; non-finite numbers as null.
std::string to_json(const RunRecord& record);
// Throws std::runtime_error naming source and the key or the place that is wrong.
RunRecord parse_run_record(std::string_view json, const std::string& source);

// out_dir/summary.json, atomically.
void write_run_record(const std::string& out_dir, const RunRecord& record);
// Throws std::runtime_error when it is missing or malformed.
RunRecord read_run_record(const std::string& out_dir);

// The hash a run's summary records for a resolved scene text.
std::string scene_hash_text(std::string_view resolved_toml);

}  // namespace runout
