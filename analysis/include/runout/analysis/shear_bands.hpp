#pragma once
// Shear bands of one particle frame, on plain arrays: the algorithms behind
// vtkRunoutShearBands, vtkRunoutHorstGraben (which bounds its blocks by
// these bands) and `runout analyse`. docs/filters.md, "Shear bands", states
// the definitions.
#include <vector>

#include "runout/mpm/base.hpp"

#include "runout/analysis/vec2.hpp"

namespace runout::analysis {

enum class ThresholdMode { Absolute = 0, RelativeToReference = 1, Percentile = 2 };

// Which particles are in a band: those whose xi is strictly above a
// threshold, so that a frame without plastic strain has no bands whatever
// the mode.
struct StrainThreshold {
  ThresholdMode mode = ThresholdMode::Percentile;
  double absolute = 1.0;   // Absolute: the threshold itself
  double relative = 1.0;   // RelativeToReference: threshold = relative * reference
  double reference = 1.0;
  double percentile = 90;  // Percentile: threshold = this percentile of xi (nearest rank)
};

double threshold_value(const std::vector<double>& xi, const StrainThreshold& threshold);

struct BandParameters {
  StrainThreshold threshold;
  double spacing = 0;             // particle spacing h (> 0)
  double linking_factor = 1.5;    // linking distance, in h (> 0)
  double orientation_radius = 6;  // radius of a particle's local orientation, in h
  double max_angle = 30;          // degrees; >= 90 links on distance alone
  int min_particles = 10;
  double skeleton_bin = 2;        // skeleton bin width along the axis, in h
};

struct ShearBand {
  std::vector<int> particles;  // indices into the frame
  Vec2 centroid;
  double centroid_s = 0;  // along the base (locate_on_base)
  Vec2 axis;              // principal axis, unit; a . tangent > 0
  double dip = 0;         // degrees in (-90, 90]: angle from the base tangent at the
                          // centroid to the axis, positive when the band descends
                          // towards the base in the direction of increasing s
  double length = 0;      // extent along the axis + h
  double thickness = 0;   // band area (count h^2) / length
  double mean_strain = 0, peak_strain = 0;
  std::vector<Vec2> skeleton;  // mean positions of the bins along the axis, in order
};

// Every band of the frame, ordered by centroid_s (rear to front).
//
// The particles whose xi is above the threshold are linked when they are at
// most linking_factor * h apart. Bands grow from the highest xi down, each
// taking the linked particles whose local orientation (principal axis of
// the selected particles within orientation_radius * h) is within max_angle
// of the band's mean orientation (a particle whose neighbourhood has no
// clear direction goes with any band): bands that meet or cross (the two
// flanks of a wedge, a band rooted in the basal shear zone) come out as
// separate bands instead of one. Bands of fewer than min_particles are
// dropped, their particles left free for later bands.
std::vector<ShearBand> find_shear_bands(const std::vector<Vec2>& points,
                                        const std::vector<double>& xi,
                                        const runout::BaseView& base,
                                        const BandParameters& parameters);

}  // namespace runout::analysis
