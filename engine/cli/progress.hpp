#pragma once
// Progress of a run on stderr: a redrawn bar with ETA on a terminal, plain
// lines at most every few seconds otherwise (logs, CI).
#include <string>

#include "runout/run/run.hpp"

namespace runout {

// h:mm:ss, or seconds in %.3g beyond any clock.
std::string clock_text(double seconds);

class ProgressReporter {
 public:
  ProgressReporter();
  void update(const RunProgress& p);
  void finish();

 private:
  bool tty_;
  double last_print_ = -1e9;
  bool drew_ = false;
};

}  // namespace runout
