#include "runout/analysis/morphology_rules.hpp"

#include "runout/analysis/tuples.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace runout::analysis {

namespace {

// Largest (take_max) or smallest value within half_window bins of each bin.
std::vector<double> running_extreme(const std::vector<double>& values, int half_window,
                                    bool take_max) {
  const int n = static_cast<int>(values.size());
  std::vector<double> out(values.size());
  for (int k = 0; k < n; ++k) {
    const auto first = values.begin() + std::max(0, k - half_window);
    const auto last = values.begin() + std::min(n, k + half_window + 1);
    out[k] = take_max ? *std::max_element(first, last) : *std::min_element(first, last);
  }
  return out;
}

// The particles as they were seeded: positions x0, y0, at rest.
runout::Particles initial_configuration(const runout::Particles& p) {
  runout::Particles initial;
  initial.x = p.x0;
  initial.y = p.y0;
  initial.vx.assign(p.x0.size(), 0.0);
  initial.vy.assign(p.x0.size(), 0.0);
  initial.mass = p.mass;
  return initial;
}

// The thickness of the main body's bins [rear_s, toe_s] of a profile of
// kMainBodyBinSpacings spacings, closed over the initial maximum thickness.
std::vector<double> main_body_thickness(const runout::Particles& particles,
                                        const runout::BaseView& base, double spacing,
                                        const runout::SlideMorphology& body,
                                        double initial_max_thickness) {
  const double width = runout::kMainBodyBinSpacings * spacing;
  std::vector<double> thickness;
  for (const runout::ProfileBin& bin : runout::slide_profile(particles, base, width, spacing).bins)
    if (bin.s >= body.rear_s && bin.s <= body.toe_s) thickness.push_back(bin.thickness);
  const int half_window = static_cast<int>(initial_max_thickness / (2.0 * width));
  return close_profile(thickness, half_window);
}

}  // namespace

const char* mechanism_name(Mechanism mechanism) {
  switch (mechanism) {
    case Mechanism::BlockSliding: return "block sliding";
    case Mechanism::Elongation: return "elongation";
    case Mechanism::Spreading: return "spreading";
    case Mechanism::Undetermined: break;
  }
  return "undetermined";
}

std::vector<double> close_profile(const std::vector<double>& values, int half_window) {
  if (half_window <= 0 || values.empty()) return values;
  return running_extreme(running_extreme(values, half_window, true), half_window, false);
}

int count_grabens(const std::vector<double>& thickness, double spacing,
                  double initial_max_thickness) {
  const int n = static_cast<int>(thickness.size());
  const double none = -std::numeric_limits<double>::infinity();
  int grabens = 0;
  for (int k = 1; k + 1 < n; ++k) {
    const double t = thickness[k];
    double rear_flank = none, front_flank = none;
    for (int j = k - 1; j >= 0 && thickness[j] > t; --j)
      rear_flank = std::max(rear_flank, thickness[j]);
    for (int j = k + 1; j < n && thickness[j] >= t; ++j)
      front_flank = std::max(front_flank, thickness[j]);
    const double flank = std::min(rear_flank, front_flank);
    if (flank == none) continue;
    const double depth = flank - t;
    if (depth >= kTroughDepthFraction * flank && depth >= kTroughDepthSpacings * spacing &&
        flank >= kHorstThicknessFraction * initial_max_thickness)
      ++grabens;
  }
  return grabens;
}

Mechanism classify_mechanism(const MechanismEvidence& e) {
  if (!std::isfinite(e.length_ratio) || !std::isfinite(e.thickness_ratio) ||
      !std::isfinite(e.runout_ratio))
    return Mechanism::Undetermined;
  if (e.grabens > e.initial_grabens) return Mechanism::Spreading;
  if (std::isfinite(e.late_stretch)) {
    if (e.runout_ratio < kMovedFraction) return Mechanism::Undetermined;
    return e.late_stretch >= kLateStretch ? Mechanism::Elongation : Mechanism::BlockSliding;
  }
  if (e.length_ratio >= kElongationLengthRatio) return Mechanism::Elongation;
  if (e.thickness_ratio > kBlockThicknessRatio && e.runout_ratio >= kMovedFraction)
    return Mechanism::BlockSliding;
  return Mechanism::Undetermined;
}

double late_stretch(const std::vector<TravelSample>& samples) {
  if (samples.size() < 2 || !(samples.back().runout > 0.0))
    return std::numeric_limits<double>::quiet_NaN();
  const TravelSample now = samples.back();
  const double half = 0.5 * now.runout;
  double length_half = samples.front().length;
  for (std::size_t k = 1; k < samples.size(); ++k) {
    const TravelSample a = samples[k - 1], b = samples[k];
    if (b.runout < half) continue;
    const double f =
        b.runout > a.runout ? std::clamp((half - a.runout) / (b.runout - a.runout), 0.0, 1.0) : 1.0;
    length_half = a.length + f * (b.length - a.length);
    break;
  }
  return (now.length - length_half) / (now.runout - half);
}

runout::Particles morphology_particles(const std::vector<double>& xyz,
                                       const std::vector<double>& velocity, int velocity_components,
                                       const std::vector<double>& mass, int mass_components,
                                       const std::vector<double>& initial, int initial_components) {
  runout::Particles p;
  const auto set = [](runout::StaggeredArray& to, const std::vector<double>& from) {
    to.assign(from.begin(), from.end());
  };
  set(p.x, component_of(xyz, 3, 0));
  set(p.y, component_of(xyz, 3, 1));
  set(p.vx, component_of(velocity, velocity_components, 0));
  set(p.vy, component_of(velocity, velocity_components, 1));
  set(p.mass, component_of(mass, mass_components, 0));
  set(p.x0, component_of(initial, initial_components, 0));
  set(p.y0, component_of(initial, initial_components, 1));
  return p;
}

FrameMorphology measure_frame(const runout::Particles& particles, const runout::BaseView& base,
                              double spacing, double bin_width) {
  FrameMorphology m;
  if (particles.size() == 0) return m;
  const runout::Particles initial = initial_configuration(particles);
  m.now = runout::measure_slide(particles, base, spacing);
  m.initial = runout::measure_slide(initial, base, spacing);
  m.runout = runout::runout_distance(m.now, m.initial.toe_s);
  m.profile = runout::slide_profile(particles, base, bin_width, spacing);

  const double h0 = m.initial.max_thickness;
  m.evidence.length_ratio = m.now.length / m.initial.length;
  m.evidence.thickness_ratio = m.now.max_thickness / h0;
  m.evidence.runout_ratio = m.runout / m.initial.length;
  m.evidence.grabens =
      count_grabens(main_body_thickness(particles, base, spacing, m.now, h0), spacing, h0);
  m.evidence.initial_grabens =
      count_grabens(main_body_thickness(initial, base, spacing, m.initial, h0), spacing, h0);
  m.mechanism = classify_mechanism(m.evidence);
  return m;
}

void classify_by_travel(FrameMorphology& m, const std::vector<TravelSample>& samples) {
  m.evidence.late_stretch = late_stretch(samples);
  m.mechanism = classify_mechanism(m.evidence);
}

}  // namespace runout::analysis
