#pragma once
// `runout study --launcher slurm`: the study's runs as one Slurm job array
// (sbatch), each element one `runout run`, with the resources the study
// states for it; elements that end without a finished summary.json
// (failed, killed, pre-empted) are submitted again, up to a cap
// (docs/study.md).
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace runout {

struct SlurmRequest {
  int cpus = 1;             // --cpus-per-task: the run's OpenMP threads
  double memory_mib = 0;    // --mem
  double minutes = 0;       // --time
  int max_resubmits = 2;    // submissions after the first, for the elements still unfinished
  std::vector<std::string> sbatch_args;  // passed to sbatch as given (--partition=..., --account=...)
};

struct SlurmElement {
  std::vector<std::string> command;  // argv of the element's run
  std::filesystem::path log;         // its stdout and stderr
};

// Writes study_dir/slurm/ (one script per element, the array script),
// submits the elements that are not finished() with `sbatch --wait
// --array`, and after each array has ended submits again those still not
// finished, at most request.max_resubmits times. Each submission is a row
// of study_dir/slurm/submissions.csv (submission, job id, elements).
// Returns the number of submissions. Throws std::runtime_error when
// sbatch cannot be run or refuses the job.
int run_on_slurm(const std::filesystem::path& study_dir, const std::vector<SlurmElement>& elements,
                 const SlurmRequest& request, const std::function<bool(std::size_t)>& finished);

}  // namespace runout
