#pragma once
// Checks of options beyond CLI11's own. Its PositiveNumber and
// NonNegativeNumber let "nan" and "inf" through (every comparison with NaN
// is false), and a NaN limit switches the limit off; and an empty folder
// name would fall back to the default folder unnoticed.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace runout::cli {

// A number that is finite and above lo (or at least lo where lo_allowed).
inline CLI::Validator finite_number(double lo, bool lo_allowed) {
  char lo_text[32];
  std::snprintf(lo_text, sizeof lo_text, "%g", lo);
  const std::string bound = std::string(lo_allowed ? "at least " : "above ") + lo_text;
  return CLI::Validator(
      [lo, lo_allowed, bound](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        const bool number = !text.empty() && end && *end == '\0';
        if (number && std::isfinite(v) && (v > lo || (lo_allowed && v == lo))) return "";
        return "must be a finite number " + bound + ", not '" + text + "'";
      },
      "FINITE " + bound);
}

// Finite and above 0.
inline CLI::Validator finite_positive() { return finite_number(0.0, false); }
// Finite and at least 0.
inline CLI::Validator finite_non_negative() { return finite_number(0.0, true); }

// A folder name that is not empty.
inline CLI::Validator non_empty_folder() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        return text.empty() ? "must name a folder, not be empty" : "";
      },
      "FOLDER");
}

}  // namespace runout::cli
