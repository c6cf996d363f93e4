#include "study_slurm.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "child_process.hpp"
#include "runout/output/atomic_file.hpp"
#include "runout/output/file_text.hpp"
#include "runout/run/run_control.hpp"

namespace runout {
namespace {

namespace fs = std::filesystem;

// A word for bash, in single quotes.
std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// "0-3,7": the indices as Slurm's --array reads them.
std::string array_spec(const std::vector<std::size_t>& indices) {
  std::string spec;
  for (std::size_t k = 0; k < indices.size();) {
    std::size_t end = k;
    while (end + 1 < indices.size() && indices[end + 1] == indices[end] + 1) ++end;
    if (!spec.empty()) spec += ',';
    spec += std::to_string(indices[k]);
    if (end > k) {
      spec += '-';
      spec += std::to_string(indices[end]);
    }
    k = end + 1;
  }
  return spec;
}

// sbatch with these arguments, its stdout into `out`; its exit status. A
// stop request to the study is passed on to it.
int sbatch(const std::vector<std::string>& args, const fs::path& out) {
  const pid_t pid = spawn(args, out, false);
  if (pid < 0) throw std::runtime_error("cannot start sbatch: fork failed");
  bool passed_on = false;
  int status = 0;
  for (;;) {
    const pid_t ended = wait_passing_stop({pid}, passed_on, status);
    if (ended == pid) return exit_code(status);
    if (ended < 0) throw std::runtime_error("lost sbatch: waitpid failed");
  }
}

}  // namespace

int run_on_slurm(const fs::path& study_dir, const std::vector<SlurmElement>& elements,
                 const SlurmRequest& request, const std::function<bool(std::size_t)>& finished) {
  const fs::path dir = fs::absolute(study_dir / "slurm");
  fs::create_directories(dir);
  for (std::size_t k = 0; k < elements.size(); ++k) {
    std::string line = "exec";
    for (const std::string& word : elements[k].command) {
      line += ' ';
      line += quoted(word);
    }
    line += " > " + quoted(fs::absolute(elements[k].log).string()) + " 2>&1\n";
    write_file_atomically((dir / ("element_" + std::to_string(k) + ".sh")).string(),
                          "#!/bin/bash\n" + line);
  }
  // One request for every element: the largest run's memory and time.
  const std::string script = (dir / "array.sh").string();
  write_file_atomically(
      script, "#!/bin/bash\n#SBATCH --job-name=runout-study\n#SBATCH --ntasks=1\n"
              "#SBATCH --cpus-per-task=" + std::to_string(request.cpus) +
              "\n#SBATCH --mem=" + std::to_string(std::lround(std::ceil(request.memory_mib))) +
              "M\n#SBATCH --time=" + std::to_string(std::lround(std::ceil(request.minutes))) +
              "\n#SBATCH --output=" + (dir / "slurm-%A_%a.out").string() +
              "\nexec /bin/bash " + quoted(dir.string()) + "/element_${SLURM_ARRAY_TASK_ID}.sh\n");

  std::string log = "submission,job_id,elements\n";
  int submissions = 0;
  for (;;) {
    std::vector<std::size_t> todo;
    for (std::size_t k = 0; k < elements.size(); ++k)
      if (!finished(k)) todo.push_back(k);
    // A stop request (a signal to the study) ends the submissions.
    if (todo.empty() || submissions > request.max_resubmits || stop_requested()) break;
    std::vector<std::string> args{"sbatch", "--parsable", "--wait", "--array=" + array_spec(todo)};
    args.insert(args.end(), request.sbatch_args.begin(), request.sbatch_args.end());
    args.push_back(script);
    const fs::path out = dir / ("sbatch_" + std::to_string(submissions) + ".out");
    std::fprintf(stderr, "runout study: sbatch --array=%s (submission %d)\n",
                 array_spec(todo).c_str(), submissions + 1);
    // sbatch --wait exits non-zero when an element failed, which the
    // summaries tell apart; no job id means it refused the job.
    const int status = sbatch(args, out);
    std::string id = file_text(out).value_or("");
    id = id.substr(0, id.find_first_of(";\n"));
    if (id.empty())
      throw std::runtime_error("sbatch refused the job array (exit " + std::to_string(status) +
                               "); its output is in " + out.string());
    log += std::to_string(++submissions) + "," + id + ",\"" + array_spec(todo) + "\"\n";
    write_file_atomically((dir / "submissions.csv").string(), log);
  }
  return submissions;
}

}  // namespace runout
