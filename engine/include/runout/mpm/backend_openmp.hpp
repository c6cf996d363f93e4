#pragma once
// The CPU backend of the driver (driver.hpp): OpenMP loops, and a scatter
// by colouring. Particles are grouped by blocks of kBlock x kBlock cells,
// and the blocks into strips kStrip blocks wide across the whole height of
// the grid box, coloured alternately; strips of one colour never write the
// same node, and a strip of the second colour starts only once the two
// beside it are done, so the scatter is race-free without atomics and adds
// at every node in the same order whatever the number of threads: results
// are bit for bit the same on 1 or 16 threads. Its helpers: the counting
// sort by block (block_sort.hpp), the cell groups (cell_group.hpp), work
// handed out owner first (owned_queue.hpp), the node loops (active_nodes.hpp).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <thread>
#include <utility>
#include <vector>

#include "runout/mpm/active_nodes.hpp"
#include "runout/mpm/backend_concept.hpp"
#include "runout/mpm/backend_host.hpp"
#include "runout/mpm/block_sort.hpp"
#include "runout/mpm/cell_group.hpp"
#include "runout/mpm/openmp_threads.hpp"
#include "runout/mpm/owned_queue.hpp"

namespace runout {

// The hot loops are [[gnu::flatten]], or GCC 12 leaves make_stencil and
// stress_update out of line in them; each loop takes its own copy of its
// stage functor (firstprivate), whose array pointers then stay in
// registers instead of being reloaded after every store that might alias
// them (docs/performance.md, "Choices in the CPU step").
class OpenMpBackend : public HostBackend {
 public:
  // Blocks are the unit of the memory order (a block's particles are
  // stored together) and of the cell means (a cell lies in one block).
  static constexpr int kBlock = 4;
  // A particle in cell c touches nodes c-1..c+2, so two strips of one
  // colour, a strip (kStrip kBlock cells) apart, never share a node. Strips
  // across x suit long, thin slides; 16 blocks was the fastest width
  // (docs/performance.md). The width fixes the block order, so it depends
  // on nothing but the grid: results stay the same on any number of threads.
  static constexpr int kStrip = 16;
  // Loops shorter than this run on one thread: a parallel region costs a
  // few microseconds, more than small scenes (and the tests) spend in the
  // loop.
  static constexpr int kParallelMin = 4096;
  // Particle loops hand out chunks as threads come free: the particles by
  // the base (sheared, yielding, in contact) cost more than the rest, so
  // equal halves left one thread waiting.
  static constexpr int kChunk = 1024;
  // Particles drift out of block order slowly (a cell in many steps), so
  // sorting them in memory every few dozen steps keeps the loops sequential.
  static constexpr long kReorderInterval = 50;
  // A cell group (cell_group.hpp) is kGroupRows block rows of a strip: the
  // fastest height, taken owner first (docs/performance.md).
  static constexpr int kGroupRows = 2;
  // A cell group's cells: kGroupCellsX along x (a strip's width) by
  // kGroupCellsY.
  static constexpr int kGroupCellsX = kStrip * kBlock, kGroupCellsY = kGroupRows * kBlock;
  // The least span of particle indices a cell group's buffers may take
  // (1.5 MiB a thread) before the limit on them (for_cell_groups) sends
  // the group to whole-particle arrays: four groups' worth at 4 x 4
  // particles a cell, so that groups that only take in particles from the
  // strips beside them keep their own.
  static constexpr int kGroupSpanMin = 1 << 15;

  OpenMpBackend(Particles particles, const std::vector<MaterialParams>& materials, const Base&,
                const std::vector<double>& nonlocal_lengths)
      : HostBackend(std::move(particles), materials, nonlocal_lengths) {
    const int n = particles_.size();
    particle_block_.assign(n, 0);
    particle_cell_.assign(n, 0);
    lx_.assign(n, 0.0);
    ly_.assign(n, 0.0);
    order_.assign(n, 0);
  }

  // The box of the particles: the one the last step's cell groups took of
  // their particles where they moved them, unless the particles were
  // handed out since (host_particles); else a pass over all of them.
  ParticleBox bounding_box() {
    if (box_known_) {
      box_known_ = false;
      return box_;
    }
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

  // Each particle's block, cell and domain; every kReorderInterval steps
  // the particles are first stored in block order, so that the block-by-block
  // loops read memory in sequence.
  void bin(const GridView& g, const StepConfig& c, long step) {
    bin_particles(g, c);
    if (step % kReorderInterval == 0) {
      particles_.permute(order_);
      bin_particles(g, c);
    }
    if (c.period > 0.0) {
      active_.whole(g);
      return;
    }
    active_.find(g, kBlock, strips_ * kStrip, blocks_y_, [&](int bi, int by) {
      const unsigned b = block_number(bi, by, blocks_y_);
      return block_start_[b + 1] > block_start_[b];
    });
  }

  // The first colour's strips are handed out before the second's, and a
  // strip of the second colour waits only for its two neighbours
  // (wait_for_strip), not for the whole first colour, whose slowest strip
  // a loop of its own would wait for. Within a colour each thread takes its
  // own strips first (owner). The order of the additions at every node is
  // the same whichever thread adds.
  template <class Stage>
  [[gnu::flatten]] void scatter(const GridView& g, const StepConfig& c, Stage stage) {
    const PlainAdd add;
    const auto lower = [](double* a, int n, double v) { a[n] = std::min(a[n], v); };
    const bool derivatives = stage.derivatives();
    const int strips = strips_;
    if (strip_done_.size() < static_cast<std::size_t>(strips))
      strip_done_ = std::vector<std::atomic<int>>(strips);
    for (int k = 0; k < strips; ++k) strip_done_[k].store(0, std::memory_order_relaxed);
    const bool parallel = order_.size() > kParallelMin;
    const int threads = parallel ? openmp::max_threads() : 1;
    for (OwnedQueue& q : colour_queue_) q.reset(threads);
    for (int k = 0; k < strips; ++k)
      colour_queue_[k % 2].add(owner(group_start(k, 0), group_start(k, blocks_y_), threads), k);
#pragma omp parallel firstprivate(stage) if (parallel)
    for (OwnedQueue& queue : colour_queue_)
      queue.run(openmp::this_thread(), [&](int strip) {
        // The first colour's strips have all been handed out by now, so
        // these waits end.
        if (strip % 2 == 1) {
          wait_for_strip(strip - 1);
          if (strip + 1 < strips) wait_for_strip(strip + 1);
        }
        const int first = group_start(strip, 0), last = group_start(strip, blocks_y_);
        const auto each = [&](const int* p, const Stencil2D* st, int count) {
          for (int k = 0; k < count; ++k) stage(p[k], st[k], add, lower);
        };
        if (derivatives)
          for_each_four<true>(g, c, first, last, each);
        else
          for_each_four<false>(g, c, first, last, each);
        strip_done_[strip].store(1, std::memory_order_release);  // its sums, to the waiters
      });
  }

  // The last step's nodes are cleared before the box moves (active_nodes.hpp),
  // the whole box only where it needed more storage.
  GridView fit_grid(const GridView& placed) {
    active_.clear(grid_.view());
    const bool grows = static_cast<std::size_t>(placed.size()) > grid_.capacity();
    const GridView& g = grid_.fit(placed);
    if (grows) ActiveNodes::clear_all(g);
    return g;
  }
  // The node stages over the nodes the particles reach (bin found them).
  template <class Stage>
  void for_each_node(const GridView&, Stage stage) {
    active_.for_each(stage);
  }
  void fill_nodes(const GridView&, double* a, double v) const { active_.fill(a, v); }
  double sum_nodes(const GridView& g, const double* a) { return active_.sum(a, g.size()); }

  template <class Stage>
  void for_each(int count, Stage stage) {
#pragma omp parallel for schedule(dynamic, kChunk) firstprivate(stage) if (count > kParallelMin)
    for (int i = 0; i < count; ++i) stage(i);
  }
  template <class Stage>
  void for_each_particle(Stage stage) {
    for_each(particles_.size(), stage);
  }
  // A thread's buffers for its cell groups.
  using Scratch = GroupScratch<kGroupCellsX * kGroupCellsY>;
  // f(cells) for each CellGroup, in parallel, each thread its own groups
  // first (owner): groups share no particle and no cell. The sum of what
  // they return.
  template <class F>
  [[gnu::flatten]] SpeedMax for_cell_groups(const GridView&, const StepConfig&, F f) {
    double smax = 0;
    int bad = 0;
    const double inf = std::numeric_limits<double>::infinity();
    double xmin = inf, ymin = inf, xmax = -inf, ymax = -inf;
    const int bands = (blocks_y_ + kGroupRows - 1) / kGroupRows, groups = strips_ * bands;
    // Group k: strip k / bands, block rows [by0(k), by1(k)).
    const auto by0 = [=](int k) { return (k % bands) * kGroupRows; };
    const auto by1 = [=, this](int k) { return std::min(by0(k) + kGroupRows, blocks_y_); };
    const bool parallel = particles_.size() > kParallelMin;
    const int threads = parallel ? openmp::max_threads() : 1;
    if (group_scratch_.size() < static_cast<std::size_t>(threads)) group_scratch_.resize(threads);
    // Buffers of threads x span_limit particles at most, as many as the
    // whole-particle arrays: a group whose span is longer uses those.
    const int span_limit = std::max(kGroupSpanMin, particles_.size() / threads);
    group_queue_.reset(threads);
    for (int k = 0; k < groups; ++k)
      group_queue_.add(owner(group_start(k / bands, by0(k)), group_start(k / bands, by1(k)), threads),
                       k);
#pragma omp parallel firstprivate(f) reduction(max : smax, xmax, ymax) \
    reduction(min : xmin, ymin) reduction(+ : bad) if (parallel)
    {
      const int thread = openmp::this_thread();
      group_queue_.run(thread, [&](int k) {
        CellGroup<OpenMpBackend> cells(*this, k / bands, by0(k), by1(k), span_limit,
                                       group_scratch_[thread]);
        if (cells.empty()) return;
        const SpeedMax speed = f(cells);
        smax = std::max(smax, speed.max);
        bad += speed.bad;
        const ParticleBox& b = cells.box();
        xmin = std::min(xmin, b.xmin);
        xmax = std::max(xmax, b.xmax);
        ymin = std::min(ymin, b.ymin);
        ymax = std::max(ymax, b.ymax);
      });
    }
    box_known_ = bad == 0;
    box_ = {xmin, xmax, ymin, ymax, 0};
    return {smax, bad};
  }

  // The longest of the threads' cell-group buffers, in particles.
  int group_buffer_particles() const {
    std::size_t most = 0;
    for (const Scratch& s : group_scratch_) most = std::max(most, s.dx.size());
    return static_cast<int>(most);
  }

  // Whoever takes the particles may move them.
  Particles& host_particles() {
    box_known_ = false;
    return particles_;
  }
  const Particles& host_particles() const { return particles_; }

 private:
  friend class CellGroup<OpenMpBackend>;

  // The stencils of particles p[0 .. 3], four at a time (GIMP), from their
  // positions and the half-widths the binning stored: made again in each
  // pass that needs them rather than stored (docs/engine.md, "Shape
  // functions"). Out of line, so that its arithmetic is compiled once: a
  // particle has the same stencil in every pass, whichever three it is made with.
  // kDerivatives false: GIMP stencils without their derivatives, for the
  // passes that do not read them (the stage's derivatives()); the weights
  // are the same operations, so the same bits (tested).
  template <bool kDerivatives>
  [[gnu::noinline, gnu::flatten]] void make_stencils(const GridView& g, const StepConfig& c,
                                                    const int p[4], Stencil2D st[4]) const {
    const double *x = particles_.x.data(), *y = particles_.y.data();
    if (c.shape == ShapeKind::Gimp) {
      gimp_stencils_x4<kDerivatives>(g, gather_lanes(x, p), gather_lanes(y, p),
                                     gather_lanes(lx_.data(), p), gather_lanes(ly_.data(), p), st);
      return;
    }
    for (int k = 0; k < 4; ++k) stencil_at(g, c, x[p[k]], y[p[k]], lx_[p[k]], ly_[p[k]], st[k]);
  }

  // f(p, st, count) for the particles order_[first .. last), four at a
  // time: p[0 .. count - 1] the particles, st their stencils (p[count .. 3]
  // copies of the last).
  template <bool kDerivatives = true, class F>
  void for_each_four(const GridView& g, const StepConfig& c, int first, int last, F&& f) const {
    for (int q = first; q < last; q += 4) {
      const int count = std::min(4, last - q);
      const int end = order_[q + count - 1];
      const int p[4] = {order_[q], count > 1 ? order_[q + 1] : end, count > 2 ? order_[q + 2] : end,
                        end};
      Stencil2D st[4];
      make_stencils<kDerivatives>(g, c, p, st);
      f(p, st, count);
    }
  }

  // Where the particles of strip's block row by start in order_ (by =
  // blocks_y_: where the strip's end): blocks are numbered strip by strip,
  // in each strip block row by block row, so that a strip's particles, and
  // a row of it, lie together in the block order and, once permuted, in
  // memory: the scatters and the cell groups then read it in sequence.
  // Block (bi, by)'s place in the block order: strip by strip, in each
  // strip block row by block row.
  static unsigned block_number(unsigned bi, unsigned by, unsigned blocks_y) {
    return ((bi / kStrip) * blocks_y + by) * kStrip + bi % kStrip;
  }
  int group_start(int strip, int by) const {
    return block_start_[(strip * blocks_y_ + by) * kStrip];
  }

  [[gnu::flatten]] void bin_particles(const GridView& grid, const StepConfig& config) {
    const ParticleView P = particles_.view();
    const GridView g = grid;
    const StepConfig c = config;
    const int cells_x = g.nx - 1, cells_y = cells_y_ = g.ny - 1;
    const int blocks_x = (cells_x + kBlock - 1) / kBlock;
    const int by = blocks_y_ = (cells_y + kBlock - 1) / kBlock;
    strips_ = (blocks_x + kStrip - 1) / kStrip;
    const int blocks = strips_ * blocks_y_ * kStrip;
    double *const lx = lx_.data(), *const ly = ly_.data();
    int *const block = particle_block_.data(), *const cell = particle_cell_.data();
    // Particle p's block and place in its cell group from its cell (ci,
    // cj) as the stencil finds it (cell_of): its nodes must lie in the
    // strip. The cell lies in the box, so its indices are not negative.
    const unsigned blocks_up = by;
    const auto place = [=](int p, unsigned ci, unsigned cj) {
      const unsigned bi = ci / kBlock;
      block[p] = static_cast<int>(block_number(bi, cj / kBlock, blocks_up));
      cell[p] = static_cast<int>((cj % kGroupCellsY) * kGroupCellsX + ci % kGroupCellsX);
    };
    const bool gimp = c.shape == ShapeKind::Gimp;
    // The particles [p0, p1): four at a time (domain_half_widths_4) from
    // p0, a multiple of four, so in groups fixed by the index, the same
    // whatever the number of threads.
    const auto bin_range = [=](int p0, int p1) {
      int p = p0;
      for (; gimp && p + 4 <= p1; p += 4) {
        domain_half_widths_4(P, p, c, g.h, lx + p, ly + p);
        // cell_of four at a time
        const Lanes ci = floor_lanes(grid_coordinate(load_lanes(P.x + p), g.ox, g.h));
        const Lanes cj = floor_lanes(grid_coordinate(load_lanes(P.y + p), g.oy, g.h));
        for (int k = 0; k < 4; ++k)
          place(p + k, static_cast<int>(lane(ci, k)), static_cast<int>(lane(cj, k)));
      }
      for (; p < p1; ++p) {
        domain_half_widths(P, p, c, g.h, lx[p], ly[p]);
        place(p, cell_of(P.x[p], g.ox, g.h), cell_of(P.y[p], g.oy, g.h));
      }
    };
    sort_by_block(particles_.size(), blocks, particle_block_.data(), bin_range,
                  particles_.size() > kParallelMin, order_.data(), block_start_, next_);
  }

  // The thread (of threads) that bins the middle particle of
  // order_[first, last), the particles of a strip or a cell group: each
  // thread bins one range of the particles' indices (sort_by_block), which
  // since the last reorder are those of a run of whole strips, and takes
  // the same particles first in the scatters and the cell groups, so that
  // they are mostly in its own core's cache from one pass to the next.
  int owner(int first, int last, int threads) const {
    const long n = std::max<long>(1, static_cast<long>(order_.size()));
    const long middle = (first + static_cast<long>(last)) / 2;
    return static_cast<int>(std::min<long>(threads - 1, middle * threads / n));
  }

  // Sized once, on whichever thread first needs it; the groups that use it
  // write only their own particles' places.
  Scratch& whole_particle_scratch() {
#pragma omp critical(runout_whole_particle_scratch)
    whole_particle_scratch_.fit(particles_.size());
    return whole_particle_scratch_;
  }

  // Spins briefly, then yields: the strip is running on another thread,
  // which may have lost its core to another process.
  void wait_for_strip(int strip) const {
    for (int spin = 0; strip_done_[strip].load(std::memory_order_acquire) == 0; ++spin)
      if (spin > 1000) std::this_thread::yield();
  }

  // The half-widths of the particles' domains at the start of the step.
  StaggeredArray lx_, ly_;
  // Particles grouped by block of kBlock x kBlock cells (counting sort).
  std::vector<int> block_start_, order_, particle_block_, particle_cell_, next_;
  ActiveNodes active_;                         // the nodes this step's particles reach
  std::vector<std::atomic<int>> strip_done_;  // a scatter's strips, 1 once added
  std::vector<Scratch> group_scratch_;     // a thread's, for its cell groups
  Scratch whole_particle_scratch_;          // for groups whose span passes the limit
  OwnedQueue colour_queue_[2], group_queue_;  // the scatters', the cell groups' work
  int blocks_y_ = 0, strips_ = 0, cells_y_ = 0;
  ParticleBox box_{};  // bounding_box's, when box_known_
  bool box_known_ = false;
};

static_assert(Backend<OpenMpBackend>);
static_assert(CellGroupPasses<CellGroup<OpenMpBackend>> && MeansInPasses<CellGroup<OpenMpBackend>>);

}  // namespace runout
