#pragma once
// The CPU backend of the driver (driver.hpp): OpenMP loops, and a scatter
// by colouring. Particles are grouped by blocks of kBlock x kBlock cells,
// and the blocks into strips kStrip blocks wide across the whole height of
// the grid box, coloured alternately; strips of one colour never write the
// same node, so the scatter is race-free without atomics and adds at every
// node in the same order whatever the number of threads: results are bit
// for bit the same on 1 or 16 threads.
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "runout/backend_host.hpp"

namespace runout {

// The hot loops are [[gnu::flatten]]: inside these templates GCC 12 left
// make_stencil and stress_update out of line, and the one-driver step ran
// about 9 % slower on one thread than the hand-written loops before it
// (case 2, 0.25 m cells, 1 s: median user time of five alternated pairs);
// flattened, the gap is within the machine's noise (3 %). Each loop takes
// its own copy of its stage functor and views (firstprivate): shared, they
// are read through a pointer, and GCC reloaded their array pointers after
// every store to a nodal or particle array, which might alias them; private,
// they stay in registers (6 % fewer instructions a step, callgrind, 1e5
// particles).
class OpenMpBackend : public HostBackend {
 public:
  // Blocks are the unit of the memory order (a block's particles are
  // stored together) and of the cell means (a cell lies in one block).
  static constexpr int kBlock = 4;
  // A particle in cell c touches nodes c-1..c+2, so a strip writes nodes
  // within one cell of itself plus two, and two strips of one colour, a
  // strip (kStrip kBlock cells) apart, never share a node. Slides are long
  // and thin: strips across x give two threads many, evenly filled pieces
  // of work in each of two colours, where rows of blocks in four colours
  // gave them few, uneven ones and four waits a scatter.
  static constexpr int kStrip = 8;
  // Loops shorter than this run on one thread: a parallel region costs a
  // few microseconds, more than small scenes (and the tests) spend in the
  // loop.
  static constexpr int kParallelMin = 4096;
  // Particle loops hand out chunks as threads come free: the particles are
  // stored by block, bottom rows first, and those by the base (sheared,
  // yielding, in contact) cost more per step than the rest, so equal halves
  // kept one of two threads waiting a third of the loop.
  static constexpr int kChunk = 1024;
  // Particles drift out of block order slowly (a cell in many steps), so
  // sorting them in memory every few dozen steps keeps the loops sequential.
  static constexpr long kReorderInterval = 50;

  OpenMpBackend(Particles particles, const std::vector<MaterialParams>& materials, const Base&,
                const std::vector<double>& nonlocal_lengths)
      : HostBackend(std::move(particles), materials, nonlocal_lengths) {
    const int n = particles_.size();
    particle_block_.assign(n, 0);
    particle_cell_.assign(n, 0);
    weights_.resize(n);
    derivatives_.resize(n);
    places_.resize(n);
    order_.assign(n, 0);
  }

  ParticleBox bounding_box() {
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
    return {xmin, xmax, ymin, ymax, non_finite};
  }

  // Each particle's block, cell and stencil; every kReorderInterval steps
  // the particles are first stored in block order, so that the block-by-block
  // loops read memory in sequence.
  void bin(const GridView& g, const StepConfig& c, long step) {
    bin_particles(g, c);
    if (step % kReorderInterval == 0) {
      particles_.permute(order_);
      bin_particles(g, c);
    }
  }

  template <class Stage>
  [[gnu::flatten]] void scatter(const GridView&, const StepConfig&, Stage stage) {
    const PlainAdd add;
    const auto lower = [](double* a, int n, double v) { a[n] = std::min(a[n], v); };
    for (int colour = 0; colour < 2; ++colour) {
#pragma omp parallel for schedule(dynamic, 1) firstprivate(stage) if (order_.size() > kParallelMin)
      for (int strip = colour; strip < strips_; strip += 2)
        for_each_in_strip(strip, [&](int p) { stage(p, stencil(p), add, lower); });
    }
  }

  template <class Stage>
  void for_each(int count, Stage stage) {
#pragma omp parallel for schedule(dynamic, kChunk) firstprivate(stage) if (count > kParallelMin)
    for (int i = 0; i < count; ++i) stage(i);
  }
  template <class Stage>
  void for_each_particle(Stage stage) {
    for_each(particles_.size(), stage);
  }
  template <class Stage>
  [[gnu::flatten]] void for_each_particle_stencil(const GridView&, const StepConfig&, Stage stage) {
    const int n = particles_.size();
#pragma omp parallel for schedule(dynamic, kChunk) firstprivate(stage) if (n > kParallelMin)
    for (int p = 0; p < n; ++p) stage(p, stencil(p));
  }

  // Four particles at a time where they share a material (stage.four), in
  // groups fixed by the index, so the same whatever the number of threads.
  template <class Stage>
  [[gnu::flatten]] SpeedMax max_speed(Stage stage) {
    double smax = 0;
    int bad = 0;
    const int n = particles_.size(), groups = (n + 3) / 4;
#pragma omp parallel for schedule(dynamic, kChunk / 4) firstprivate(stage) \
    reduction(max : smax) reduction(+ : bad) if (n > kParallelMin)
    for (int q = 0; q < groups; ++q) {
      const int p = 4 * q, count = std::min(4, n - p);
      double s[4];
      if (count < 4 || !stage.four(p, s))
        for (int k = 0; k < count; ++k) s[k] = stage(p + k);
      for (int k = 0; k < count; ++k) {
        if (s[k] >= 0.0 && std::isfinite(s[k]))
          smax = std::max(smax, s[k]);
        else
          ++bad;
      }
    }
    return {smax, bad};
  }

  // Volume-weighted mean of value(p) over the particles of each grid cell.
  template <class Value>
  CellMeanView cell_means(const GridView& g, Value value) {
    const ParticleView P = particles_.view();
    const int cells = clear_cells(g);
    // A cell's particles all lie in one block, so strips never share a cell.
#pragma omp parallel for schedule(dynamic, 1) firstprivate(value) if (P.n > kParallelMin)
    for (int strip = 0; strip < strips_; ++strip) {
      for_each_in_strip(strip, [&](int p) {
        const int c = particle_cell_[p];
        cell_volume_[c] += P.vol[p];
        cell_mean_[c] += P.vol[p] * value(p);
      });
    }
#pragma omp parallel for if (cells > kParallelMin)
    for (int c = 0; c < cells; ++c)
      if (cell_volume_[c] > 0.0) cell_mean_[c] /= cell_volume_[c];
    return {cell_mean_.data(), particle_cell_.data()};
  }

 private:
  StencilRefs stencil(int p) const { return {weights_[p], derivatives_[p], places_[p]}; }

  // The particles of a strip, block row by block row, each block's in
  // index order.
  template <class F>
  void for_each_in_strip(int strip, F&& f) const {
    const int bx0 = strip * kStrip, bx1 = std::min(bx0 + kStrip, blocks_x_);
    for (int by = 0; by < blocks_y_; ++by) {
      const int row = by * blocks_x_;
      for (int q = block_start_[row + bx0]; q < block_start_[row + bx1]; ++q) f(order_[q]);
    }
  }

  [[gnu::flatten]] void bin_particles(const GridView& grid, const StepConfig& config) {
    const ParticleView P = particles_.view();
    const GridView g = grid;
    const StepConfig c = config;
    const int cells_x = g.nx - 1, cells_y = g.ny - 1;
    const int bx = blocks_x_ = (cells_x + kBlock - 1) / kBlock;
    blocks_y_ = (cells_y + kBlock - 1) / kBlock;
    strips_ = (blocks_x_ + kStrip - 1) / kStrip;
    const int blocks = blocks_x_ * blocks_y_;
    StencilWeights* const w = weights_.data();
    StencilDerivatives* const d = derivatives_.data();
    StencilPlace* const r = places_.data();
    int *const block = particle_block_.data(), *const cell = particle_cell_.data();
    const auto place = [&](int p) {
      const int ci = r[p].cell_x, cj = r[p].cell_y;
      block[p] = (cj / kBlock) * bx + ci / kBlock;
      cell[p] = cj * cells_x + ci;
    };
    // Four particles at a time (make_stencils_x4): in groups fixed by the
    // index, so the same whatever the number of threads.
    const int groups = P.n / 4;
#pragma omp parallel for schedule(dynamic, kChunk / 4) firstprivate(P, g, c) \
    if (P.n > kParallelMin)
    for (int q = 0; q < groups; ++q) {
      make_stencils_x4(g, c, P, 4 * q, w + 4 * q, d + 4 * q, r + 4 * q);
      for (int p = 4 * q; p < 4 * q + 4; ++p) place(p);
    }
    for (int p = 4 * groups; p < P.n; ++p) {
      make_stencil(g, c, P, p, [&](const Stencil1D& x, const Stencil1D& y, double lx, double ly) {
        set_stencil(x, y, lx, ly, w[p], d[p], r[p]);
      });
      place(p);
    }
    // Stable counting sort: within a block particles keep their index order,
    // which fixes the order of the sums at every node.
    block_start_.assign(blocks + 1, 0);
    for (int p = 0; p < P.n; ++p) ++block_start_[particle_block_[p] + 1];
    for (int b = 0; b < blocks; ++b) block_start_[b + 1] += block_start_[b];
    next_.assign(block_start_.begin(), block_start_.end() - 1);
    for (int p = 0; p < P.n; ++p) order_[next_[particle_block_[p]]++] = p;
  }

  // The particles' stencils, a part an array (stages.hpp, Stencil2D).
  std::vector<StencilWeights> weights_;
  std::vector<StencilDerivatives> derivatives_;
  std::vector<StencilPlace> places_;
  // Particles grouped by block of kBlock x kBlock cells (counting sort).
  std::vector<int> block_start_, order_, particle_block_, particle_cell_, next_;
  int blocks_x_ = 0, blocks_y_ = 0, strips_ = 0;
};

}  // namespace runout
