#pragma once
// checkpoint.bin: everything an MPM run needs to continue bit for bit (the
// particles in their memory order, the driver's counters, the run
// schedule's place and the resolved scene), in a versioned binary file
// with a checksum. Format in docs/output.md, "Checkpoints".
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "runout/particles.hpp"
#include "runout/simulation.hpp"

namespace runout {

inline constexpr const char* kCheckpointFile = "checkpoint.bin";

// Where the run schedule (run_schedule.hpp) stands after a history row.
struct ScheduleState {
  long row = 0;              // the schedule's k: rows 0..row are in history.csv
  long checkpoint_rows = 0;  // a checkpoint every this many rows
  int frames = 0;            // frames written, frame_00000 .. frame_<frames - 1>
  std::vector<std::pair<double, std::string>> pvd;  // the index: time, file
  double rest_peak = 0, rest_since = -1;            // the at-rest test
  double initial_toe = 0;    // runout is measured from it
};

struct CheckpointState {
  std::string scene_toml;  // the resolved scene, to_toml
  StepCounters counters;
  ScheduleState schedule;
};

struct Checkpoint {
  CheckpointState state;
  Particles particles;
};

// The file cannot be used: missing, unreadable, not a checkpoint, of
// another version, truncated, or failing its checksum. what() names the
// file and the problem.
class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The file does not exist (or cannot be opened).
class CheckpointMissing : public CheckpointError {
 public:
  using CheckpointError::CheckpointError;
};

std::string encode_checkpoint(const CheckpointState& state, const Particles& particles);
// source names the bytes in error messages.
Checkpoint decode_checkpoint(std::string_view bytes, const std::string& source);

// Written atomically (atomic_file.hpp): the previous checkpoint stays until
// the new one is complete on disk.
void write_checkpoint(const std::string& path, const CheckpointState& state,
                      const Particles& particles);
Checkpoint read_checkpoint(const std::string& path);

}  // namespace runout
