#include "runout/analysis/frame_checks.hpp"

#include <algorithm>
#include <cmath>

#include "runout/measure/morphology.hpp"

namespace runout::analysis {

namespace {

// Profile bins a frame may need: far beyond any slide (a 10 km runout in
// 0.5 m bins is 2e4), well short of exhausting memory (48 B each).
constexpr double kMaxProfileBins = 1e6;

// The farthest a point may lie from the origin, in metres: beyond any
// geographic coordinate (UTM northings stay under 1e7 m), and far enough
// inside the double range that differences and squares of coordinates in
// the base geometry (locate_on_base) stay finite.
constexpr double kMaxReach = 1e12;

double span(const runout::StaggeredArray& x, const runout::StaggeredArray& y) {
  const auto [x_lo, x_hi] = std::minmax_element(x.begin(), x.end());
  const auto [y_lo, y_hi] = std::minmax_element(y.begin(), y.end());
  return std::hypot(*x_hi - *x_lo, *y_hi - *y_lo);
}

// The profile bins of width `width` run along the base over the points,
// now and (for the initial morphology) at their initial positions.
std::string bins_problem(const Particles& p, double width) {
  const double widest = std::max(span(p.x, p.y), span(p.x0, p.y0));
  if (widest / width <= kMaxProfileBins) return "";
  return "The points (or their initial positions) span " + std::to_string(widest) +
         " m, more than 10^6 profile bins of " + std::to_string(width) + " m: a stray point?";
}

// The base's reach against the spacing, as for the points: the profile
// bins run along it.
std::string base_extent_problem(const Base& base, double spacing) {
  const BaseView view = base.view();
  std::vector<Vec2> points{{0.0, view.y0}};
  for (int k = 0; k < view.n; ++k) points.push_back({view.px[k], view.py[k]});
  return extent_problem(points, spacing);
}

std::vector<Vec2> positions(const runout::StaggeredArray& x, const runout::StaggeredArray& y) {
  std::vector<Vec2> points(x.size());
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = {x[i], y[i]};
  return points;
}

}  // namespace

std::string points_problem(const std::vector<double>& xyz) {
  for (std::size_t k = 0; k < xyz.size(); ++k)
    if (!std::isfinite(xyz[k]))
      return "Point " + std::to_string(k / 3) + " has a coordinate that is not a finite number.";
  return "";
}

std::string point_array_problem(const std::string& name, const std::vector<double>& values,
                                int components, std::size_t points, int needed, double limit) {
  const std::string quoted = "The point array \"" + name + "\"";
  const std::size_t tuples = components > 0 ? values.size() / components : 0;
  if (tuples != points)
    return quoted + " has " + std::to_string(tuples) + " tuples for " + std::to_string(points) +
           " points.";
  if (components < needed)
    return quoted + " has " + std::to_string(components) + " component(s), fewer than " +
           std::to_string(needed) + ".";
  for (std::size_t k = 0; k < values.size(); ++k)
    if (!(std::abs(values[k]) <= limit))
      return quoted + " has a value that is not a finite number" +
             (limit < kAnyFinite ? " within +-" + std::to_string(limit) : "") + " at point " +
             std::to_string(k / components) + ".";
  return "";
}

std::string extent_problem(const std::vector<Vec2>& points, double spacing) {
  if (points.empty()) return "";
  Vec2 lo = points[0], hi = points[0];
  for (const Vec2& p : points) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  const double reach = std::max({std::abs(lo.x), std::abs(lo.y), std::abs(hi.x), std::abs(hi.y)});
  if (!(reach <= kMaxReach))
    return "The points reach " + std::to_string(reach) +
           " m from the origin, more than 10^12 m: not a Runout particle frame.";
  if (reach / spacing < 1073741824.0) return "";
  return "The points reach " + std::to_string(reach) + " from the origin, more than 2^30 " +
         "particle spacings of " + std::to_string(spacing) + ": not a Runout particle frame.";
}

std::string morphology_problem(const Particles& particles, const std::optional<Base>& base,
                               double spacing, double bin_spacings, const std::string& mass_name) {
  if (!(spacing > 0 && std::isfinite(spacing)))
    return "The frame has no field data \"particle_spacing\" (h / ppc, > 0): not a Runout "
           "particle frame.";
  if (!base)
    return "The frame has no field data \"base_points\" (the base polyline: at least two "
           "(x, y, 0) points, x strictly increasing): not a Runout particle frame.";
  for (const std::string& problem :
       {extent_problem(positions(particles.x, particles.y), spacing),
        extent_problem(positions(particles.x0, particles.y0), spacing),
        base_extent_problem(*base, spacing)})
    if (!problem.empty()) return problem;
  // measure_slide divides by the masses.
  for (const double m : particles.mass)
    if (!(m > 0 && std::isfinite(m)))
      return "The point array \"" + mass_name + "\" (the mass) must be > 0 everywhere.";
  if (particles.size() == 0) return "";
  return bins_problem(particles, std::min(bin_spacings, kMainBodyBinSpacings) * spacing);
}

}  // namespace runout::analysis
