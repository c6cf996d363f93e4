#pragma once
// The physical parameters of a study (docs/study.md): `--set KEY=V1,V2`
// sweeps, crossed with each other, and `--vary KEY=DISTRIBUTION` drawn
// `--sample N` times (Latin hypercube or Monte Carlo) with `--seed S`. Each
// point is one set of scene settings; the study crosses the points with its
// numerical dimensions.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "runout/scene/scene_settings.hpp"

namespace runout {

// The most runs one study holds (docs/study.md): scene points, and their
// product with the numerical dimensions. A study beyond it is refused
// before anything is sampled, parsed or written.
inline constexpr std::size_t kMaxStudyRuns = 10000;

// Throws SceneError unless `runs` is at most kMaxStudyRuns; `what` says
// which options made them.
void require_study_size(double runs, const std::string& what);

struct StudyParameters {
  std::vector<std::string> keys;                    // --set keys, then --vary keys: CSV columns
  std::vector<std::vector<SceneSetting>> points;    // each the value of every key; one empty point
                                                    // when the study varies no scene key
};

// Throws SceneError naming the option and the key: a malformed --set or
// --vary, a key given twice, --vary without --sample or --sample without
// --vary, a distribution that cannot be sampled, more points than
// kMaxStudyRuns. Whether the scene accepts
// a key and its values is the caller's check (scene_with_settings).
StudyParameters study_parameters(const std::vector<std::string>& set,
                                 const std::vector<std::string>& vary, int samples,
                                 std::uint64_t seed, const std::string& design);

}  // namespace runout
