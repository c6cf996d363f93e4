#include "progress.hpp"

#include <unistd.h>

#include <cstdio>
#include <string>

namespace runout {

std::string clock_text(double seconds) {
  char buf[32];
  if (!(seconds < 1e9)) {  // past 30 years, and NaN: no clock holds it
    std::snprintf(buf, sizeof buf, "%.3g s", seconds);
    return buf;
  }
  const long s = static_cast<long>(seconds + 0.5);
  std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  return buf;
}

ProgressReporter::ProgressReporter() : tty_(isatty(STDERR_FILENO) != 0) {}

void ProgressReporter::update(const RunProgress& p) {
  const double interval = tty_ ? 0.2 : 5.0;
  if (p.wall_seconds - last_print_ < interval && p.time < p.end) return;
  last_print_ = p.wall_seconds;
  const double frac = p.end > 0 ? p.time / p.end : 1.0;
  // Simulated time per wall second is nearly steady once the slide moves.
  const double eta = frac > 0 ? p.wall_seconds * (1.0 - frac) / frac : 0.0;
  if (tty_) {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(frac * kWidth);
    std::fprintf(stderr, "\r[%s%s] %5.1f%%  t = %.3g / %.3g s  step %ld  ETA %s ",
                 std::string(filled, '#').c_str(), std::string(kWidth - filled, ' ').c_str(),
                 100.0 * frac, p.time, p.end, p.steps, clock_text(eta).c_str());
    drew_ = true;
  } else {
    std::fprintf(stderr, "t = %.4g / %.4g s (%.1f%%), step %ld, elapsed %s, ETA %s\n", p.time,
                 p.end, 100.0 * frac, p.steps, clock_text(p.wall_seconds).c_str(),
                 clock_text(eta).c_str());
  }
  std::fflush(stderr);
}

void ProgressReporter::finish() {
  if (drew_) std::fputc('\n', stderr);
}

}  // namespace runout
