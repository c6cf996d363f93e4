#pragma once
// The CPU backend's cell groups (backend_openmp.hpp): what its
// for_cell_groups hands the driver's stages 6 and 7 (CellGroupPasses,
// backend_concept.hpp), and the buffers a thread keeps for them.
#include <algorithm>
#include <limits>

#include "runout/mpm/lanes.hpp"
#include "runout/mpm/stages.hpp"
#include "runout/mpm/staggered_allocator.hpp"
#include "runout/mpm/step_views.hpp"

namespace runout {

// A cell group's L and displacements (stages 6 and 7), in buffers of its
// thread's, indexed from the group's smallest particle index: they stay in
// the core's cache from the gradient to the stress update, where
// whole-particle arrays went out to memory. kCells: a group's cells.
template <int kCells>
struct GroupScratch {
  StaggeredArray xx, xy, yx, yy, dx, dy;
  // The group's cell means, by the cell's place in the group
  // (particle_cell_), so a cell's sums stay with the thread that takes
  // them. Two sets: the stress update reads the volumetric rate's means
  // while it adds up the mean stress's.
  StaggeredArray volume[2] = {StaggeredArray(kCells), StaggeredArray(kCells)};
  StaggeredArray mean[2] = {StaggeredArray(kCells), StaggeredArray(kCells)};
  void fit(int count) {
    if (static_cast<int>(dx.size()) >= count) return;
    for (StaggeredArray* a : {&xx, &xy, &yx, &yy, &dx, &dy}) a->resize(count);
  }
};

// The cells of kGroupRows block rows of one strip (each kStrip blocks of
// kBlock x kBlock cells) and their particles, which lie together in the
// block order: a few thousand, so what the driver's stages pass from one
// of these loops to the next (gradients, displacements, cell means) is
// still in the cache when the next reads it. Backend: OpenMpBackend, whose
// block order and arrays it reads.
template <class Backend>
class CellGroup {
  using Scratch = typename Backend::Scratch;
  static constexpr int kBlock = Backend::kBlock, kGroupCellsX = Backend::kGroupCellsX;

 public:
  CellGroup(Backend& b, int strip, int by0, int by1, int span_limit, Scratch& scratch)
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
  // which saves a pass of its own; the guards have found them finite where
  // no particle failed.
  template <class Stage>
  SpeedMax max_speed(Stage stage) {
    return max_speed_then(stage, [](int) {});
  }
  const ParticleBox& box() const { return box_; }

  // The same passes, with the group's cells' volume-weighted means of
  // mean_of(p) (MeansInPasses, backend_concept.hpp): each particle's share
  // added right after the stage has run on it, in the group's order, so
  // the sums of a loop of their own without reading each particle again.
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
  Backend& b_;
  Scratch& scratch_;       // its thread's
  int first_, last_;      // the particles order_[first_ .. last_)
  int rows_;               // its rows of cells (kGroupCellsY, or fewer at the box's top)
  Scratch* arrays_ = &scratch_;  // L and the displacements: its thread's, or whole-particle
  int lowest_ = 0;         // the particle index at arrays_' start
  ParticleBox box_{};      // max_speed's
};

}  // namespace runout
