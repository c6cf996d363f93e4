#pragma once
// The pieces of `runout report`'s page (report_command.hpp): escaped text,
// tables, line charts as SVG and images as data URIs, so that the page is
// one file that needs no network and no other file.
#include <string>
#include <string_view>
#include <vector>

namespace runout::html {

// Text with &, <, > and " escaped for an element or an attribute.
std::string escape(std::string_view text);

// A number as a table shows it: 4 significant digits, "-" for NaN.
std::string number(double value);

// <table> with a header row; every cell is escaped.
std::string table(const std::vector<std::string>& header,
                  const std::vector<std::vector<std::string>>& rows);

// data:MIME;base64,... of the bytes.
std::string data_uri(std::string_view mime, std::string_view bytes);

struct Series {
  std::string label;
  std::vector<double> x, y;  // the same length; non-finite points are left out
};

// An SVG line chart of one or more series against a shared x axis, with
// axis labels, ticks at 1, 2 or 5 times a power of ten and a legend where
// there is more than one series.
std::string line_chart_svg(const std::string& title, const std::string& x_label,
                           const std::string& y_label, const std::vector<Series>& series);

}  // namespace runout::html
