#pragma once
// A run's output folder as the checkpoint tests look at it: a scratch
// folder per test, whole files, the frames the .pvd index lists, and the
// checks that two runs wrote the same thing.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace runout::run_folder {

namespace fs = std::filesystem;

// An empty folder named after the running test, removed afterwards.
class ScratchFolder {
 public:
  ScratchFolder() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / ("runout_" + std::string(info->test_suite_name()) + "_" +
                                         info->name() + "_" + std::to_string(::getpid()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchFolder() { fs::remove_all(path_); }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  const fs::path& path() const { return path_; }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path_ / name, std::ios::binary) << text;
    return (path_ / name).string();
  }

 private:
  fs::path path_;
};

inline std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The file="..." entries of a .pvd index, in order.
inline std::vector<std::string> pvd_files(const fs::path& pvd) {
  const std::string text = read_file(pvd);
  std::vector<std::string> files;
  const std::string key = "file=\"";
  for (auto at = text.find(key); at != std::string::npos; at = text.find(key, at)) {
    at += key.size();
    files.push_back(text.substr(at, text.find('"', at) - at));
  }
  return files;
}

inline std::string frame_name(int k) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%05d.vtu", k);
  return name;
}

// The index lists frame_00000 .. frame_<n-1> in order, and the folder holds
// no other frame or profile.
inline void expect_frames_in_sequence(const fs::path& dir, const fs::path& pvd) {
  const std::vector<std::string> files = pvd_files(pvd);
  for (std::size_t k = 0; k < files.size(); ++k)
    EXPECT_EQ(files[k], frame_name(static_cast<int>(k))) << "index entry " << k;
  int frames = 0, profiles = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    frames += name.rfind("frame_", 0) == 0;
    profiles += name.rfind("profile_", 0) == 0;
  }
  EXPECT_EQ(frames, static_cast<int>(files.size())) << "frames on disk against the index";
  EXPECT_EQ(profiles, static_cast<int>(files.size())) << "profiles on disk against the index";
}

// Two folders of the same scene hold byte-identical history, index and
// frames: the same particle state, bit for bit and in the same order, at
// every frame.
inline void expect_same_run(const fs::path& a, const fs::path& b, const std::string& pvd) {
  EXPECT_EQ(read_file(a / "history.csv"), read_file(b / "history.csv")) << "history.csv";
  EXPECT_EQ(read_file(a / pvd), read_file(b / pvd)) << pvd;
  for (const std::string& f : pvd_files(a / pvd))
    EXPECT_TRUE(read_file(a / f) == read_file(b / f)) << f << " differs";
}

}  // namespace runout::run_folder
