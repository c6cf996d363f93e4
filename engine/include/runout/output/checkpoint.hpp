#pragma once
// checkpoint.bin: everything an MPM run needs to continue bit for bit (the
// particles in their memory order, the driver's counters, the run
// schedule's place and the resolved scene), in a versioned binary file
// with a checksum. Format in docs/output.md, "Checkpoints".
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "runout/mpm/particles.hpp"
#include "runout/scene/scene.hpp"
#include "runout/mpm/simulation.hpp"

namespace runout {

inline constexpr const char* kCheckpointFile = "checkpoint.bin";
// The folder of a run's output folder that `runout analyse` writes into; a
// new run removes it with the rest of the old run's files.
inline constexpr const char* kAnalysisFolder = "analysis";

// Where the run schedule (run_schedule.hpp) stands after a history row.
struct ScheduleState {
  long row = 0;              // the schedule's k: rows 0..row are in history.csv
  long checkpoint_rows = 0;  // a checkpoint every this many rows
  int frames = 0;            // frames written, frame_00000 .. frame_<frames - 1>
  std::vector<std::pair<double, std::string>> pvd;  // the index: time, file
  // Each index entry's manifest line ("file size crc32") when the checkpoint
  // was written: a resume keeps those frames only if they are still these.
  std::vector<std::string> frame_records;
  double rest_peak = 0, rest_since = -1;            // the at-rest test (RestDetector)
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

// The checkpoint is sound but the folder does not go with it (a kept frame
// changed or missing, history.csv shorter than it counts): the resume is
// refused before anything in the folder changes.
class ResumeRefused : public std::runtime_error {
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
// Reads the header first and refuses, before reading the rest, a file that
// is not regular (a device, a pipe) or whose stated size is not its size.
Checkpoint read_checkpoint(const std::string& path);

// FNV-1a of a resolved scene's text: which run a checkpoint belongs to.
std::uint64_t scene_hash(std::string_view scene_toml);

// Throws CheckpointError unless the run folder's resolved scene (the file
// at resolved_path, which a run writes first) is the checkpoint's own:
// another run's checkpoint copied in would mix two runs in one folder.
void require_same_scene(const CheckpointState& state, const std::string& resolved_path,
                        const std::string& source);

// Throws CheckpointError unless every particle's material and body index
// is one of the scene's (the step indexes tables with them).
void require_particles_fit(const Particles& particles, const Scene& scene,
                           const std::string& source);

}  // namespace runout
