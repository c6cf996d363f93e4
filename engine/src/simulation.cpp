#include "runout/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "runout/materials.hpp"
#include "runout/seeding.hpp"

namespace runout {
namespace {

// Blocks of kBlock x kBlock cells, coloured 2 x 2. A particle in cell c
// touches nodes c-1..c+2, so a block writes nodes within one cell around
// itself plus two, and two same-colour blocks, kBlock cells apart, never
// share a node as long as kBlock > 2.
constexpr int kBlock = 4;

// Loops shorter than this run on one thread: a parallel region costs a few
// microseconds, more than small scenes (and the tests) spend in the loop.
constexpr int kParallelMin = 4096;

// Particles drift out of block order slowly (a cell in many steps), so
// sorting them in memory every few dozen steps keeps the loops sequential.
constexpr long kReorderInterval = 50;

StepConfig make_config(const Scene& s, const std::vector<MaterialParams>& materials) {
  const double h = s.grid.cell_size;
  StepConfig c;
  c.shape = s.grid.shape;
  c.domain = s.grid.domain;
  c.lp = h / (2.0 * s.grid.ppc);
  c.gx = s.gravity.vector.x();
  c.gy = s.gravity.vector.y();
  c.gravity_ramp = s.gravity.ramp;
  c.transfer = s.solver.transfer;
  c.flip = s.solver.flip;
  // The PIC share's time scale: pic_cells crossings of a cell by the
  // fastest P-wave, so it shrinks with the cell (the filtered sub-cell
  // velocity then carries less and less) but not with the time step.
  double c_max = 0;
  for (const auto& m : materials) c_max = std::max(c_max, std::sqrt(p_wave_modulus(m) / m.density));
  c.pic_time = c_max > 0.0 ? s.solver.pic_cells * h / c_max : 0.0;
  double rho_max = 0;
  for (const auto& m : materials) rho_max = std::max(rho_max, m.density);
  c.min_node_mass = s.solver.mass_threshold * rho_max * h * h;
  c.damping = s.solver.damping;
  c.left = s.boundary.left;
  c.right = s.boundary.right;
  c.bottom = s.boundary.bottom;
  c.top = s.boundary.top;
  // The parser snaps max up to a node; the tolerance absorbs the rounding.
  c.domain_nx = static_cast<int>(std::ceil((s.grid.max.x() - s.grid.min.x()) / h - 1e-9));
  c.domain_ny = static_cast<int>(std::ceil((s.grid.max.y() - s.grid.min.y()) / h - 1e-9));
  if (s.boundary.left == BoundaryKind::Periodic) {
    c.period = c.domain_nx * h;
    c.domain_x0 = s.grid.min.x();
  }
  c.interface = s.base.interface;
  c.shear_strength = s.base.shear_strength;
  c.friction = s.base.friction;
  c.xpic_order = s.solver.xpic_order;
  // As pic_time: xpic_cells crossings of a cell by the fastest P-wave; a
  // schedule of FLIP's only. The parser refuses it with another transfer
  // and sets 0 there (so a resolved scene reads back); a scene built in
  // code keeps SolverSpec's default 40 whatever its transfer.
  const bool scheduled = s.solver.transfer == TransferKind::Flip && c_max > 0.0;
  c.xpic_period = scheduled ? s.solver.xpic_cells * h / c_max : 0.0;
  return c;
}

std::vector<double> nonlocal_lengths(const Scene& s) {
  std::vector<double> out;
  for (const auto& m : s.materials) out.push_back(m.nonlocal_length);
  return out;
}

std::vector<MaterialParams> make_materials(const Scene& s) {
  std::vector<MaterialParams> out;
  for (const auto& m : s.materials) out.push_back(material_params(m));
  return out;
}

}  // namespace

Simulation::Simulation(const Scene& scene) : Simulation(scene, seed_particles(scene)) {}

Simulation::Simulation(const Scene& scene, Particles particles)
    : particles_(std::move(particles)),
      base_(scene.base, scene.grid.min.y()),
      materials_(make_materials(scene)),
      nonlocal_(nonlocal_lengths(scene)),
      domain_min_(scene.grid.min),
      domain_max_(scene.grid.max),
      h_(scene.grid.cell_size),
      courant_(scene.time.courant),
      spacing_(scene.grid.cell_size / scene.grid.ppc),
      smooth_volumetric_(scene.solver.volumetric_smoothing) {
  config_ = make_config(scene, materials_);
  config_.base = base_.view();
  const int n = particles_.size();
  scratch_dx_.assign(n, 0.0);
  scratch_dy_.assign(n, 0.0);
  particle_block_.assign(n, 0);
  particle_cell_.assign(n, 0);
  stencils_.resize(n);
  gradients_.resize(n);
  order_.assign(n, 0);
  const ParticleView P = particles_.view();
  double smax = 0;
  for (int p = 0; p < n; ++p) smax = std::max(smax, cfl_speed(P, p, materials_[P.material[p]]));
  max_signal_speed_ = smax;
  limits_ = guard_limits(scene, materials_, particles_);
}

StepCounters Simulation::counters() const {
  return StepCounters{time_, steps_, last_dt_, basal_shear_force_, max_signal_speed_,
                      limits_.max_speed};
}

void Simulation::restore(const StepCounters& c) {
  time_ = c.time;
  steps_ = c.steps;
  last_dt_ = c.last_dt;
  basal_shear_force_ = c.basal_shear_force;
  max_signal_speed_ = c.max_signal_speed;
  limits_.max_speed = c.speed_limit;
}

void Simulation::fit_grid(double dt) {
  const ParticleView P = particles_.view();
  double xmin = std::numeric_limits<double>::infinity(), ymin = xmin;
  double xmax = -xmin, ymax = -xmin;
  int non_finite = 0;  // min and max pass over NaN
#pragma omp parallel for reduction(min : xmin, ymin) reduction(max : xmax, ymax) \
    reduction(+ : non_finite) if (P.n > kParallelMin)
  for (int p = 0; p < P.n; ++p) {
    xmin = std::min(xmin, P.x[p]);
    xmax = std::max(xmax, P.x[p]);
    ymin = std::min(ymin, P.y[p]);
    ymax = std::max(ymax, P.y[p]);
    non_finite += !(std::isfinite(P.x[p]) && std::isfinite(P.y[p]));
  }
  // The end of every step checks the particles; this catches particles
  // given (or changed between steps) outside the domain before they index
  // the grid.
  const GuardLimits& g = limits_;
  if (non_finite > 0 || !(xmin >= g.xmin && ymin >= g.ymin && xmax <= g.xmax && ymax <= g.ymax))
    throw NumericalFailure(describe_faults(particles_, limits_, steps_, time_, dt));
  if (config_.period > 0.0) periodic_span(config_, h_, xmin, xmax);
  grid_.fit(xmin, xmax, ymin, ymax, domain_min_.x(), domain_min_.y(), h_);
}

void Simulation::bin_particles() {
  const GridView& g = grid_.view();
  const ParticleView P = particles_.view();
  const int cells_x = g.nx - 1, cells_y = g.ny - 1;
  blocks_x_ = (cells_x + kBlock - 1) / kBlock;
  blocks_y_ = (cells_y + kBlock - 1) / kBlock;
  const int blocks = blocks_x_ * blocks_y_;
#pragma omp parallel for if (P.n > kParallelMin)
  for (int p = 0; p < P.n; ++p) {
    const int ci = static_cast<int>(std::floor((P.x[p] - g.ox) / g.h));
    const int cj = static_cast<int>(std::floor((P.y[p] - g.oy) / g.h));
    particle_block_[p] = (cj / kBlock) * blocks_x_ + ci / kBlock;
    particle_cell_[p] = cj * cells_x + ci;
    make_stencil(g, config_, P, p, stencils_[p]);
  }
  // Stable counting sort: within a block particles keep their index order,
  // which fixes the order of the sums at every node.
  block_start_.assign(blocks + 1, 0);
  for (int p = 0; p < P.n; ++p) ++block_start_[particle_block_[p] + 1];
  for (int b = 0; b < blocks; ++b) block_start_[b + 1] += block_start_[b];
  std::vector<int>& next = scratch_next_;
  next.assign(block_start_.begin(), block_start_.end() - 1);
  for (int p = 0; p < P.n; ++p) order_[next[particle_block_[p]]++] = p;
}

template <class Stage>
void Simulation::scatter(Stage&& stage) {
  const auto add = [](double* a, int n, double v) { a[n] += v; };
  // A thread takes a whole row of blocks: blocks side by side in a row
  // write nodes two apart, often in one cache line, and two threads there
  // would fight over it; rows of one colour are 2 kBlock node rows apart.
  for (int colour = 0; colour < 4; ++colour) {
    const int cx = colour & 1, cy = colour >> 1;
#pragma omp parallel for schedule(dynamic, 1) if (order_.size() > kParallelMin)
    for (int by = cy; by < blocks_y_; by += 2) {
      for (int bx = cx; bx < blocks_x_; bx += 2) {
        const int b = by * blocks_x_ + bx;
        for (int q = block_start_[b]; q < block_start_[b + 1]; ++q) stage(order_[q], add);
      }
    }
  }
}

template <class Value>
void Simulation::cell_means(Value&& value) {
  const GridView& g = grid_.view();
  const ParticleView P = particles_.view();
  const int cells = (g.nx - 1) * (g.ny - 1);
  cell_volume_.assign(cells, 0.0);
  cell_mean_.assign(cells, 0.0);
  // A cell's particles all lie in one block, so blocks never share a cell.
  const int blocks = blocks_x_ * blocks_y_;
#pragma omp parallel for schedule(dynamic, 1) if (P.n > kParallelMin)
  for (int b = 0; b < blocks; ++b) {
    for (int q = block_start_[b]; q < block_start_[b + 1]; ++q) {
      const int p = order_[q], c = particle_cell_[p];
      cell_volume_[c] += P.vol[p];
      cell_mean_[c] += P.vol[p] * value(p);
    }
  }
#pragma omp parallel for if (cells > kParallelMin)
  for (int c = 0; c < cells; ++c)
    if (cell_volume_[c] > 0.0) cell_mean_[c] /= cell_volume_[c];
}

void Simulation::smooth_volumetric_rates() {
  VelocityGradient* L = gradients_.data();
  cell_means([L](int p) { return L[p].xx + L[p].yy; });
#pragma omp parallel for if (particles_.size() > kParallelMin)
  for (int p = 0; p < particles_.size(); ++p)
    set_volumetric_rate(L[p], cell_mean_[particle_cell_[p]]);
}

void Simulation::smooth_mean_stress() {
  const ParticleView P = particles_.view();
  cell_means([P](int p) { return (P.sxx[p] + P.syy[p] + P.szz[p]) / 3.0; });
#pragma omp parallel for if (P.n > kParallelMin)
  for (int p = 0; p < P.n; ++p) {
    const double shift = cell_mean_[particle_cell_[p]] - (P.sxx[p] + P.syy[p] + P.szz[p]) / 3.0;
    P.sxx[p] += shift;
    P.syy[p] += shift;
    P.szz[p] += shift;
  }
}

// The return mapping has put each particle on the yield surface of its own
// increment; the nonlocal one takes over from the next step, where the
// strength is evaluated at the regularised xi (the explicit scheme of
// Galavi & Schweiger 2010: local return, nonlocal internal variable). The
// increments are measured at the particles' end-of-step positions.
void Simulation::regularise_softening() {
  const ParticleView P = particles_.view();
  dxi_local_.resize(P.n);
  dxi_average_.resize(P.n);
#pragma omp parallel for if (P.n > kParallelMin)
  for (int p = 0; p < P.n; ++p) dxi_local_[p] = P.xi[p] - xi_start_[p];
  nonlocal_.apply({P.n, P.x, P.y, P.vol, P.material}, dxi_local_.data(), dxi_average_.data());
#pragma omp parallel for if (P.n > kParallelMin)
  for (int p = 0; p < P.n; ++p) {
    if (nonlocal_.length(P.material[p]) <= 0.0) continue;
    P.xi[p] = xi_start_[p] + dxi_average_[p];
    P.su[p] = strength(materials_[P.material[p]].strength, P.xi[p], P.gamma_dot[p]);
  }
}

// V* of XPIC(m) (stages.hpp): m - 1 round trips of the start velocity.
void Simulation::xpic_start_velocity() {
  const GridView g = grid_.view();
  const ParticleView P = particles_.view();
  const StepConfig& c = config_;
  const Stencil2D* st = stencils_.data();
  const int nodes = g.size();
#pragma omp parallel for if (nodes > kParallelMin)
  for (int n = 0; n < nodes; ++n) xpic_start(g, n, c);
  for (int k = 2; k <= c.xpic_order; ++k) {
    std::fill_n(g.px, nodes, 0.0);
    std::fill_n(g.py, nodes, 0.0);
    scatter([&](int p, auto add) { p2g_smoothed(P, p, st[p], g, add); });
    if (c.period > 0.0)
      for (int j = 0; j < g.ny; ++j) exchange_periodic(g, j, Exchange::AfterMomentum);
#pragma omp parallel for if (nodes > kParallelMin)
    for (int n = 0; n < nodes; ++n) xpic_term(g, n, c, k);
    if (c.period > 0.0)
      for (int j = 0; j < g.ny; ++j) exchange_periodic(g, j, Exchange::AfterXpicTerm);
  }
}

void Simulation::step(double dt) {
  fit_grid(dt);
  bin_particles();
  if (steps_ % kReorderInterval == 0) {
    // Store the particles in block order, so that the block-by-block loops
    // read memory in sequence; the binning is then the identity.
    particles_.permute(order_);
    bin_particles();
  }
  const GridView g = grid_.view();
  const ParticleView P = particles_.view();
  configure_step(config_, time_, dt);
  const StepConfig& c = config_;
  const StepScratch s{scratch_dx_.data(), scratch_dy_.data()};
  const int nodes = g.size();

  const Stencil2D* st = stencils_.data();
  const auto lower = [](double* a, int n, double v) { a[n] = std::min(a[n], v); };
  const auto exchange = [&](Exchange after) {
    if (c.period > 0.0)
      for (int j = 0; j < g.ny; ++j) exchange_periodic(g, j, after);
  };
  scatter([&](int p, auto add) { p2g(P, p, st[p], g, c, add, lower); });
  exchange(Exchange::AfterP2g);
#pragma omp parallel for if (nodes > kParallelMin)
  for (int n = 0; n < nodes; ++n) grid_update(g, n, c, dt);
  exchange(Exchange::AfterGridUpdate);
  double basal = 0;  // in node order, so the same every run
  if (c.base.kind != BaseKind::None)
    for (int n = 0; n < nodes; ++n) basal += g.fbase[n];
  if (c.xpic_now) xpic_start_velocity();
  // g2p reads only nodal velocities, so each particle's remap can follow it
  // in the same pass.
  std::fill_n(g.px, nodes, 0.0);
  std::fill_n(g.py, nodes, 0.0);
  scatter([&](int p, auto add) {
    g2p(P, p, st[p], g, c);
    p2g_momentum(P, p, st[p], g, add);
  });
  exchange(Exchange::AfterMomentum);
#pragma omp parallel for if (nodes > kParallelMin)
  for (int n = 0; n < nodes; ++n) remap_velocity(g, n, c, dt);
  exchange(Exchange::AfterRemap);

  VelocityGradient* L = gradients_.data();
#pragma omp parallel for if (P.n > kParallelMin)
  for (int p = 0; p < P.n; ++p) {
    L[p] = velocity_gradient(st[p], g);
    displacement(p, st[p], g, dt, s);
  }
  if (smooth_volumetric_) smooth_volumetric_rates();
  if (nonlocal_.active()) xi_start_.assign(P.xi, P.xi + P.n);

  double smax = 0;
  int bad = 0;
  const MaterialParams* mats = materials_.data();
  const GuardLimits limits = limits_;
#pragma omp parallel for reduction(max : smax) reduction(+ : bad) if (P.n > kParallelMin)
  for (int p = 0; p < P.n; ++p) {
    smax = std::max(smax, stress_update(P, p, L[p], mats, dt, s));
    wrap_periodic(P, p, c);
    bad += particle_fault(P, p, limits) != Fault::None;
  }
  if (bad > 0) throw NumericalFailure(describe_faults(particles_, limits_, steps_, time_, dt));
  if (nonlocal_.active()) regularise_softening();
  if (smooth_volumetric_) smooth_mean_stress();
  max_signal_speed_ = smax;
  basal_shear_force_ = basal;
  time_ += dt;
  last_dt_ = dt;
  ++steps_;
}

void Simulation::advance_to(double t) {
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
