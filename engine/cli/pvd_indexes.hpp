#pragma once
// The .pvd indexes in a run's output folder, for the commands that read a
// finished run (verify, analyse, report): a run writes one; none where the
// folder is missing or cannot be read. Sorted, so they come in one order.
#include <algorithm>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace runout::cli {

inline std::vector<std::string> pvd_indexes(const std::string& out_dir) {
  std::vector<std::string> indexes;
  std::error_code unreadable;
  for (const auto& e : std::filesystem::directory_iterator(out_dir, unreadable))
    if (e.path().extension() == ".pvd") indexes.push_back(e.path().string());
  std::sort(indexes.begin(), indexes.end());
  return indexes;
}

}  // namespace runout::cli
