#pragma once
// Values as `runout analyse` writes them: numbers with 17 significant
// digits, so that each reads back as the double that was measured (as the
// engine's history.csv and profiles have them), and text quoted for CSV or
// JSON.
#include <string>
#include <string_view>

namespace runout::analysis::text {

// "%.17g"; "nan", "inf" or "-inf" for a value that is not finite.
std::string csv_number(double value);

// The same, but null for a value that is not finite: JSON has no NaN.
std::string json_number(double value);

// The text as it is, or in double quotes (inner quotes doubled) when it
// holds a comma, a quote or a line break.
std::string csv_text(std::string_view value);

// The text as a JSON string: quoted, with quotes, backslashes and control
// characters escaped.
std::string json_text(std::string_view value);

}  // namespace runout::analysis::text
