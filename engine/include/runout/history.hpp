#pragma once
// history.csv: one row per history time, appended and flushed as the run
// goes, so a killed run keeps every row it computed.
#include <cstdio>
#include <string>

#include "runout/simulation.hpp"

namespace runout {

class HistoryWriter {
 public:
  explicit HistoryWriter(const std::string& path);  // writes the header
  ~HistoryWriter();
  HistoryWriter(const HistoryWriter&) = delete;
  HistoryWriter& operator=(const HistoryWriter&) = delete;

  void append(const Simulation& sim);

 private:
  std::string path_;
  std::FILE* file_;
};

}  // namespace runout
