#pragma once
// Checks of options beyond CLI11's own. Its PositiveNumber,
// NonNegativeNumber and Range let "nan" through (every comparison with NaN
// is false), and a NaN limit switches the limit off; the first two print
// their upper bound, the largest double, in 309 digits; and an empty folder
// name would fall back to the default folder unnoticed.
#include <CLI/CLI.hpp>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <string>

namespace runout::cli {

// A number that is finite and that `ok` accepts; `bound` says which ones
// it accepts ("above 0"), for the refusal.
inline CLI::Validator finite_number(std::function<bool(double)> ok, const std::string& bound) {
  return CLI::Validator(
      [ok, bound](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        const bool number = !text.empty() && end && *end == '\0';
        if (number && std::isfinite(v) && ok(v)) return "";
        return "must be a finite number " + bound + ", not '" + text + "'";
      },
      "FINITE " + bound);
}

inline CLI::Validator finite_positive() {
  return finite_number([](double v) { return v > 0; }, "above 0");
}
inline CLI::Validator finite_non_negative() {
  return finite_number([](double v) { return v >= 0; }, "at least 0");
}
inline CLI::Validator finite_between(double lo, double hi) {
  char bound[64];
  std::snprintf(bound, sizeof bound, "in [%g, %g]", lo, hi);
  return finite_number([lo, hi](double v) { return v >= lo && v <= hi; }, bound);
}

// A whole number from lo to INT_MAX, for the int options (counts).
inline CLI::Validator whole_number_from(long lo) {
  const std::string bound = "a whole number from " + std::to_string(lo) + " to " +
                            std::to_string(std::numeric_limits<int>::max());
  return CLI::Validator(
      [lo, bound](std::string& text) -> std::string {
        char* end = nullptr;
        errno = 0;
        const long v = std::strtol(text.c_str(), &end, 10);
        const bool whole = !text.empty() && end && *end == '\0' && errno == 0;
        if (whole && v >= lo && v <= std::numeric_limits<int>::max()) return "";
        return "must be " + bound + ", not '" + text + "'";
      },
      "INT");
}

// A folder name that is not empty.
inline CLI::Validator non_empty_folder() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        return text.empty() ? "must name a folder, not be empty" : "";
      },
      "FOLDER");
}

}  // namespace runout::cli
