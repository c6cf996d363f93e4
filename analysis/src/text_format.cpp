#include "text_format.hpp"

#include <cmath>
#include <cstdio>

#include "runout/output/quoted_text.hpp"

namespace runout::analysis::text {

std::string csv_number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", value);
  return buf;
}

std::string json_number(double value) {
  return std::isfinite(value) ? csv_number(value) : "null";
}

std::string csv_text(std::string_view value) {
  if (value.find_first_of(",\"\n\r") == std::string_view::npos) return std::string(value);
  std::string out = "\"";
  for (const char c : value) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string json_text(std::string_view value) { return quoted_text(value); }

}  // namespace runout::analysis::text
