#include "runout/output/atomic_file.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>
#include <stdexcept>

namespace runout {

namespace {

// "dir/.name.tmp.<pid>.<n>": same folder, so rename(2) stays within one file
// system and is atomic; hidden, so a half-written file never shows up in a
// file dialog or matches ParaView's frame_*.vtu grouping; pid and a counter
// keep concurrent writers (processes or threads) apart.
std::string temporary_name(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  const auto slash = path.rfind('/');
  const std::size_t base = slash == std::string::npos ? 0 : slash + 1;
  return path.substr(0, base) + "." + path.substr(base) + ".tmp." +
         std::to_string(::getpid()) + "." + std::to_string(counter++);
}

// The folder locks this process holds: descriptor and depth, by folder.
struct HeldLock {
  int fd;
  int depth;
};
std::mutex held_mutex;
std::map<std::string, HeldLock> held;

std::string lock_key(const std::string& dir) {
  return std::filesystem::weakly_canonical(std::filesystem::absolute(dir)).string();
}

// The pid the holder wrote into the lock file, or "unknown".
std::string holder_pid(int fd) {
  char buf[32] = {};
  const ssize_t n = ::pread(fd, buf, sizeof buf - 1, 0);
  std::string pid(buf, n > 0 ? static_cast<std::size_t>(n) : 0);
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  return pid.empty() ? "unknown" : pid;
}

// The lock file, opened without following a link (one planted there would
// have the run overwrite its target) and refused unless it is a regular
// file of one name: a hard link would be overwritten the same way.
int open_lock_file(const std::string& path) {
  const int fd =
      ::open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0666);
  if (fd < 0 && errno == ELOOP)
    throw std::runtime_error("the lock file " + path +
                             " is a symbolic link; runout does not write through it: remove it");
  if (fd < 0)
    throw std::runtime_error("cannot create the lock file " + path + ": " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || st.st_nlink != 1) {
    ::close(fd);
    throw std::runtime_error("the lock file " + path +
                             " is not a regular file of its own (a device, a pipe, a hard link); "
                             "remove it");
  }
  return fd;
}

}  // namespace

bool write_all(int fd, std::string_view contents) {
  const char* p = contents.data();
  std::size_t left = contents.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return false;
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  return true;
}

bool is_atomic_temporary(const std::string& name) {
  return !name.empty() && name[0] == '.' && name.find(".tmp.") != std::string::npos;
}

void lock_output_folder(const std::string& dir) {
  const std::string key = lock_key(dir);
  const std::lock_guard<std::mutex> guard(held_mutex);
  if (const auto it = held.find(key); it != held.end()) {
    ++it->second.depth;
    return;
  }
  const std::string path = (std::filesystem::path(dir) / kOutputLockFile).string();
  const int fd = open_lock_file(path);
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    const std::string pid = holder_pid(fd);
    ::close(fd);
    if (error == EWOULDBLOCK)
      throw OutputFolderBusy("the output folder " + dir + " is in use by another runout (pid " +
                             pid + "); wait for it to end or choose another --out");
    throw std::runtime_error("cannot lock " + path + ": " + std::strerror(error));
  }
  // The pid is for the message of a refused second writer only: the lock
  // itself is the flock, so a stale pid in the file means nothing.
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) < 0) {
    const int error = errno;
    ::close(fd);
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(error));
  }
  held[key] = HeldLock{fd, 1};
}

void unlock_output_folder(const std::string& dir) {
  const std::lock_guard<std::mutex> guard(held_mutex);
  const auto it = held.find(lock_key(dir));
  if (it == held.end() || --it->second.depth > 0) return;
  ::close(it->second.fd);  // drops the flock
  held.erase(it);
}

void write_file_atomically(const std::string& path, std::string_view contents) {
  const std::string temp = temporary_name(path);
  // O_EXCL: never write through a stale temporary that another writer holds.
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) {
    throw std::runtime_error("cannot create a temporary file for " + path +
                             ": " + std::strerror(errno));
  }

  // The first step that fails, with its errno; later steps are skipped.
  const char* failed = nullptr;
  int error = 0;
  auto check = [&](bool ok, const char* step) {
    if (!failed && !ok) {
      failed = step;
      error = errno;
    }
  };
  check(write_all(fd, contents), "write");
  // fsync before rename: otherwise a crash can leave the name pointing at a
  // file whose data never reached the disk.
  if (!failed) check(::fsync(fd) == 0, "sync");
  check(::close(fd) == 0, "close");
  if (!failed) check(::rename(temp.c_str(), path.c_str()) == 0, "rename a temporary file onto");

  if (failed) {
    ::unlink(temp.c_str());
    throw std::runtime_error(std::string("cannot ") + failed + " " + path +
                             ": " + std::strerror(error));
  }
}

}  // namespace runout
