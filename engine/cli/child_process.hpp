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

// The exit code of a child waitpid reported as `status`: 128 + the signal
// for one a signal ended, as a shell reports it.
int exit_code(int status);

}  // namespace runout
