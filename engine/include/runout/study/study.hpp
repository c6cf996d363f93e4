#pragma once
// The arithmetic of `runout study` and `runout check --budget` (docs/study.md):
// a run's accuracy metrics from its history.csv, errors against a reference
// (the finest run, or the rigid-block answer), the observed order of
// convergence, the Pareto front of error against cost, and the cost model
// that picks the finest cell size a time budget allows. No processes and no
// files beyond reading history.csv, so each piece is tested on its own.
#include <string>
#include <string_view>
#include <vector>

#include "runout/scene/scene.hpp"

namespace runout::study {

// The history.csv columns the study reads (docs/output.md).
struct History {
  std::vector<double> time, step, toe_velocity, runout, length;
  std::vector<double> runout_95;  // empty where the file has no such column (an older run)
};

// Throws std::runtime_error naming the source and the missing column or the
// bad line.
History parse_history(std::string_view csv, const std::string& source);
History read_history(const std::string& path);

// value(t) interpolated linearly between rows. Past the last row: the last
// value when hold_after_end (a run that stopped at rest keeps its runout),
// NaN otherwise (a run that never got there). NaN for an empty series.
double value_at(const std::vector<double>& time, const std::vector<double>& value, double t,
                bool hold_after_end);

// The accuracy metrics of one run.
struct Metrics {
  std::vector<double> runout_at;  // toe runout at each of the study's times [m]
  double runout_end = 0;          // at the end of the run [m]
  double peak_toe_velocity = 0;   // [m/s]
  double final_length = 0;        // main body length at the end [m]
};

Metrics run_metrics(const History& history, const std::vector<double>& times, bool at_rest);

// |value - reference| / |reference|; NaN when either is NaN or the
// reference is 0 (no scale to measure the error against).
double relative_error(double value, double reference);

// The metrics' relative errors, in the order of Metrics' fields (one per
// time, then end runout, peak toe velocity, final length).
std::vector<double> metric_errors(const Metrics& run, const Metrics& reference);

// A rigid block sliding on a planar base from rest (or its initial
// velocity): the verification answer. Newton's law along the base for the
// block of mass rho A and contact length L_c:
//   frictional (tau):  a = g_t - tau L_c / (rho A)
//   Coulomb (mu):      a = g_t - mu g_n
//   no-slip:           a = 0
// clamped at 0 (a held block stays), so s(t) = v0 t + a t^2 / 2.
struct RigidBlock {
  double acceleration = 0;  // [m/s2]
  double velocity0 = 0;     // initial velocity along the base [m/s]
  double length = 0;        // extent along the base [m]
};
// Throws SceneError when the scene is not one body on a planar base.
RigidBlock rigid_block(const Scene& scene);
// Its metrics at the study's times, for a run ending at end_time.
Metrics rigid_block_metrics(const RigidBlock& block, const std::vector<double>& times,
                            double end_time);

// The scene on a planar slope of angle_deg (the run is in the slope frame,
// so gravity becomes |g| (sin, -cos) of the angle, its magnitude kept),
// recorded in scene.overrides. Throws SceneError for a polyline [base],
// whose points are the bathymetry and so the slope, or an angle outside
// (-90, 90) degrees.
void set_slope_angle(Scene& scene, double angle_deg);

// The exponent p of error = C h^p, fitted by least squares to
// (log h, log error); NaN with fewer than two usable points (finite,
// positive error and h, at least two distinct h).
double observed_order(const std::vector<double>& cell, const std::vector<double>& error);

// Indices of the points no other point beats in both cost and error (one
// at most as good in both and better in one), sorted by cost. Points with
// a non-finite cost or error take no part.
std::vector<int> pareto_front(const std::vector<double>& cost, const std::vector<double>& error);

// The cost model of `runout check --budget`: a calibration at cell h_c
// measured seconds_c for the whole run (its measured throughput times the
// steps and particles the scene needs); particles scale as h^-2 (MPM, 2D)
// or elements as h^-1 (DAM, 1D), and the CFL step as h, so the run's time
// scales as (h_c / h)^(dimension + 1).
struct CostModel {
  double cell = 0;          // h_c [m]
  double seconds = 0;       // estimated whole-run wall time at h_c [s]
  int dimension = 2;        // 2: MPM particles, 1: DAM elements
};
double estimated_seconds(const CostModel& model, double cell);
// The h with estimated_seconds(model, h) = budget.
double finest_cell_for_budget(const CostModel& model, double budget_seconds);

// The slide's size: its extent along x and its mean thickness, the area of
// its bodies over that extent (in the slope frame of a planar scene, the
// length along the base and the mean height above it); and the largest
// sensitivity St of its bodies' clays.
struct SlideSize {
  double length = 0, mean_thickness = 0;
  double sensitivity = 1;
};
SlideSize slide_size(const Scene& scene);

// Which method a budget allows: MPM when its finest affordable cell puts at
// least kResolvingCells across the slide's mean thickness (enough for the
// shear bands and blocks of the mechanism to form over several cells), else
// the depth-averaged model when it can run the scene, the slide is long
// and thin (length / thickness at least kLongAndThin, where depth-averaging
// holds) and its clay is not sensitive (St below kSensitiveClay: a
// sensitive clay fails retrogressively, in blocks and bands that one
// sheared layer cannot follow; on case 4 and the escarpment, St = 40, the
// depth-averaged runout is off the MPM's by a factor of 2.5 to 3.7,
// docs/dam.md), else MPM, under-resolved, with that said.
inline constexpr double kResolvingCells = 10.0, kLongAndThin = 5.0;
// "Sensitive" from St = 4 in Skempton and Northey's (1952) classes.
inline constexpr double kSensitiveClay = 4.0;
struct MethodChoice {
  Method method = Method::Mpm;
  std::string reason;
};
MethodChoice choose_method(double mpm_cell, bool dam_runs, const SlideSize& size);

}  // namespace runout::study
