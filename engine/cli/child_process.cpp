#include "child_process.hpp"

#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <cstdio>

namespace runout {

pid_t spawn(const std::vector<std::string>& args, const std::filesystem::path& out,
            bool with_stderr) {
  std::vector<char*> argv;
  for (const std::string& s : args) argv.push_back(const_cast<char*>(s.c_str()));
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid != 0) return pid;
  // A group of its own: a terminal's Ctrl-C reaches the study alone, which
  // passes it on once (a second signal would kill the run unsaved).
  setpgid(0, 0);
  const int fd = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd >= 0) {
    dup2(fd, STDOUT_FILENO);
    if (with_stderr) dup2(fd, STDERR_FILENO);
  }
  execvp(argv[0], argv.data());
  std::perror(("runout study: cannot run " + args[0]).c_str());
  _exit(127);
}

int exit_code(int status) {
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace runout
