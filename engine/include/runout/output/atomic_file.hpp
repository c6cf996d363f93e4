#pragma once
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

namespace runout {

// Writes contents to path through a temporary file in the same folder and
// rename(2), so readers see the old file or the whole new one, never a part.
// Throws std::runtime_error naming the path on any I/O failure.
void write_file_atomically(const std::string& path, std::string_view contents);

// Writes all of contents to fd, across short writes and EINTR; false with
// errno set when a write fails (a full disk: ENOSPC).
bool write_all(int fd, std::string_view contents);

}  // namespace runout

namespace runout {

// Another live process writes into the output folder.
class OutputFolderBusy : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The hidden lock file of an output folder.
inline constexpr const char* kOutputLockFile = ".runout.lock";

// Takes the exclusive lock of an output folder for this process (flock(2)
// on dir/.runout.lock, which records the holder's pid), or throws
// OutputFolderBusy naming the holder. The kernel drops the lock when its
// process dies, so a lock left by a killed run is taken over. Re-entrant
// within a process: each lock needs one unlock.
void lock_output_folder(const std::string& dir);
void unlock_output_folder(const std::string& dir);

// Releases a lock taken earlier when it goes out of scope.
class AdoptedFolderLock {
 public:
  explicit AdoptedFolderLock(std::string dir) : dir_(std::move(dir)) {}
  ~AdoptedFolderLock() { unlock_output_folder(dir_); }
  AdoptedFolderLock(const AdoptedFolderLock&) = delete;
  AdoptedFolderLock& operator=(const AdoptedFolderLock&) = delete;

 private:
  std::string dir_;
};

// Whether a file name is one of write_file_atomically's temporaries.
bool is_atomic_temporary(const std::string& file_name);

}  // namespace runout
