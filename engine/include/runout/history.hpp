#pragma once
// history.csv: one row per history time, appended and flushed as the run
// goes, so a killed run keeps every row it computed. Columns in
// docs/output.md; the morphology ones are defined in docs/morphology.md.
#include <cstdio>
#include <string>

#include "runout/morphology.hpp"
#include "runout/simulation.hpp"

namespace runout {

class HistoryWriter {
 public:
  explicit HistoryWriter(const std::string& path);  // writes the header
  ~HistoryWriter();
  HistoryWriter(const HistoryWriter&) = delete;
  HistoryWriter& operator=(const HistoryWriter&) = delete;

  // runout: toe displacement along the base since t = 0.
  void append(const Simulation& sim, const SlideMorphology& shape, double runout);

 private:
  std::string path_;
  std::FILE* file_;
};

}  // namespace runout
