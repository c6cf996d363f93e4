#pragma once
// Per-tuple views of an array stored as VTK stores it (tuples of
// `components` values, interleaved): how the VTK filters and `runout
// analyse` both turn a frame's arrays into the algorithms' inputs, so that
// both hand them the same doubles.
#include <cmath>
#include <cstddef>
#include <vector>

#include "runout/analysis/vec2.hpp"

namespace runout::analysis {

// Component `component` of every tuple.
inline std::vector<double> component_of(const std::vector<double>& values, int components,
                                        int component) {
  std::vector<double> out(values.size() / components);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = values[i * components + component];
  return out;
}

// The Euclidean norm of every tuple (a displacement's magnitude).
inline std::vector<double> norms_of(const std::vector<double>& values, int components) {
  std::vector<double> out(values.size() / components);
  for (std::size_t i = 0; i < out.size(); ++i) {
    double sum = 0;
    for (int c = 0; c < components; ++c) sum += values[i * components + c] * values[i * components + c];
    out[i] = std::sqrt(sum);
  }
  return out;
}

// The (x, y) of every (x, y, z) point: a run is two-dimensional.
inline std::vector<Vec2> points_of(const std::vector<double>& xyz) {
  std::vector<Vec2> out(xyz.size() / 3);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = {xyz[3 * i], xyz[3 * i + 1]};
  return out;
}

}  // namespace runout::analysis
