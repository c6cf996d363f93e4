#include "study_parameters.hpp"

#include <algorithm>
#include <cstdio>
#include <string>

#include "runout/study/sampling.hpp"
#include "runout/scene/scene_parser.hpp"

namespace runout {
namespace {

void add_key(StudyParameters& p, const std::string& option, const std::string& key) {
  if (std::find(p.keys.begin(), p.keys.end(), key) != p.keys.end())
    throw SceneError(option + " " + key + ": the key is varied twice", 0);
  p.keys.push_back(key);
}

// Ten significant digits: the scene gets exactly the value its CSV row shows.
std::string value_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

}  // namespace

void require_study_size(double runs, const std::string& what) {
  if (runs <= static_cast<double>(kMaxStudyRuns)) return;
  char count[32];
  std::snprintf(count, sizeof count, "%.0f", runs);
  throw SceneError(what + ": " + count + " runs, more than a study holds (" +
                       std::to_string(kMaxStudyRuns) + "); split it into smaller studies",
                   0);
}

StudyParameters study_parameters(const std::vector<std::string>& set,
                                 const std::vector<std::string>& vary, int samples,
                                 std::uint64_t seed, const std::string& design) {
  StudyParameters p;
  p.points.emplace_back();
  for (const std::string& text : set) {  // the grid: each key's values crossed with the others'
    const auto [key, values] = parse_setting_list(text);
    add_key(p, "--set", key);
    require_study_size(double(p.points.size()) * double(values.size()), "--set");
    std::vector<std::vector<SceneSetting>> crossed;
    for (const auto& point : p.points)
      for (const std::string& v : values) {
        crossed.push_back(point);
        crossed.back().push_back({key, v});
      }
    p.points = std::move(crossed);
  }
  if (vary.empty() != (samples == 0))
    throw SceneError(vary.empty() ? "--sample: no --vary KEY=DISTRIBUTION to sample"
                                  : "--vary: give the number of samples with --sample N",
                     0);
  if (vary.empty()) return p;
  require_study_size(double(p.points.size()) * samples, "--sample");
  std::vector<std::pair<std::string, sampling::Distribution>> dists;
  for (const std::string& text : vary) {
    const std::size_t eq = text.find('=');
    if (eq == std::string::npos || eq == 0)
      throw SceneError("--vary " + text + ": expected KEY=DISTRIBUTION", 0);
    const std::string key = text.substr(0, eq);
    add_key(p, "--vary", key);
    dists.emplace_back(key, sampling::parse_distribution(key, text.substr(eq + 1)));
  }
  const auto u = sampling::unit_design(
      samples, static_cast<int>(dists.size()), seed,
      design == "mc" ? sampling::Design::MonteCarlo : sampling::Design::LatinHypercube);
  // Every grid point with every sample: the samples are the same at each.
  std::vector<std::vector<SceneSetting>> crossed;
  for (const auto& point : p.points)
    for (const std::vector<double>& draw : u) {
      crossed.push_back(point);
      for (std::size_t j = 0; j < dists.size(); ++j)
        crossed.back().push_back(
            {dists[j].first, value_text(sampling::quantile(dists[j].second, draw[j]))});
    }
  p.points = std::move(crossed);
  return p;
}

}  // namespace runout
