#include "runout/study/study.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "runout/output/file_text.hpp"
#include "runout/scene/polygon.hpp"
#include "runout/scene/scene_parser.hpp"
#include "../scene/scene_text.hpp"

namespace runout::study {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<std::string> split_commas(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  return cells;
}

int column(const std::vector<std::string>& header, const char* name, const std::string& source) {
  const auto it = std::find(header.begin(), header.end(), name);
  if (it == header.end())
    throw std::runtime_error(source + ": no column '" + name + "' in the header");
  return static_cast<int>(it - header.begin());
}

double number(const std::string& text, const std::string& source, int line) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0')
    throw std::runtime_error(source + ":" + std::to_string(line) + ": '" + text +
                             "' is not a number");
  return v;
}

}  // namespace

History parse_history(std::string_view csv, const std::string& source) {
  std::stringstream in{std::string(csv)};
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error(source + ": empty, no header");
  const std::vector<std::string> header = split_commas(line);
  const int c_time = column(header, "time", source), c_step = column(header, "step", source),
            c_vel = column(header, "toe_velocity", source),
            c_run = column(header, "runout", source), c_len = column(header, "length", source);
  const auto found_95 = std::find(header.begin(), header.end(), "runout_95");
  const int c_run95 = found_95 == header.end() ? -1 : static_cast<int>(found_95 - header.begin());
  History h;
  for (int n = 2; std::getline(in, line); ++n) {
    if (line.empty()) continue;
    const std::vector<std::string> cells = split_commas(line);
    if (cells.size() != header.size())
      throw std::runtime_error(source + ":" + std::to_string(n) + ": " +
                               std::to_string(cells.size()) + " values, the header has " +
                               std::to_string(header.size()));
    h.time.push_back(number(cells[c_time], source, n));
    h.step.push_back(number(cells[c_step], source, n));
    h.toe_velocity.push_back(number(cells[c_vel], source, n));
    h.runout.push_back(number(cells[c_run], source, n));
    h.length.push_back(number(cells[c_len], source, n));
    if (c_run95 >= 0) h.runout_95.push_back(number(cells[c_run95], source, n));
  }
  return h;
}

History read_history(const std::string& path) {
  return parse_history(file_text_or_throw(path, "cannot read '" + path + "'"), path);
}

double value_at(const std::vector<double>& time, const std::vector<double>& value, double t,
                bool hold_after_end) {
  if (time.empty()) return kNaN;
  if (t <= time.front()) return value.front();
  if (t > time.back()) return hold_after_end ? value.back() : kNaN;
  const auto hi = std::lower_bound(time.begin(), time.end(), t);
  const std::size_t k = hi - time.begin();
  const double w = (t - time[k - 1]) / (time[k] - time[k - 1]);
  return value[k - 1] + w * (value[k] - value[k - 1]);
}

Metrics run_metrics(const History& h, const std::vector<double>& times, bool at_rest) {
  Metrics m;
  for (double t : times) m.runout_at.push_back(value_at(h.time, h.runout, t, at_rest));
  if (h.time.empty()) {
    m.runout_end = m.peak_toe_velocity = m.final_length = kNaN;
    return m;
  }
  m.runout_end = h.runout.back();
  m.peak_toe_velocity = *std::max_element(h.toe_velocity.begin(), h.toe_velocity.end());
  m.final_length = h.length.back();
  return m;
}

double relative_error(double value, double reference) {
  if (!std::isfinite(value) || !std::isfinite(reference) || reference == 0) return kNaN;
  return std::abs(value - reference) / std::abs(reference);
}

std::vector<double> metric_errors(const Metrics& run, const Metrics& ref) {
  std::vector<double> e;
  for (std::size_t k = 0; k < run.runout_at.size(); ++k)
    e.push_back(relative_error(run.runout_at[k], ref.runout_at[k]));
  e.push_back(relative_error(run.runout_end, ref.runout_end));
  e.push_back(relative_error(run.peak_toe_velocity, ref.peak_toe_velocity));
  e.push_back(relative_error(run.final_length, ref.final_length));
  return e;
}

RigidBlock rigid_block(const Scene& s) {
  if (s.bodies.size() != 1 || s.base.kind != BaseKind::Planar)
    throw SceneError("the rigid-block reference needs one body on a planar [base]", 0);
  const Polygon& poly = s.bodies[0].polygon;
  const MaterialSpec& mat = s.materials[s.bodies[0].material];
  // Contact length: the polygon's edges lying on the base line y = grid.min.y.
  const double y0 = s.grid.min.y(), tol = 1e-9 * (1.0 + std::abs(y0));
  double contact = 0, lo = poly[0].x(), hi = poly[0].x();
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const Eigen::Vector2d& a = poly[k];
    const Eigen::Vector2d& b = poly[(k + 1) % poly.size()];
    if (std::abs(a.y() - y0) < tol && std::abs(b.y() - y0) < tol) contact += std::abs(b.x() - a.x());
    lo = std::min(lo, a.x());
    hi = std::max(hi, a.x());
  }
  if (contact <= 0) throw SceneError("the rigid-block reference: the body does not lie on the base", 0);
  const double g_t = s.gravity.vector.x(), g_n = -s.gravity.vector.y();
  const double mass = mat.density * signed_area(poly);  // per metre out of plane
  double resistance = 0;                                // per unit mass [m/s2]
  switch (s.base.interface) {
    case InterfaceKind::Frictional: resistance = s.base.shear_strength * contact / mass; break;
    case InterfaceKind::Coulomb: resistance = s.base.friction * g_n; break;
    case InterfaceKind::NoSlip: resistance = std::abs(g_t); break;
  }
  RigidBlock block;
  block.acceleration = std::max(0.0, g_t - resistance);
  block.velocity0 = s.bodies[0].velocity.x();
  block.length = hi - lo;
  return block;
}

Metrics rigid_block_metrics(const RigidBlock& b, const std::vector<double>& times,
                            double end_time) {
  const auto s = [&](double t) { return b.velocity0 * t + 0.5 * b.acceleration * t * t; };
  Metrics m;
  for (double t : times) m.runout_at.push_back(t <= end_time ? s(t) : kNaN);
  m.runout_end = s(end_time);
  m.peak_toe_velocity = b.velocity0 + b.acceleration * end_time;  // a >= 0: largest at the end
  m.final_length = b.length;
  return m;
}

void set_slope_angle(Scene& s, double angle_deg) {
  if (s.base.kind == BaseKind::Polyline)
    throw SceneError("--slope-angle: the scene's [base] is a polyline: its points are the "
                     "bathymetry and so the slope; a slope angle applies to a planar base",
                     0);
  if (!(angle_deg > -90.0 && angle_deg < 90.0))
    throw SceneError("--slope-angle: must be in (-90, 90) degrees (got " +
                         scene_text::format_number(angle_deg) + ")",
                     0);
  s.gravity.slope_angle_deg = angle_deg;
  s.gravity.vector = scene_text::slope_gravity(s.gravity.vector.norm(), angle_deg);
  s.overrides.push_back("gravity.slope_angle = " + scene_text::format_number(angle_deg));
}

double observed_order(const std::vector<double>& cell, const std::vector<double>& error) {
  std::vector<double> x, y;
  for (std::size_t k = 0; k < cell.size() && k < error.size(); ++k)
    if (cell[k] > 0 && error[k] > 0 && std::isfinite(error[k]) && std::isfinite(cell[k])) {
      x.push_back(std::log(cell[k]));
      y.push_back(std::log(error[k]));
    }
  const double n = static_cast<double>(x.size());
  if (x.size() < 2) return kNaN;
  const double mx = std::accumulate(x.begin(), x.end(), 0.0) / n;
  const double my = std::accumulate(y.begin(), y.end(), 0.0) / n;
  double sxy = 0, sxx = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    sxy += (x[k] - mx) * (y[k] - my);
    sxx += (x[k] - mx) * (x[k] - mx);
  }
  return sxx > 0 ? sxy / sxx : kNaN;
}

std::vector<int> pareto_front(const std::vector<double>& cost, const std::vector<double>& error) {
  std::vector<int> usable;
  for (std::size_t k = 0; k < cost.size(); ++k)
    if (std::isfinite(cost[k]) && std::isfinite(error[k])) usable.push_back(static_cast<int>(k));
  // Sorted by cost, then error: a point is on the front when its error is
  // below that of every cheaper (or equally cheap, better) point.
  std::sort(usable.begin(), usable.end(), [&](int a, int b) {
    return cost[a] != cost[b] ? cost[a] < cost[b] : error[a] < error[b];
  });
  std::vector<int> front;
  double best = std::numeric_limits<double>::infinity();
  for (int k : usable)
    if (error[k] < best) {
      front.push_back(k);
      best = error[k];
    }
  return front;
}

double estimated_seconds(const CostModel& m, double cell) {
  return m.seconds * std::pow(m.cell / cell, m.dimension + 1);
}

double finest_cell_for_budget(const CostModel& m, double budget_seconds) {
  return m.cell * std::pow(m.seconds / budget_seconds, 1.0 / (m.dimension + 1));
}

SlideSize slide_size(const Scene& s) {
  double area = 0, lo = std::numeric_limits<double>::infinity(), hi = -lo, sensitivity = 1;
  for (const BodySpec& b : s.bodies) {
    area += signed_area(b.polygon);
    sensitivity = std::max(sensitivity, s.materials[b.material].sensitivity);
    for (const Eigen::Vector2d& p : b.polygon) {
      lo = std::min(lo, p.x());
      hi = std::max(hi, p.x());
    }
  }
  return hi > lo ? SlideSize{hi - lo, area / (hi - lo), sensitivity} : SlideSize{};
}

MethodChoice choose_method(double mpm_cell, bool dam_runs, const SlideSize& size) {
  char buf[400];
  const double cells = size.mean_thickness / mpm_cell;
  const double aspect = size.length / size.mean_thickness;
  if (cells >= kResolvingCells) {
    std::snprintf(buf, sizeof buf,
                  "MPM resolves the slide with %.3g cells across its mean thickness %.3g m "
                  "(%.0f or more let the shear bands and blocks of the mechanism form)",
                  cells, size.mean_thickness, kResolvingCells);
    return {Method::Mpm, buf};
  }
  const bool sensitive = size.sensitivity >= kSensitiveClay;
  if (dam_runs && aspect >= kLongAndThin && !sensitive) {
    std::snprintf(buf, sizeof buf,
                  "MPM would have only %.3g cells across the mean thickness %.3g m (fewer than "
                  "%.0f: the mechanism is not resolved) and the slide is long and thin "
                  "(length / thickness = %.3g), where depth-averaging holds",
                  cells, size.mean_thickness, kResolvingCells, aspect);
    return {Method::Dam, buf};
  }
  char why_not_dam[160];
  if (!dam_runs)
    std::snprintf(why_not_dam, sizeof why_not_dam, "cannot run this scene");
  else if (sensitive)
    std::snprintf(why_not_dam, sizeof why_not_dam,
                  "does not suit a sensitive clay (St = %.3g): it fails in blocks and bands that "
                  "one sheared layer cannot follow",
                  size.sensitivity);
  else
    std::snprintf(why_not_dam, sizeof why_not_dam, "does not suit a slide this short and thick");
  std::snprintf(buf, sizeof buf,
                "MPM, under-resolved: %.3g cells across the mean thickness %.3g m (fewer than "
                "%.0f); the depth-averaged model %s",
                cells, size.mean_thickness, kResolvingCells, why_not_dam);
  return {Method::Mpm, buf};
}

}  // namespace runout::study
