#include "child_process.hpp"

#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <signal.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <thread>

#include "runout/run/run_control.hpp"

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

pid_t wait_passing_stop(const std::vector<pid_t>& running, bool& passed_on, int& status) {
  constexpr std::chrono::milliseconds kPoll{20};
  for (;;) {
    if (!passed_on && stop_requested()) {
      passed_on = true;
      for (const pid_t pid : running) ::kill(pid, stop_requested());
    }
    const pid_t pid = ::waitpid(-1, &status, WNOHANG);
    if (pid > 0) return pid;
    if (pid < 0 && errno != EINTR) return -1;
    std::this_thread::sleep_for(kPoll);
  }
}

int exit_code(int status) {
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace runout
