#include "runout/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
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

}  // namespace

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
