#pragma once
// The explicit MPM step, written once (docs/engine.md, "One driver"): the
// order of the stages of stages.hpp, the volumetric smoothing, the nonlocal
// averaging, the guards, the counters and advance_to, over a backend that
// says only how to run a loop: the concept Backend of backend_concept.hpp,
// each primitive there with a line on what it does.
//
// The CPU backend (backend_openmp.hpp) runs the loops with OpenMP and
// scatters by block colouring, race-free and in a fixed order; the CUDA
// backend (engine/cuda/backend_cuda.cuh) runs one thread per particle or
// node and scatters with atomics; the serial device backend
// (backend_serial.hpp) runs the CUDA backend's order on the CPU (a sort by
// cell, stencils computed in each pass, scatters in particle order without
// colouring), so that the code the GPU runs is tested where no GPU is.
// The stage functors below are the kernels' bodies: plain structs with a
// host-and-device call operator, so nvcc and g++ compile the same ones.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "runout/mpm/backend_concept.hpp"
#include "runout/mpm/base.hpp"
#include "runout/mpm/grid.hpp"
#include "runout/mpm/guards.hpp"
#include "runout/mpm/material.hpp"
#include "runout/scene/materials.hpp"
#include "runout/mpm/nonlocal.hpp"
#include "runout/mpm/particles.hpp"
#include "runout/scene/scene.hpp"
#include "runout/scene/scene_quantities.hpp"
#include "runout/mpm/stages.hpp"
#include "runout/mpm/step_views.hpp"

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

// The scene's step configuration (step_config.cpp).
StepConfig make_step_config(const Scene& scene, const std::vector<MaterialParams>& materials);

namespace stage {

struct P2g {
  ParticleView P;
  GridView g;
  StepConfig c;
  const MaterialParams* mats;
  template <class St, class Add, class Lower>
  RUNOUT_HD void operator()(int p, const St& st, Add add, Lower lower) const {
    p2g(P, p, st, g, c, mats, add, lower);
  }
  // Whether the stage reads the stencil's derivatives (st.d): a backend
  // that makes stencils in each pass may leave them out where not.
  RUNOUT_HD bool derivatives() const { return true; }
};
struct GridUpdate {
  GridView g;
  StepConfig c;
  double dt;
  RUNOUT_HD void operator()(int n) const { grid_update(g, n, c, dt); }
};
struct ExchangeRow {
  GridView g;
  Exchange after;
  RUNOUT_HD void operator()(int j) const { exchange_periodic(g, j, after); }
};
struct XpicStart {
  GridView g;
  StepConfig c;
  RUNOUT_HD void operator()(int n) const { xpic_start(g, n, c); }
};
struct P2gSmoothed {
  ParticleView P;
  GridView g;
  template <class St, class Add, class Lower>
  RUNOUT_HD void operator()(int p, const St& st, Add add, Lower) const {
    p2g_smoothed(P, p, st, g, add);
  }
  RUNOUT_HD bool derivatives() const { return false; }
};
struct XpicTerm {
  GridView g;
  StepConfig c;
  int k;
  RUNOUT_HD void operator()(int n) const { xpic_term(g, n, c, k); }
};
// g2p reads only nodal velocities, so each particle's remap can follow it
// in the same pass.
struct G2pMomentum {
  ParticleView P;
  GridView g;
  StepConfig c;
  const MaterialParams* mats;
  double dt;
  template <class St, class Add, class Lower>
  RUNOUT_HD void operator()(int p, const St& st, Add add, Lower) const {
    g2p(P, p, st, g, c);
    if (c.clay_band) band_softening(P, p, st, g, c, mats, dt);
    p2g_momentum(P, p, st, g, c, add);
  }
  // APIC's g2p takes the cell gradient where its D is degenerate.
  RUNOUT_HD bool derivatives() const { return c.transfer == TransferKind::Apic; }
};
struct Remap {
  GridView g;
  StepConfig c;
  double dt;
  RUNOUT_HD void operator()(int n) const { remap_velocity(g, n, c, dt); }
};
struct Gradient {
  GridView g;
  double dt;
  StepScratch s;
  GradientView L;
  template <class St>
  RUNOUT_HD void operator()(int p, const St& st) const {
    L.store(p, velocity_gradient(st, g));
    displacement(p, st, g, dt, s);
  }
};
struct VolumetricRate {
  GradientView L;
  RUNOUT_HD double operator()(int p) const { return L.xx[L.at(p)] + L.yy[L.at(p)]; }
};
// The particle's signal speed, or -1 where it fails a guard. With
// volumetric smoothing (rate.mean set), L's volumetric part is first its
// cell's mean.
struct Stress {
  ParticleView P;
  GradientView L;
  CellMeanView rate;
  const MaterialParams* mats;
  double dt;
  StepScratch s;
  StepConfig c;
  GuardLimits limits;
  RUNOUT_HD double operator()(int p) const {
    VelocityGradient l = L.load(p);
    if (rate.mean) set_volumetric_rate(l, rate(p));
    const double speed = stress_update(P, p, l, mats, dt, s);
    return checked(p, speed);
  }
  // Particles p .. p + 3 at once (stress_update_x4) into speeds, where they
  // share a material; false, and nothing done, where they do not.
  bool four(int p, double speeds[4]) const {
    const int m = P.material[p];
    if (P.material[p + 1] != m || P.material[p + 2] != m || P.material[p + 3] != m) return false;
    const int i = L.at(p);
    Lanes xx = load_lanes(L.xx + i), yy = load_lanes(L.yy + i);
    if (rate.mean) {
      const double trace[4] = {rate(p), rate(p + 1), rate(p + 2), rate(p + 3)};
      set_volumetric_rate(xx, yy, load_lanes(trace));
    }
    store_lanes(speeds, stress_update_x4(P, p, xx, load_lanes(L.xy + i), load_lanes(L.yx + i), yy,
                                         mats[m], dt, s));
    if (c.period > 0.0 || !no_fault_x4(P, p, limits))
      for (int k = 0; k < 4; ++k) speeds[k] = checked(p + k, speeds[k]);
    return true;
  }
  // After the update: the move across a periodic seam, and the guards.
  RUNOUT_HD double checked(int p, double speed) const {
    wrap_periodic(P, p, c);
    return particle_fault(P, p, limits) == Fault::None ? speed : -1.0;
  }
};
struct MeanStress {
  ParticleView P;
  RUNOUT_HD double operator()(int p) const { return (P.sxx[p] + P.syy[p] + P.szz[p]) / 3.0; }
};
struct SetMeanStress {
  ParticleView P;
  CellMeanView mean;
  RUNOUT_HD void operator()(int p) const {
    const double shift = mean(p) - (P.sxx[p] + P.syy[p] + P.szz[p]) / 3.0;
    P.sxx[p] += shift;
    P.syy[p] += shift;
    P.szz[p] += shift;
  }
};
struct CopyXi {
  ParticleView P;
  double* to;
  RUNOUT_HD void operator()(int p) const { to[p] = P.xi[p]; }
};
struct XiIncrement {
  ParticleView P;
  const double* start;
  double* increment;
  RUNOUT_HD void operator()(int p) const { increment[p] = P.xi[p] - start[p]; }
};
// The regularised increment replaces the local one; its rate is the one
// the next step's strength takes (StrengthParams::regularised), and su
// follows both. A particle that neither yields (average 0: its local
// increment, and so its change of xi, was 0) nor had a rate keeps the su
// its stress update gave it at that xi and rate 0: most particles of a
// slide, whose exp this spares.
struct SetNonlocalXi {
  ParticleView P;
  const double* start;
  const double* average;
  const double* lengths;  // per material
  const MaterialParams* mats;
  double dt;
  RUNOUT_HD void operator()(int p) const {
    if (lengths[P.material[p]] <= 0.0) return;
    if (average[p] == 0.0 && P.gamma_dot[p] == 0.0) return;
    P.xi[p] = start[p] + average[p];
    P.gamma_dot[p] = average[p] / dt;
    P.su[p] = strength(mats[P.material[p]].strength, P.xi[p], P.gamma_dot[p]);
  }
};

}  // namespace stage

template <Backend B>
class Driver {
 public:
  Driver(const Scene& scene, Particles particles);
  Driver(Driver&&) = default;
  Driver(const Driver&) = delete;
  Driver& operator=(const Driver&) = delete;

  // dt = C h / max_p (c_p + |v_p|) from the current state.
  double stable_dt() const { return courant_ * h_ / max_signal_speed_; }
  // One step of size dt. Throws NumericalFailure.
  void step(double dt);
  // Steps with the CFL dt, shortening the last one to land on t exactly.
  void advance_to(double t);

  // The counters, and a driver that continues from them (its particles
  // given to the constructor in the memory order they had).
  StepCounters counters() const {
    return StepCounters{time_, steps_, last_dt_, basal_shear_force_, max_signal_speed_,
                        limits_.max_speed};
  }
  void restore(const StepCounters& c);

  double time() const { return time_; }
  long steps() const { return steps_; }
  double last_dt() const { return last_dt_; }
  // Tangential force of the base on the slide along +s in the last step
  // [N per metre out of plane]; negative while it resists.
  double basal_shear_force() const { return basal_shear_force_; }
  const Base& base() const { return base_; }
  double particle_spacing() const { return spacing_; }  // h / ppc
  const std::vector<MaterialParams>& materials() const { return materials_; }
  const StepConfig& config() const { return config_; }  // its base view on the host
  const GuardLimits& limits() const { return limits_; }
  B& backend() { return backend_; }
  const B& backend() const { return backend_; }

 private:
  void fit_grid(double dt);
  void exchange(Exchange after);
  void xpic_start_velocity(const StepConfig& c);
  void regularise_softening(double dt);
  [[noreturn]] void fail(double dt);

  Base base_;
  std::vector<MaterialParams> materials_;
  StepConfig config_;
  NonlocalAverage nonlocal_;
  std::vector<double> nonlocal_lengths_;
  GuardLimits limits_;
  double max_signal_speed_ = 0;
  B backend_;
  GridView grid_{};
  double domain_x_, domain_y_, h_, courant_, spacing_;
  bool smooth_volumetric_;
  double time_ = 0, last_dt_ = 0, basal_shear_force_ = 0;
  long steps_ = 0;
};

// ---- Implementation -------------------------------------------------------

namespace driver_detail {

// Per material, l and t_s of regularised softening (nonlocal.hpp); l is
// kRegularisationCells cells unless the scene sets it.
inline std::vector<Regularisation> regularisations(const Scene& s) {
  std::vector<Regularisation> out;
  for (const auto& m : s.materials) {
    Regularisation r;
    if (m.model == MaterialModel::Tresca && m.band_thickness > 0.0) {
      r.band_thickness = m.band_thickness;
      r.length = m.nonlocal_length > 0.0 ? m.nonlocal_length
                                         : kRegularisationCells * s.grid.cell_size;
    }
    out.push_back(r);
  }
  return out;
}
// The base's images enter the average where the base is no-slip: the
// clay's shear gathers in a band along it (nonlocal.hpp). The period is
// the step's (0: not periodic).
inline NonlocalAverage nonlocal_average(const Scene& s, const StepConfig& c, const Base& base) {
  const BaseView mirror = s.base.kind != BaseKind::None && s.base.interface == InterfaceKind::NoSlip
                              ? base.view()
                              : BaseView{};
  return NonlocalAverage(regularisations(s), c.period, c.domain_x0, mirror);
}

// The driver's own particles, before the backend takes them: view() needs
// a mutable owner, and a copy of every particle would cost start-up.
inline double first_signal_speed(Particles& particles,
                                 const std::vector<MaterialParams>& materials) {
  const ParticleView P = particles.view();
  double smax = 0;
  for (int p = 0; p < P.n; ++p) smax = std::max(smax, cfl_speed(P, p, materials[P.material[p]]));
  return smax;
}

// A cell group's pass, and its cells' volume-weighted means of mean_of:
// taken in the same pass where the group offers it (MeansInPasses, the
// CPU's), else in a loop of their own after it (cell_means).
template <class Cells, class Stage, class Value>
CellMeanView stencil_pass_and_means(Cells& cells, const GridView& g, const StepConfig& c,
                                    const Stage& stage, const Value& mean_of) {
  if constexpr (MeansInPasses<Cells>) {
    return cells.for_each_particle_stencil(g, c, stage, mean_of);
  } else {
    cells.for_each_particle_stencil(g, c, stage);
    return cells.cell_means(g, mean_of);
  }
}
template <class Cells, class Stage, class Value>
SpeedMax max_speed_and_means(Cells& cells, const GridView& g, const Stage& stage,
                             const Value& mean_of, CellMeanView& means) {
  if constexpr (MeansInPasses<Cells>) {
    return cells.max_speed(stage, mean_of, means);
  } else {
    const SpeedMax speed = cells.max_speed(stage);
    means = cells.cell_means(g, mean_of);
    return speed;
  }
}

}  // namespace driver_detail

template <Backend B>
Driver<B>::Driver(const Scene& scene, Particles particles)
    : base_(scene.base, scene.grid.min.y()),
      materials_(make_materials(scene)),
      config_(make_step_config(scene, materials_)),
      nonlocal_(driver_detail::nonlocal_average(scene, config_, base_)),
      nonlocal_lengths_(nonlocal_.lengths()),
      limits_(guard_limits(scene, materials_, particles)),
      max_signal_speed_(driver_detail::first_signal_speed(particles, materials_)),
      backend_(std::move(particles), materials_, base_, nonlocal_lengths_),
      domain_x_(scene.grid.min.x()),
      domain_y_(scene.grid.min.y()),
      h_(scene.grid.cell_size),
      courant_(scene.time.courant),
      spacing_(runout::particle_spacing(scene)),
      smooth_volumetric_(scene.solver.volumetric_smoothing) {
  config_.base = base_.view();
}

template <Backend B>
void Driver<B>::restore(const StepCounters& c) {
  time_ = c.time;
  steps_ = c.steps;
  last_dt_ = c.last_dt;
  basal_shear_force_ = c.basal_shear_force;
  max_signal_speed_ = c.max_signal_speed;
  limits_.max_speed = c.speed_limit;
}

template <Backend B>
void Driver<B>::fail(double dt) {
  throw NumericalFailure(describe_faults(backend_.host_particles(), limits_, steps_, time_, dt));
}

template <Backend B>
void Driver<B>::fit_grid(double dt) {
  ParticleBox b = backend_.bounding_box();
  // The end of every step checks the particles; this catches particles
  // given (or changed between steps) outside the domain before they index
  // the grid.
  const GuardLimits& g = limits_;
  if (b.non_finite > 0 ||
      !(b.xmin >= g.xmin && b.ymin >= g.ymin && b.xmax <= g.xmax && b.ymax <= g.ymax))
    fail(dt);
  if (config_.period > 0.0) periodic_span(config_, h_, b.xmin, b.xmax);
  GridView placed;
  place_box(placed, b.xmin, b.xmax, b.ymin, b.ymax, domain_x_, domain_y_, h_);
  grid_ = backend_.fit_grid(placed);
}

template <Backend B>
void Driver<B>::exchange(Exchange after) {
  if (config_.period > 0.0) backend_.for_each(grid_.ny, stage::ExchangeRow{grid_, after});
}

// V* of XPIC(m) (musl_stages.hpp): m - 1 round trips of the start velocity.
template <Backend B>
void Driver<B>::xpic_start_velocity(const StepConfig& c) {
  const GridView g = grid_;
  const ParticleView P = backend_.particles();
  backend_.for_each_node(g, stage::XpicStart{g, c});
  for (int k = 2; k <= c.xpic_order; ++k) {
    backend_.fill_nodes(g, g.px, 0.0);
    backend_.fill_nodes(g, g.py, 0.0);
    backend_.scatter(g, c, stage::P2gSmoothed{P, g});
    exchange(Exchange::AfterMomentum);
    backend_.for_each_node(g, stage::XpicTerm{g, c, k});
    exchange(Exchange::AfterXpicTerm);
  }
}

// The return mapping has put each particle on the yield surface of its own
// increment; the nonlocal one takes over from the next step, where the
// strength is evaluated at the regularised xi (the explicit scheme of
// Galavi & Schweiger 2010: local return, nonlocal internal variable). The
// increments are measured at the particles' end-of-step positions.
template <Backend B>
void Driver<B>::regularise_softening(double dt) {
  const ParticleView P = backend_.particles();
  double* start = backend_.xi_start();
  double* local = backend_.xi_local();
  double* average = backend_.xi_average();
  backend_.for_each_particle(stage::XiIncrement{P, start, local});
  backend_.nonlocal_average(nonlocal_, local, average);
  backend_.for_each_particle(stage::SetNonlocalXi{P, start, average, backend_.nonlocal_lengths(),
                                                  backend_.materials(), dt});
}

template <Backend B>
void Driver<B>::step(double dt) {
  fit_grid(dt);
  backend_.bin(grid_, config_, steps_);
  configure_step(config_, time_, dt);
  const StepConfig c = backend_.kernel_config(config_);
  const GridView g = grid_;
  const ParticleView P = backend_.particles();
  const bool nonlocal = nonlocal_.active();

  backend_.scatter(g, c, stage::P2g{P, g, c, backend_.materials()});
  exchange(Exchange::AfterP2g);
  backend_.for_each_node(g, stage::GridUpdate{g, c, dt});
  exchange(Exchange::AfterGridUpdate);
  const double basal = c.base.kind != BaseKind::None ? backend_.sum_nodes(g, g.fbase) : 0.0;
  // grid_update leaves px, py zero; XPIC's round trips use them again.
  if (c.xpic_now) {
    xpic_start_velocity(c);
    backend_.fill_nodes(g, g.px, 0.0);
    backend_.fill_nodes(g, g.py, 0.0);
  }
  backend_.scatter(g, c, stage::G2pMomentum{P, g, c, backend_.materials(), dt});
  exchange(Exchange::AfterMomentum);
  backend_.for_each_node(g, stage::Remap{g, c, dt});
  exchange(Exchange::AfterRemap);

  // Stages 6 and 7 need of other particles only those of the particle's own
  // cell (the volumetric smoothing's means), so they run group by group of
  // whole cells, and what they pass between them (L, the displacements)
  // is the group's own.
  const SpeedMax speed = backend_.for_cell_groups(g, c, [&](CellGroupPasses auto& cells) {
    const GradientView L = cells.gradients();
    const StepScratch s = cells.scratch();
    const stage::Gradient gradient{g, dt, s, L};
    CellMeanView rate{}, mean{};
    if (smooth_volumetric_)
      rate = driver_detail::stencil_pass_and_means(cells, g, c, gradient, stage::VolumetricRate{L});
    else
      cells.for_each_particle_stencil(g, c, gradient);
    if (nonlocal) cells.for_each_particle(stage::CopyXi{P, backend_.xi_start()});
    const stage::Stress stress{P, L, rate, backend_.materials(), dt, s, c, limits_};
    const SpeedMax sp =
        smooth_volumetric_
            ? driver_detail::max_speed_and_means(cells, g, stress, stage::MeanStress{P}, mean)
            : cells.max_speed(stress);
    // A group with a failed particle is left as its update left it, for
    // describe_faults: its cell means would spread the failure to its cells.
    if (smooth_volumetric_ && sp.bad == 0) cells.for_each_particle(stage::SetMeanStress{P, mean});
    return sp;
  });
  if (speed.bad > 0) fail(dt);
  // After the mean stress, which it neither reads nor changes.
  if (nonlocal) regularise_softening(dt);
  max_signal_speed_ = speed.max;
  basal_shear_force_ = basal;
  time_ += dt;
  last_dt_ = dt;
  ++steps_;
}

template <Backend B>
void Driver<B>::advance_to(double t) {
  // Equal steps no longer than the CFL limit, so the last one is not a
  // sliver; the final step lands on t exactly.
  while (time_ < t) {
    const double remaining = t - time_;
    const double n = std::ceil(remaining / stable_dt());
    step(remaining / n);
    if (n <= 1.0) time_ = t;
  }
}

}  // namespace runout
