#pragma once
// The serial device backend of the driver (driver.hpp): the CUDA backend's
// way of running the step, on one CPU thread, so that the code path the GPU
// takes is tested on machines without one (tests/test_device_backend.cpp).
// As engine/cuda/backend_cuda.cuh: the particles are sorted by cell at
// every step (a stable sort, as CUB's radix sort), each pass computes the
// stencil afresh instead of storing it, a scatter adds each particle's
// shares straight to the nodes with no colouring (atomics on the GPU, in
// particle order here), the cell means are sums scattered by particle, and
// the nonlocal average goes element by element (nonlocal_by_elements.hpp).
// Only the order of the additions differs from the GPU's, so results
// agree with the OpenMP backend's to rounding, not bit for bit.
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "runout/mpm/backend_concept.hpp"
#include "runout/mpm/backend_host.hpp"
#include "runout/mpm/nonlocal_by_elements.hpp"

namespace runout {

class SerialDeviceBackend : public HostBackend, public HostNonlocalLattice {
 public:
  SerialDeviceBackend(Particles particles, const std::vector<MaterialParams>& materials,
                      const Base&, const std::vector<double>& nonlocal_lengths)
      : HostBackend(std::move(particles), materials, nonlocal_lengths) {
    const std::size_t n = particles_.size();
    cell_.assign(n, 0);
    for (auto* a : {&dx_, &dy_, &lxx_, &lxy_, &lyx_, &lyy_}) a->assign(n, 0.0);
  }

  ParticleBox bounding_box() {
    const ParticleView P = particles_.view();
    ParticleBox b{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                  std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                  0};
    for (int p = 0; p < P.n; ++p) {
      if (!(std::isfinite(P.x[p]) && std::isfinite(P.y[p]))) {
        ++b.non_finite;
        continue;
      }
      b.xmin = std::min(b.xmin, P.x[p]);
      b.xmax = std::max(b.xmax, P.x[p]);
      b.ymin = std::min(b.ymin, P.y[p]);
      b.ymax = std::max(b.ymax, P.y[p]);
    }
    return b;
  }

  // The particles in cell order, every step.
  void bin(const GridView& g, const StepConfig&, long) {
    const ParticleView P = particles_.view();
    const int cells = (g.nx - 1) * (g.ny - 1);
    std::vector<int> key(P.n), start(cells + 1, 0), order(P.n);
    for (int p = 0; p < P.n; ++p) {
      const int ci = cell_of(P.x[p], g.ox, g.h), cj = cell_of(P.y[p], g.oy, g.h);
      key[p] = cj * (g.nx - 1) + ci;
      ++start[key[p] + 1];
    }
    for (int c = 0; c < cells; ++c) start[c + 1] += start[c];
    for (int p = 0; p < P.n; ++p) {
      const int q = start[key[p]]++;
      order[q] = p;
      cell_[q] = key[p];
    }
    particles_.permute(order);
  }

  template <class Stage>
  void scatter(const GridView& g, const StepConfig& c, Stage stage) {
    const PlainAdd add;
    const auto lower = [](double* a, int n, double v) { a[n] = std::min(a[n], v); };
    const ParticleView P = particles_.view();
    Stencil2D st;
    for (int p = 0; p < P.n; ++p) {
      make_stencil(g, c, P, p, st);
      stage(p, st, add, lower);
    }
  }

  template <class Stage>
  void for_each(int count, Stage stage) {
    for (int i = 0; i < count; ++i) stage(i);
  }
  template <class Stage>
  void for_each_node(const GridView& g, Stage stage) {  // every node of the box, as on the GPU
    for_each(g.size(), stage);
  }
  template <class Stage>
  void for_each_particle(Stage stage) {
    for_each(particles_.size(), stage);
  }
  template <class Stage>
  void for_each_particle_stencil(const GridView& g, const StepConfig& c, Stage stage) {
    const ParticleView P = particles_.view();
    Stencil2D st;
    for (int p = 0; p < P.n; ++p) {
      make_stencil(g, c, P, p, st);
      stage(p, st);
    }
  }

  template <class Stage>
  SpeedMax max_speed(Stage stage) {
    SpeedMax out;
    for (int p = 0; p < particles_.size(); ++p) {
      out.take(stage(p));
    }
    return out;
  }

  // One group: every cell.
  template <class F>
  SpeedMax for_cell_groups(const GridView&, const StepConfig&, F&& f) {
    return f(*this);
  }
  void nonlocal_average(NonlocalAverage& nonlocal, const double* in, double* out) {
    const ParticleView P = particles_.view();
    std::copy_n(in, P.n, out);
    const ParticleBox box = bounding_box();
    if (P.n == 0 || box.non_finite > 0) return;  // the step's guards report it
    average_by_elements(*this, nonlocal, P, box, nonlocal.mirror(), in, out, PlainAdd{});
  }

  // The one cell group's L and displacements: every particle's.
  GradientView gradients() { return {lxx_.data(), lxy_.data(), lyx_.data(), lyy_.data()}; }
  StepScratch scratch() { return {dx_.data(), dy_.data()}; }

  template <class Value>
  CellMeanView cell_means(const GridView& g, Value value) {
    const ParticleView P = particles_.view();
    const int cells = (g.nx - 1) * (g.ny - 1);
    cell_volume_.assign(cells, 0.0);
    cell_mean_.assign(cells, 0.0);
    for (int p = 0; p < P.n; ++p) {
      cell_volume_[cell_[p]] += P.vol[p];
      cell_mean_[cell_[p]] += P.vol[p] * value(p);
    }
    for (int c = 0; c < cells; ++c)
      cell_mean_[c] = cell_volume_[c] > 0.0 ? cell_mean_[c] / cell_volume_[c] : 0.0;
    return {cell_mean_.data(), cell_.data()};
  }

 private:
  std::vector<int> cell_;  // each (sorted) particle's cell in the grid box
  StaggeredArray dx_, dy_, lxx_, lxy_, lyx_, lyy_;
  StaggeredArray cell_volume_, cell_mean_;  // per cell of the grid box
};

static_assert(Backend<SerialDeviceBackend> && CellGroupPasses<SerialDeviceBackend>);

}  // namespace runout
