#include "html_page.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "runout/output/base64.hpp"

namespace runout::html {

namespace {

std::string format(const char* spec, double value) {
  char text[160];
  std::snprintf(text, sizeof text, spec, value);
  return text;
}

// The axis of a chart: its range widened to whole ticks, the ticks 1, 2
// or 5 times a power of ten apart (at most about eight of them).
struct Axis {
  double lo = 0, hi = 1, step = 1;
  int decimals = 0;
};

Axis axis_of(double lo, double hi) {
  if (!(lo < hi)) {  // one value, or none: a unit range round it
    const double centre = std::isfinite(lo) ? lo : 0.0;
    const double half = centre != 0.0 ? 0.1 * std::fabs(centre) : 1.0;
    lo = centre - half;
    hi = centre + half;
  }
  const double raw = (hi - lo) / 6.0;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  double step = power;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * power >= raw) {
      step = m * power;
      break;
    }
  Axis a;
  a.step = step;
  a.lo = std::floor(lo / step) * step;
  a.hi = std::ceil(hi / step) * step;
  a.decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
  return a;
}

std::string tick_label(const Axis& a, double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", a.decimals, std::fabs(value) < 1e-12 * a.step ? 0.0 : value);
  return text;
}

constexpr const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e"};

}  // namespace

std::string escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string number(double value) { return std::isnan(value) ? "-" : format("%.4g", value); }

std::string table(const std::vector<std::string>& header,
                  const std::vector<std::vector<std::string>>& rows) {
  std::string out = "<table>\n<tr>";
  for (const std::string& h : header) out += "<th>" + escape(h) + "</th>";
  out += "</tr>\n";
  for (const auto& row : rows) {
    out += "<tr>";
    for (const std::string& cell : row) out += "<td>" + escape(cell) + "</td>";
    out += "</tr>\n";
  }
  return out + "</table>\n";
}

std::string data_uri(std::string_view mime, std::string_view bytes) {
  return "data:" + std::string(mime) + ";base64," + base64_encode(bytes.data(), bytes.size());
}

std::string line_chart_svg(const std::string& title, const std::string& x_label,
                           const std::string& y_label, const std::vector<Series>& series) {
  constexpr double kWidth = 640, kHeight = 360, kLeft = 72, kRight = 24, kTop = 40, kBottom = 52;
  const double inf = std::numeric_limits<double>::infinity();
  double xlo = inf, xhi = -inf, ylo = inf, yhi = -inf;
  for (const Series& s : series)
    for (std::size_t k = 0; k < s.x.size(); ++k)
      if (std::isfinite(s.x[k]) && std::isfinite(s.y[k])) {
        xlo = std::min(xlo, s.x[k]);
        xhi = std::max(xhi, s.x[k]);
        ylo = std::min(ylo, s.y[k]);
        yhi = std::max(yhi, s.y[k]);
      }
  const Axis ax = axis_of(xlo, xhi), ay = axis_of(ylo, yhi);
  const double pw = kWidth - kLeft - kRight, ph = kHeight - kTop - kBottom;
  const auto px = [&](double x) { return kLeft + (x - ax.lo) / (ax.hi - ax.lo) * pw; };
  const auto py = [&](double y) { return kTop + (ay.hi - y) / (ay.hi - ay.lo) * ph; };

  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"640\" height=\"360\" "
                    "viewBox=\"0 0 640 360\" font-family=\"sans-serif\" font-size=\"12\">\n"
                    "<rect width=\"640\" height=\"360\" fill=\"white\"/>\n";
  svg += "<text x=\"320\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">" + escape(title) +
         "</text>\n";
  for (int k = 0; ax.lo + k * ax.step <= ax.hi + 1e-9 * ax.step; ++k) {
    const double x = ax.lo + k * ax.step, X = px(x);
    svg += format("<line x1=\"%.1f\" ", X) + format("x2=\"%.1f\" ", X) +
           format("y1=\"%.1f\" ", kTop) + format("y2=\"%.1f\" stroke=\"#ddd\"/>\n", kTop + ph);
    svg += format("<text x=\"%.1f\" ", X) + format("y=\"%.1f\" text-anchor=\"middle\">", kTop + ph + 16) +
           tick_label(ax, x) + "</text>\n";
  }
  for (int k = 0; ay.lo + k * ay.step <= ay.hi + 1e-9 * ay.step; ++k) {
    const double y = ay.lo + k * ay.step, Y = py(y);
    svg += format("<line x1=\"%.1f\" ", kLeft) + format("x2=\"%.1f\" ", kLeft + pw) +
           format("y1=\"%.1f\" ", Y) + format("y2=\"%.1f\" stroke=\"#ddd\"/>\n", Y);
    svg += format("<text x=\"%.1f\" ", kLeft - 6) + format("y=\"%.1f\" text-anchor=\"end\">", Y + 4) +
           tick_label(ay, y) + "</text>\n";
  }
  svg += format("<rect x=\"%.1f\" ", kLeft) + format("y=\"%.1f\" ", kTop) +
         format("width=\"%.1f\" ", pw) + format("height=\"%.1f\" fill=\"none\" stroke=\"#444\"/>\n", ph);
  svg += format("<text x=\"%.1f\" ", kLeft + pw / 2) +
         format("y=\"%.1f\" text-anchor=\"middle\">", kHeight - 12) + escape(x_label) + "</text>\n";
  svg += format("<text transform=\"translate(16 %.1f) rotate(-90)\" text-anchor=\"middle\">",
                kTop + ph / 2) +
         escape(y_label) + "</text>\n";
  for (std::size_t s = 0; s < series.size(); ++s) {
    std::string points;
    for (std::size_t k = 0; k < series[s].x.size(); ++k)
      if (std::isfinite(series[s].x[k]) && std::isfinite(series[s].y[k]))
        points += format("%.1f,", px(series[s].x[k])) + format("%.1f ", py(series[s].y[k]));
    const char* colour = kColours[s % std::size(kColours)];
    svg += "<polyline fill=\"none\" stroke-width=\"2\" stroke=\"" + std::string(colour) +
           "\" points=\"" + points + "\"/>\n";
    if (series.size() > 1) {
      const double Y = kTop + 14 + 16 * s;
      svg += format("<line x1=\"%.1f\" ", kLeft + 10) + format("x2=\"%.1f\" ", kLeft + 34) +
             format("y1=\"%.1f\" ", Y - 4) + format("y2=\"%.1f\" stroke-width=\"2\" ", Y - 4) +
             "stroke=\"" + colour + "\"/>\n";
      svg += format("<text x=\"%.1f\" ", kLeft + 40) + format("y=\"%.1f\">", Y) +
             escape(series[s].label) + "</text>\n";
    }
  }
  return svg + "</svg>\n";
}

}  // namespace runout::html
