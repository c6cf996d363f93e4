#pragma once
// The CPU (OpenMP) driver of the explicit MPM step: it owns the particles,
// the grid box and the scratch, and calls the stage functions of stages.hpp
// in order. Particle-to-grid is scattered by block colouring, so it is
// race-free and gives the same sums in the same order whatever the number
// of threads.
#include <stdexcept>
#include <string>
#include <vector>

#include "runout/base.hpp"
#include "runout/grid.hpp"
#include "runout/guards.hpp"
#include "runout/material.hpp"
#include "runout/nonlocal.hpp"
#include "runout/particles.hpp"
#include "runout/scene.hpp"
#include "runout/stages.hpp"

namespace runout {

// A step produced non-finite values, lost a particle from the domain, sped
// one past any physical speed or inverted or collapsed its volume (guards.hpp).
// The state is then unusable; what was written before stays good.
class NumericalFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A driver's state besides its particles: with the particles in their
// memory order, enough to continue a run bit for bit (checkpoint.hpp).
struct StepCounters {
  double time = 0;
  long steps = 0;
  double last_dt = 0;
  double basal_shear_force = 0;
  double max_signal_speed = 0;  // sets the next stable_dt
  double speed_limit = 0;       // GuardLimits::max_speed, fixed by the first particles
};

class Simulation {
 public:
  explicit Simulation(const Scene& scene);              // seeds the bodies
  Simulation(const Scene& scene, Particles particles);  // given particles
  // Moves keep the base's arrays (and so the views into them) in place.
  Simulation(Simulation&&) = default;
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  // dt = C h / max_p (c_p + |v_p|) from the current state.
  double stable_dt() const { return courant_ * h_ / max_signal_speed_; }
  // One step of size dt. Throws NumericalFailure.
  void step(double dt);
  // Steps with the CFL dt, shortening the last one to land on t exactly.
  void advance_to(double t);

  // The counters, and a driver that continues from them (its particles
  // given to the constructor in the memory order they had).
  StepCounters counters() const;
  void restore(const StepCounters& counters);

  double time() const { return time_; }
  long steps() const { return steps_; }
  double last_dt() const { return last_dt_; }
  // Tangential force of the base on the slide along +s in the last step
  // [N per metre out of plane]; negative while it resists.
  double basal_shear_force() const { return basal_shear_force_; }
  const Base& base() const { return base_; }
  double particle_spacing() const { return spacing_; }  // h / ppc
  const std::vector<MaterialParams>& materials() const { return materials_; }
  Particles& particles() { return particles_; }
  const Particles& particles() const { return particles_; }
  const Grid& grid() const { return grid_; }
  const StepConfig& config() const { return config_; }
  const GuardLimits& limits() const { return limits_; }

 private:
  void fit_grid(double dt);
  void bin_particles();  // and computes the particles' stencils
  template <class Stage>
  void scatter(Stage&& stage);
  // Volume-weighted mean of value(p) over the particles of each grid cell,
  // into cell_mean_.
  template <class Value>
  void cell_means(Value&& value);
  void xpic_start_velocity();
  void smooth_volumetric_rates();
  void smooth_mean_stress();
  // Replaces the step's increment of xi by its nonlocal average
  // (nonlocal.hpp) and sets su to match, for materials with a length.
  void regularise_softening();

  Particles particles_;
  Base base_;
  Grid grid_;
  StepConfig config_;
  std::vector<MaterialParams> materials_;
  GuardLimits limits_;
  std::vector<double> scratch_dx_, scratch_dy_;
  std::vector<Stencil2D> stencils_;
  std::vector<VelocityGradient> gradients_;
  std::vector<double> cell_volume_, cell_mean_;  // per cell of the grid box
  NonlocalAverage nonlocal_;
  std::vector<double> xi_start_, dxi_local_, dxi_average_;  // per particle, nonlocal runs
  // Particles grouped by block of kBlock x kBlock cells (counting sort).
  std::vector<int> block_start_, order_, particle_block_, particle_cell_, scratch_next_;
  int blocks_x_ = 0, blocks_y_ = 0;
  Eigen::Vector2d domain_min_, domain_max_;
  double h_, courant_, spacing_;
  bool smooth_volumetric_;
  double max_signal_speed_ = 0;
  double time_ = 0, last_dt_ = 0, basal_shear_force_ = 0;
  long steps_ = 0;
};

}  // namespace runout
