#pragma once
// The CPU backend of the driver (driver.hpp): OpenMP loops, and a scatter
// by colouring. Particles are grouped by blocks of kBlock x kBlock cells,
// and the blocks into strips kStrip blocks wide across the whole height of
// the grid box, coloured alternately; strips of one colour never write the
// same node, and a strip of the second colour starts only once the two
// beside it are done, so the scatter is race-free without atomics and adds
// at every node in the same order whatever the number of threads: results
// are bit for bit the same on 1 or 16 threads.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <thread>
#include <utility>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "runout/active_nodes.hpp"
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
  // Sixteen blocks (64 cells) wide: the step ran 1.02 to 1.09 times as
  // fast as with eight on two threads (bench_step, 1e5 and 1e6 particles;
  // longer runs along a node row), and 64 gave too few strips for two
  // threads at 1e5. The price is fewer strips for many threads: a grid
  // 1800 cells long has 28, 14 a colour. The width fixes the block order,
  // so it depends on nothing but the grid: results stay the same whatever
  // the number of threads.
  static constexpr int kStrip = 16;
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
  // A cell group (CellGroup) is kGroupRows block rows of a strip. Taken
  // by whichever thread came first, four rows ran 1.06 to 1.11 times as
  // fast as one on two threads (bench_step, 1e5 and 1e6 particles); taken
  // owner first (OwnedQueue), two ran 1.01 to 1.02 times as fast as four
  // at 1e5 and 1.00 to 1.01 at 1e6, and one 1.01 times as fast as two at
  // 1e5 but 0.96 to 0.97 at 1e6.
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
    const int blocks_x = (g.nx - 1 + kBlock - 1) / kBlock;
    active_.find(g, kBlock, blocks_x, blocks_y_, [&](int bi, int by) {
      const int b = ((bi / kStrip) * blocks_y_ + by) * kStrip + bi % kStrip;
      return block_start_[b + 1] > block_start_[b];
    });
  }

  // The first colour's strips are handed out before the second's, and a
  // strip of the second colour waits only for its two neighbours
  // (wait_for_strip), not for the whole first colour: with each colour's
  // strips a loop of its own, the second loop waited at the first's end
  // for its slowest strip, and with two threads and five strips of the
  // first colour, one thread ran three of them while the other waited (the
  // step ran 1.02 to 1.05 times as fast without that wait on two threads
  // at 1e5 particles, bench_step). Within a colour each thread takes its
  // own strips first (owner). The order of the additions at every node is
  // the same as with the two loops, whichever thread adds.
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
    const int threads = parallel ? max_threads() : 1;
    for (OwnedQueue& q : colour_queue_) q.reset(threads);
    for (int k = 0; k < strips; ++k)
      colour_queue_[k % 2].add(owner(group_start(k, 0), group_start(k, blocks_y_), threads), k);
#pragma omp parallel firstprivate(stage) if (parallel)
    for (OwnedQueue& queue : colour_queue_)
      queue.run(this_thread(), [&](int strip) {
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
  // A cell group's L and displacements (stages 6 and 7), in buffers of
  // its thread's, indexed from the group's smallest particle index: they
  // stay in the core's cache from the gradient to the stress update, and
  // are not written back to memory after it as whole-particle arrays were
  // (with the counting sort's runs, the two-thread step ran 1.07 to 1.09
  // times as fast at 1e6 particles, 1.02 at 1e5, bench_step).
  struct GroupScratch {
    StaggeredArray xx, xy, yx, yy, dx, dy;
    // The group's cell means, by the cell's place in the group
    // (particle_cell_): a cell's sums stay with the thread that takes
    // them, where in arrays over the whole grid box a group's cells were
    // in the cache of whichever thread had the group the step before. Two
    // sets: the stress update reads the volumetric rate's means while it
    // adds up the mean stress's.
    StaggeredArray volume[2] = {StaggeredArray(kGroupCellsX * kGroupCellsY),
                                StaggeredArray(kGroupCellsX * kGroupCellsY)};
    StaggeredArray mean[2] = {StaggeredArray(kGroupCellsX * kGroupCellsY),
                              StaggeredArray(kGroupCellsX * kGroupCellsY)};
    void fit(int count) {
      if (static_cast<int>(dx.size()) >= count) return;
      for (StaggeredArray* a : {&xx, &xy, &yx, &yy, &dx, &dy}) a->resize(count);
    }
  };
  class CellGroup;
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
    const auto by1 = [=](int k) { return std::min(by0(k) + kGroupRows, blocks_y_); };
    const bool parallel = particles_.size() > kParallelMin;
    const int threads = parallel ? max_threads() : 1;
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
      const int thread = this_thread();
      group_queue_.run(thread, [&](int k) {
        CellGroup cells(*this, k / bands, by0(k), by1(k), span_limit, group_scratch_[thread]);
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
    for (const GroupScratch& s : group_scratch_) most = std::max(most, s.dx.size());
    return static_cast<int>(most);
  }

  // Whoever takes the particles may move them.
  Particles& host_particles() {
    box_known_ = false;
    return particles_;
  }
  const Particles& host_particles() const { return particles_; }

  // The cells of kGroupRows block rows of one strip (each kStrip blocks
  // of kBlock x kBlock cells) and their particles, which lie together in
  // the block order: a few thousand, so what the driver's stages pass from
  // one of these loops to the next (gradients, displacements, cell means)
  // is still in the cache when the next reads it, where loops over all
  // particles had written it out to memory and read it back.
  class CellGroup {
   public:
    CellGroup(OpenMpBackend& b, int strip, int by0, int by1, int span_limit, GroupScratch& scratch)
        : b_(b), scratch_(scratch) {
      first_ = b.group_start(strip, by0);
      last_ = b.group_start(strip, by1);
      rows_ = std::min(by1 * kBlock, b.cells_y_) - by0 * kBlock;
      // The group's particle indices: since the last reorder, the run
      // first_ .. last_ - 1 and the few that have moved in from the groups
      // around it (whose indices lie near).
      int lo = std::numeric_limits<int>::max(), hi = -1;
      for (int q = first_; q < last_; ++q) {
        lo = std::min(lo, b.order_[q]);
        hi = std::max(hi, b.order_[q]);
      }
      if (hi < lo) return;
      // A particle that has crossed a periodic seam since the last reorder
      // keeps its index but joins a group at the other end of the box, so
      // the span lo .. hi can reach across all the particles: sized to it,
      // every thread's buffers would grow to the particle count.
      if (hi - lo < span_limit) {
        lowest_ = lo;
        scratch_.fit(hi - lo + 1);
      } else {
        arrays_ = &b.whole_particle_scratch();
      }
    }
    bool empty() const { return first_ == last_; }

    GradientView gradients() const {
      return {arrays_->xx.data(), arrays_->xy.data(), arrays_->yx.data(), arrays_->yy.data(),
              lowest_};
    }
    StepScratch scratch() const { return {arrays_->dx.data(), arrays_->dy.data(), lowest_}; }

    template <class Stage>
    void for_each_particle(Stage stage) const {
      for (int q = first_; q < last_; ++q) stage(b_.order_[q]);
    }
    template <class Stage>
    void for_each_particle_stencil(const GridView& g, const StepConfig& c, Stage stage) const {
      b_.for_each_four(g, c, first_, last_, [&](const int* p, const Stencil2D* st, int count) {
        for (int k = 0; k < count; ++k) stage(p[k], st[k]);
      });
    }

    // Four particles at a time where four in a row are also consecutive in
    // memory and share a material (stage.four): which ones depends on the
    // block order alone, so not on the number of threads. Also the box of
    // the particles where the stage moved them (box()), the next step's,
    // from the positions it has just stored (a pass of its own over the
    // group's particles cost 1.5 % of a step at 1e5 particles); the guards
    // have found them finite where no particle failed.
    template <class Stage>
    SpeedMax max_speed(Stage stage) {
      return max_speed_then(stage, [](int) {});
    }
    const ParticleBox& box() const { return box_; }

    // The same passes, with the group's cells' volume-weighted means of
    // mean_of(p), each particle's share added right after the stage has run
    // on it, in the group's order (the driver's kMeansInPasses), so the same
    // sums: in loops of their own the means read each particle's volume,
    // cell and value again (two threads ran 1.00 to 1.01 times as fast at
    // 1e5 particles and 1.00 to 1.02 at 1e6, bench_step; all of it from
    // the volumetric rate's means, the mean stress's alone changed nothing).
    static constexpr bool kMeansInPasses = true;
    template <class Stage, class Value>
    CellMeanView for_each_particle_stencil(const GridView& g, const StepConfig& c, Stage stage,
                                           Value mean_of) const {
      const CellSums sums = start_means(0);
      b_.for_each_four(g, c, first_, last_, [&](const int* p, const Stencil2D* st, int count) {
        for (int k = 0; k < count; ++k) {
          stage(p[k], st[k]);
          sums.add(p[k], mean_of(p[k]));
        }
      });
      return finish_means(0);
    }
    template <class Stage, class Value>
    SpeedMax max_speed(Stage stage, Value mean_of, CellMeanView& means) {
      const CellSums sums = start_means(1);
      const SpeedMax out = max_speed_then(stage, [&](int p) { sums.add(p, mean_of(p)); });
      means = finish_means(1);
      return out;
    }

   private:
    // The group's cell sums: volume and volume times the value, by the
    // cell's place in the group (particle_cell_).
    struct CellSums {
      double *volume, *mean;
      const double* vol;
      const int* cell;
      void add(int p, double value) const {
        volume[cell[p]] += vol[p];
        mean[cell[p]] += vol[p] * value;
      }
    };
    CellSums start_means(int set) const {
      double *const volume = scratch_.volume[set].data(), *const mean = scratch_.mean[set].data();
      const int cells = rows_ * kGroupCellsX;
      std::fill_n(volume, cells, 0.0);
      std::fill_n(mean, cells, 0.0);
      return {volume, mean, b_.particles_.vol.data(), b_.particle_cell_.data()};
    }
    CellMeanView finish_means(int set) const {
      double *const volume = scratch_.volume[set].data(), *const mean = scratch_.mean[set].data();
      const int cells = rows_ * kGroupCellsX;
      for (int c = 0; c < cells; ++c)
        if (volume[c] > 0.0) mean[c] /= volume[c];
      return {mean, b_.particle_cell_.data()};
    }

    // max_speed, with then(p) after the stage has run on p.
    template <class Stage, class Then>
    SpeedMax max_speed_then(Stage stage, Then then) {
      const int* const order = b_.order_.data();
      const double *const x = b_.particles_.x.data(), *const y = b_.particles_.y.data();
      const double inf = std::numeric_limits<double>::infinity();
      Lanes x0 = splat(inf), x1 = splat(-inf), y0 = x0, y1 = x1;
      const auto take = [&](const Lanes& px, const Lanes& py) {
        x0 = select_less(px, x0, px, x0);
        x1 = select_less(x1, px, px, x1);
        y0 = select_less(py, y0, py, y0);
        y1 = select_less(y1, py, py, y1);
      };
      SpeedMax out;
      for (int q = first_; q < last_;) {
        const int p = order[q];
        double s[4];
        if (q + 4 <= last_ && order[q + 1] == p + 1 && order[q + 2] == p + 2 &&
            order[q + 3] == p + 3 && stage.four(p, s)) {
          for (int k = 0; k < 4; ++k) {
            out.take(s[k]);
            then(p + k);
          }
          take(load_lanes(x + p), load_lanes(y + p));
          q += 4;
        } else {
          out.take(stage(p));
          then(p);
          take(splat(x[p]), splat(y[p]));
          ++q;
        }
      }
      box_ = {inf, -inf, inf, -inf, 0};
      for (int k = 0; k < 4; ++k) {
        box_.xmin = std::min(box_.xmin, lane(x0, k));
        box_.xmax = std::max(box_.xmax, lane(x1, k));
        box_.ymin = std::min(box_.ymin, lane(y0, k));
        box_.ymax = std::max(box_.ymax, lane(y1, k));
      }
      return out;
    }
    OpenMpBackend& b_;
    GroupScratch& scratch_;  // its thread's
    int first_, last_;      // the particles order_[first_ .. last_)
    int rows_;               // its rows of cells (kGroupCellsY, or fewer at the box's top)
    GroupScratch* arrays_ = &scratch_;  // L and the displacements: its thread's, or whole-particle
    int lowest_ = 0;         // the particle index at arrays_' start
    ParticleBox box_{};      // max_speed's
  };

 private:
  // The stencils of particles p[0 .. 3], four at a time (GIMP), from their
  // positions and the half-widths the binning stored: made again in each
  // pass that needs them, where storing the 160 bytes of each and reading
  // them back in three passes made the step wait on memory (docs/engine.md,
  // "Shape functions"). Out of line, so that its arithmetic is compiled
  // once: a particle has the same stencil in every pass, whichever three it
  // is made with.
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
      block[p] = static_cast<int>(((bi / kStrip) * blocks_up + cj / kBlock) * kStrip + bi % kStrip);
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
    sort_by_block(blocks, bin_range);
  }

  // Stable counting sort: within a block particles keep their index order,
  // which fixes the order of the sums at every node. Each thread bins
  // (bin(p0, p1): each particle's block), counts and places one contiguous
  // range of the particles, the ranges in index order, so the order is the
  // serial sort's whatever the number of threads; done on one, it kept the
  // other waiting 6 % of a two-thread step (1e5 particles). Binning and
  // sorting in one parallel region, rather than one each, saves waking the
  // other threads once (the CLI's wait, openmp_wait.hpp).
  template <class Bin>
  void sort_by_block(int blocks, Bin bin) {
    const int n = particles_.size();
    const int* const block = particle_block_.data();
    int* const order = order_.data();
    block_start_.assign(blocks + 1, 0);
    next_.resize(static_cast<std::size_t>(max_threads()) * blocks);
#pragma omp parallel firstprivate(bin) if (n > kParallelMin)
    {
      const int t = this_thread(), threads = team_threads();
      // next_: thread t's count in each block, then its next place there.
      int* const next = next_.data() + static_cast<std::size_t>(t) * blocks;
      std::fill_n(next, blocks, 0);
      const auto start_of = [&](int u) {  // a multiple of four, for bin
        return u == threads ? n : 4 * static_cast<int>(static_cast<long>(n / 4) * u / threads);
      };
      const int p0 = start_of(t), p1 = start_of(t + 1);
      bin(p0, p1);
      count_runs(block, p0, p1, next);
#pragma omp barrier
#pragma omp single
      {
        int start = 0;
        for (int b = 0; b < blocks; ++b) {
          block_start_[b] = start;
          for (int u = 0; u < threads; ++u) {
            int& slot = next_[static_cast<std::size_t>(u) * blocks + b];
            const int count = slot;
            slot = start;
            start += count;
          }
        }
        block_start_[blocks] = start;
      }
      place_runs(block, p0, p1, next, order);
    }
  }

  // The counting sort's two passes over a thread's range, run by run of
  // particles of one block: the particles lie in block order since the
  // last reorder, bar the few that have moved since, so runs are long, and
  // a count kept in a register does not wait, particle after particle, on
  // the store of the one before it (++next[block[p]] did).
  static void count_runs(const int* block, int p0, int p1, int* count) {
    if (p0 == p1) return;
    int run_block = block[p0], run = 0;
    for (int p = p0; p < p1; ++p) {
      if (block[p] != run_block) {
        count[run_block] += run;
        run_block = block[p];
        run = 0;
      }
      ++run;
    }
    count[run_block] += run;
  }
  static void place_runs(const int* block, int p0, int p1, int* next, int* order) {
    if (p0 == p1) return;
    int run_block = block[p0], at = next[run_block];
    for (int p = p0; p < p1; ++p) {
      if (block[p] != run_block) {
        next[run_block] = at;
        run_block = block[p];
        at = next[run_block];
      }
      order[at++] = p;
    }
    next[run_block] = at;
  }

  // Work handed out owner first: each thread takes the items of its own
  // list, then those left in the others' lists, so that the load stays
  // balanced.
  class OwnedQueue {
   public:
    void reset(int lists) {
      if (static_cast<int>(lists_.size()) != lists) {
        lists_.resize(lists);
        taken_ = std::vector<std::atomic<int>>(lists);
      }
      for (int l = 0; l < lists; ++l) {
        lists_[l].clear();
        taken_[l].store(0, std::memory_order_relaxed);
      }
    }
    void add(int list, int item) { lists_[list].push_back(item); }
    // f(item) for each item this thread takes; on every thread, each item once.
    template <class F>
    void run(int thread, F&& f) {
      const int lists = static_cast<int>(lists_.size());
      for (int u = 0; u < lists; ++u) {
        const int l = (thread + u) % lists;
        const int size = static_cast<int>(lists_[l].size());
        for (int at; (at = taken_[l].fetch_add(1, std::memory_order_relaxed)) < size;)
          f(lists_[l][at]);
      }
    }

   private:
    std::vector<std::vector<int>> lists_;
    std::vector<std::atomic<int>> taken_;  // how far each list has been handed out
  };

  // The thread (of threads) that bins the middle particle of
  // order_[first, last), the particles of a strip or a cell group: each
  // thread bins one range of the particles' indices (sort_by_block), which
  // since the last reorder are those of a run of whole strips, and takes
  // the same particles first in the scatters and the cell groups, so that
  // they are mostly in its own core's cache from one pass to the next: the
  // two-thread step ran 1.03 to 1.05 times as fast at 1e5 particles and
  // 1.01 to 1.02 at 1e6 as with one queue for all threads (bench_step).
  // Taken by whichever thread comes first, a strip's particles were read
  // from the other core's cache as often as not.
  int owner(int first, int last, int threads) const {
    const long n = std::max<long>(1, static_cast<long>(order_.size()));
    const long middle = (first + static_cast<long>(last)) / 2;
    return static_cast<int>(std::min<long>(threads - 1, middle * threads / n));
  }
  static int max_threads() {
#ifdef _OPENMP
    return omp_get_max_threads();
#else
    return 1;
#endif
  }
  static int this_thread() {
#ifdef _OPENMP
    return omp_get_thread_num();
#else
    return 0;
#endif
  }
  static int team_threads() {  // in the parallel region that calls it
#ifdef _OPENMP
    return omp_get_num_threads();
#else
    return 1;
#endif
  }

  // Sized once, on whichever thread first needs it; the groups that use it
  // write only their own particles' places.
  GroupScratch& whole_particle_scratch() {
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
  std::vector<GroupScratch> group_scratch_;     // a thread's, for its cell groups
  GroupScratch whole_particle_scratch_;          // for groups whose span passes the limit
  OwnedQueue colour_queue_[2], group_queue_;  // the scatters', the cell groups' work
  int blocks_y_ = 0, strips_ = 0, cells_y_ = 0;
  ParticleBox box_{};  // bounding_box's, when box_known_
  bool box_known_ = false;
};

}  // namespace runout
