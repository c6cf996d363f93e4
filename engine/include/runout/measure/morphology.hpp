#pragma once
// The slide's shape and motion from its particles, measured along the rigid
// base (docs/morphology.md). Every position is in base coordinates from
// locate_on_base: s along the base (x on a planar base, arc length on a
// polyline) and d above it. Pure functions of the particle state; sums run
// in particle order, so the results are the same run after run.
//
// Main body. The particles are binned by s into bins of width
// kMainBodyBinSpacings * spacing, the first centred on the rear-most
// particle. A bin
// is occupied when it holds at least one particle. Occupied bins separated
// by at most kMainBodyGapBins empty bins belong to the same run; the main
// body is the run holding the largest mass (the rear-most of equally heavy
// runs). With bin width w, two particles whose s differ by less than
// (kMainBodyGapBins + 1) w (6 spacings) are always in one run, and two with
// nothing between them are never when they differ by
// (kMainBodyGapBins + 2) w (8 spacings) or more: stray particles and
// out-runner blocks beyond such a gap are left out of every main-body
// quantity and show up in SlideMorphology::outside_mass instead.
#include <string>
#include <vector>

#include "runout/mpm/base.hpp"
#include "runout/mpm/particles.hpp"

namespace runout {

constexpr double kMainBodyBinSpacings = 2.0;  // main-body bin width, in particle spacings
constexpr int kMainBodyGapBins = 2;           // empty bins a run bridges
constexpr double kToeWindowSpacings = 2.0;    // depth of the toe-velocity window, in spacings
constexpr double kMassFrontFraction = 0.95;   // the mass front's share of the mass behind it

// The base at along-base coordinate s: its point, unit tangent (towards
// increasing s) and outward unit normal (the tangent turned +90 degrees).
// A polyline (at least two points) is extended beyond its ends along its
// first and last segments, as locate_on_base does; at an interior vertex the
// segment that starts there is used.
struct BaseFrame {
  double x, y;
  double tx, ty;
  double nx, ny;
};
BaseFrame base_frame_at(const BaseView& base, double s);

struct SlideMorphology {
  // Main body. Toe and rear are the particles' outer edges: the front-most
  // (rear-most) particle's s plus (minus) half a spacing, like the thickness.
  int particles = 0;          // number of particles in the main body
  double toe_s = 0;           // [m] front
  double rear_s = 0;          // [m] rear
  double length = 0;          // [m] toe_s - rear_s
  double centroid_x = 0, centroid_y = 0;  // [m] mass-weighted, run frame
  double centroid_s = 0;                  // [m] mass-weighted s
  double centroid_vx = 0, centroid_vy = 0;  // [m/s] mass-weighted velocity
  double centroid_velocity_s = 0;  // [m/s] its component along the base tangent at centroid_s
  // [m/s] mass-weighted along-base velocity of the main-body particles whose
  // centre lies within kToeWindowSpacings spacings of the toe (the two front
  // columns of a regular lattice): one particle's velocity is too noisy.
  double toe_velocity = 0;
  double max_thickness = 0;   // [m] largest d + spacing / 2: the profile's largest thickness
  double outside_mass = 0;    // [kg/m] mass of all particles not in the main body
  // All particles:
  // [m] the mass front: the s of the first particle, in order of s, at which
  // the mass from the rear reaches kMassFrontFraction of the whole. Blocks
  // that break away count with their mass, so the front does not jump when
  // one parts, as the main body's toe does.
  double mass_front_s = 0;
  // [m/s] the blocks' bulk speed: sqrt(sum_b m_b u_b^2 / M) over the
  // blocks b (the runs of occupied bins that the main body is chosen from,
  // the main body one of them), u_b a block's mass-weighted mean velocity
  // along the base. A block that runs on after the main body has stopped
  // shows in it; noise inside a block, which carries no mean momentum,
  // does not.
  double block_speed = 0;
  double max_speed = 0;       // [m/s]
  double kinetic_energy = 0;  // [J/m]
};

// spacing: the particle spacing h / ppc (> 0). Particle masses must be > 0.
// No particles: all zero.
SlideMorphology measure_slide(const Particles& particles, const BaseView& base, double spacing);

// Runout distance: how far the toe has moved along the base since t = 0.
double runout_distance(const SlideMorphology& now, double initial_toe_s);

struct ProfileBin {
  double s = 0;           // [m] bin centre
  int particles = 0;
  double thickness = 0;   // [m] largest d in the bin + spacing / 2; 0 when empty
  double x_surface = 0, y_surface = 0;  // [m] the base point at s moved thickness along the normal
  double velocity_s = 0;  // [m/s] mass-weighted along-base velocity; 0 when empty
};

struct Profile {
  double bin_width = 0;  // [m]
  std::vector<ProfileBin> bins;  // rear to front
};

// Troughs of the thickness profile narrower than about twice this many bins
// are filled (a morphological closing): they are gaps between particle
// columns that have moved apart, not the slide's surface.
constexpr int kProfileClosingBins = 2;

// Thickness profile of all particles, in bins of bin_width (> 0) along the
// base, the first centred on the rear-most particle's s, the last holding
// the front-most one. spacing: the particle spacing h / ppc (> 0). No
// particles: no bins. A bin's thickness is the highest particle above the
// base plus half a spacing, closed over kProfileClosingBins; a wider gap
// keeps thickness 0.
Profile slide_profile(const Particles& particles, const BaseView& base, double bin_width,
                      double spacing);

// CSV: "# time = <t>", then "s,x_surface,y_surface,thickness,particles,velocity_s"
// and one row per bin; written atomically (write_file_atomically).
void write_profile_csv(const std::string& path, double time, const Profile& profile);

}  // namespace runout
