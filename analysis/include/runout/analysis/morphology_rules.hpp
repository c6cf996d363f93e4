#pragma once
// The slide's morphology on one frame and its mechanism class, on the
// engine's own types: the algorithms behind vtkRunoutMorphology,
// vtkRunoutMorphologyHistory and `runout analyse` (docs/filters.md, "Runout
// morphology"). The toe, rear, thickness and profile are the engine's
// measure_slide and slide_profile (docs/morphology.md), so they are the
// numbers of the run's history.csv; this file adds the comparison with the
// initial configuration and the mechanism rule.
#include <limits>
#include <vector>

#include "runout/mpm/base.hpp"
#include "runout/measure/morphology.hpp"
#include "runout/mpm/particles.hpp"

namespace runout::analysis {

enum class Mechanism { Undetermined = 0, BlockSliding = 1, Elongation = 2, Spreading = 3 };

// "undetermined", "block sliding", "elongation", "spreading".
const char* mechanism_name(Mechanism mechanism);

// Width of a frame's profile bins along the base, in particle spacings: the
// default of vtkRunoutMorphology's BinSpacings and of `runout analyse
// --bin-spacings` (narrower bins show the gaps between particle columns as
// dips of the profile), and the range both accept.
constexpr double kProfileBinSpacings = 2.0;
constexpr double kMinProfileBinSpacings = 0.25;
constexpr double kMaxProfileBinSpacings = 1000.0;

// Thresholds of the rule; docs/filters.md gives the reasons.
constexpr double kElongationLengthRatio = 1.15;   // L / L0 from which the slide has lengthened
constexpr double kBlockThicknessRatio = 0.8;      // Hmax / H0 above which it kept its height
constexpr double kMovedFraction = 0.1;            // runout / L0 from which it has moved
constexpr double kTroughDepthFraction = 0.2;      // trough depth / its lower flank
constexpr double kTroughDepthSpacings = 2.0;      // trough depth, in particle spacings
constexpr double kHorstThicknessFraction = 0.5;   // flank thickness / H0 of a horst
constexpr double kLateStretch = 0.5;              // dL / dR over an elongation's late travel

// Morphological closing of a profile: the largest value within half_window
// bins, then the smallest of those within half_window bins. It fills every
// trough narrower than 2 half_window + 1 bins and leaves wider ones as they
// are.
std::vector<double> close_profile(const std::vector<double>& values, int half_window);

// Grabens in a thickness profile (rear to front), counted once each. A bin
// is the bottom of a trough when, going rearwards until a bin at most as
// thick and frontwards until a bin thinner (so that a flat or repeated
// bottom counts once), both sides hold a thicker flank; with F the lower of
// the two flanks' largest thickness and t the bin's, it is a graben when
//   F - t >= kTroughDepthFraction F,  F - t >= kTroughDepthSpacings spacing
//   and F >= kHorstThicknessFraction initial_max_thickness
// (both flanks are horsts: blocks that kept at least half the initial
// height). Call it on a closed profile, or particle-scale gaps count.
int count_grabens(const std::vector<double>& thickness, double spacing,
                  double initial_max_thickness);

// What the rule compares; the ratios are against the initial configuration.
struct MechanismEvidence {
  double length_ratio = 0;     // L / L0
  double thickness_ratio = 0;  // Hmax / H0
  double runout_ratio = 0;     // runout / L0
  int grabens = 0;
  int initial_grabens = 0;
  double late_stretch = std::numeric_limits<double>::quiet_NaN();  // NaN: no series
};

// In this order: spreading when grabens have formed since t = 0 (more than
// initially); then, where the frame's series gives the late stretch, for a
// slide moved by runout / L0 >= kMovedFraction: elongation when it is at
// least kLateStretch, block sliding below; without it (one frame alone):
// elongation when L / L0 >= kElongationLengthRatio, block sliding when
// Hmax / H0 > kBlockThicknessRatio and runout / L0 >= kMovedFraction;
// undetermined otherwise, and for non-finite ratios.
Mechanism classify_mechanism(const MechanismEvidence& evidence);

// The slide's runout and main-body length at one time of its series.
struct TravelSample {
  double runout = 0;
  double length = 0;
};

// How much of the toe's late travel went into lengthening the slide rather
// than carrying its rear: (L_now - L_half) / (R_now / 2) over the second
// half of the runout so far, L_half interpolated where the runout first
// reached R_now / 2; samples in time order, the last one now. About 0 for
// a block that slides on after its faces slumped, about 1 for a slide
// whose rear stays while its front runs on. NaN with fewer than two
// samples or no runout yet.
double late_stretch(const std::vector<TravelSample>& samples);

struct FrameMorphology {
  runout::SlideMorphology now;      // the frame
  runout::SlideMorphology initial;  // the initial configuration (x0, y0)
  double runout = 0;                // now.toe_s - initial.toe_s
  runout::Profile profile;          // all particles, in the requested bins
  MechanismEvidence evidence;
  Mechanism mechanism = Mechanism::Undetermined;
};

// The particles measure_frame reads (x, y, vx, vy, mass, x0, y0) from a
// frame's arrays as VTK stores them: its points (x, y, z per point), and its
// velocity, mass and initial position with their components per tuple.
runout::Particles morphology_particles(const std::vector<double>& xyz,
                                       const std::vector<double>& velocity, int velocity_components,
                                       const std::vector<double>& mass, int mass_components,
                                       const std::vector<double>& initial, int initial_components);

// The frame's morphology. particles: the frame, with x0 and y0 the initial
// position of each particle (the t = 0 configuration, which the engine
// writes in every frame); spacing: h / ppc (> 0); bin_width: the profile's
// bins (> 0). The grabens are counted on the main body's part of a profile
// of kMainBodyBinSpacings spacings whatever bin_width, closed over the
// initial maximum thickness H0: bands crossing a slide at 45 to 60 degrees
// bound blocks about as wide as it is thick, so a narrower trough is a
// crack or particle-scale noise, not a graben. No particles: all zero,
// undetermined.
FrameMorphology measure_frame(const runout::Particles& particles, const runout::BaseView& base,
                              double spacing, double bin_width);

// m classified again with the late stretch of its series (`samples`, in
// time order, ending with m's own runout and length).
void classify_by_travel(FrameMorphology& m, const std::vector<TravelSample>& samples);

}  // namespace runout::analysis
