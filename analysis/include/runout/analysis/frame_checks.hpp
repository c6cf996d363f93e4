#pragma once
// What makes a particle frame unusable for the analysis, checked the same
// way whoever read it (the VTK filters from a vtkPointSet, `runout analyse`
// from the engine's .vtu): each check returns "" or a sentence naming what
// is wrong, so that a bad frame is refused in the same words everywhere
// instead of being measured from NaNs, or binned into gigabytes.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "runout/analysis/vec2.hpp"
#include "runout/mpm/base.hpp"
#include "runout/mpm/particles.hpp"

namespace runout::analysis {

// The largest double: by default a value need only be finite.
constexpr double kAnyFinite = 1.7976931348623157e308;
// Particle ids are read as 64-bit integers, so they must lie within this.
constexpr double kParticleIdLimit = 9.2e18;

// The first point of xyz (x, y, z per point) with a coordinate that is not
// finite: a NaN or infinity in a position would become an index or a bin.
std::string points_problem(const std::vector<double>& xyz);

// What makes the point array `name`, `values` in tuples of `components`,
// unusable in a frame of `points` points read with `needed` components: a
// tuple count other than the point count, fewer components, or a value
// that is not finite or exceeds `limit` in magnitude.
std::string point_array_problem(const std::string& name, const std::vector<double>& values,
                                int components, std::size_t points, int needed,
                                double limit = kAnyFinite);

// What makes the points too far apart for neighbour searches at `spacing`:
// a bounding box wider than 2^30 spacings, whose cell indices would not fit
// the 32 bits of PointGrid's keys (any real slide is far smaller), or a
// point farther than 10^12 m from the origin, where the base geometry's
// arithmetic would overflow.
std::string extent_problem(const std::vector<Vec2>& points, double spacing);

// What stops the morphology of a frame read into `particles` (x, y, vx, vy,
// mass, x0, y0) with the base and particle spacing it carries (base nullopt:
// none, or none usable): no spacing > 0, no base, points, initial
// positions or base beyond extent_problem, a mass (the point array
// `mass_name`) that is not > 0, or more than 10^6 profile bins of
// bin_spacings spacings over the points or their initial positions (one
// stray point would otherwise cost gigabytes).
std::string morphology_problem(const Particles& particles, const std::optional<Base>& base,
                               double spacing, double bin_spacings,
                               const std::string& mass_name = "mass");

}  // namespace runout::analysis
