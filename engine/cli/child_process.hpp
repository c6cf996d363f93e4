#pragma once
// The study's children: `runout run` here, and `sbatch` for the Slurm
// launcher, each started with its output going to a file.
#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

namespace runout {

// fork + exec of args[0] (searched on PATH when it has no '/'), its stdout
// (and stderr when with_stderr) into `out`, in a process group of its own.
// The pid, or -1 when fork fails.
pid_t spawn(const std::vector<std::string>& args, const std::filesystem::path& out,
            bool with_stderr);

// Waits for any child of this process to end and returns its pid, with its
// waitpid status in `status`; -1 when there is none. It polls, so that a
// stop request (run_control.hpp: SIGINT, SIGTERM, SIGHUP) is seen at once
// however it falls, and passes that signal on to each of `running` once
// (`passed_on` says it has been).
pid_t wait_passing_stop(const std::vector<pid_t>& running, bool& passed_on, int& status);

// The exit code of a child waitpid reported as `status`: 128 + the signal
// for one a signal ended, as a shell reports it.
int exit_code(int status);

}  // namespace runout
