#pragma once
// What the two host backends of the driver (driver.hpp) share: the
// particles and the grid in host memory, the step's per-particle arrays,
// and the primitives that do not depend on how loops are run. The OpenMP
// backend (backend_openmp.hpp) and the serial device backend
// (backend_serial.hpp) add the loops, the binning and the scatter.
#include <algorithm>
#include <utility>
#include <vector>

#include "runout/mpm/grid.hpp"
#include "runout/mpm/lanes.hpp"
#include "runout/mpm/material.hpp"
#include "runout/mpm/nonlocal.hpp"
#include "runout/mpm/particles.hpp"
#include "runout/mpm/stages.hpp"
#include "runout/mpm/step_views.hpp"

namespace runout {

class Base;  // the rigid base: the host backends use the driver's own

class HostBackend {
 public:
  HostBackend(Particles particles, const std::vector<MaterialParams>& materials,
              const std::vector<double>& nonlocal_lengths)
      : particles_(std::move(particles)), materials_(materials), lengths_(nonlocal_lengths) {
    const std::size_t n = particles_.size();
    const bool nonlocal = std::any_of(lengths_.begin(), lengths_.end(), [](double l) { return l > 0; });
    if (nonlocal)
      for (auto* a : {&xi_start_, &xi_local_, &xi_average_}) a->assign(n, 0.0);
  }

  Particles& host_particles() { return particles_; }
  const Particles& host_particles() const { return particles_; }
  ParticleView particles() { return particles_.view(); }
  const Grid& grid() const { return grid_; }

  GridView fit_grid(const GridView& placed) {
    const GridView& g = grid_.fit(placed);
    for (int n = 0; n < g.size(); ++n) clear_node(g, n);
    return g;
  }
  // The base's force is summed in node order, so the same every run.
  double sum_nodes(const GridView& g, const double* a) const {
    double total = 0;
    for (int i = 0; i < g.size(); ++i) total += a[i];
    return total;
  }
  void fill_nodes(const GridView& g, double* a, double v) const { std::fill_n(a, g.size(), v); }

  double* xi_start() { return xi_start_.data(); }
  double* xi_local() { return xi_local_.data(); }
  double* xi_average() { return xi_average_.data(); }
  void nonlocal_average(NonlocalAverage& nonlocal, const double* in, double* out) {
    const ParticleView P = particles_.view();
    nonlocal.apply({P.n, P.x, P.y, P.vol, P.material}, in, out);
  }
  const double* nonlocal_lengths() const { return lengths_.data(); }
  const MaterialParams* materials() const { return materials_.data(); }
  const StepConfig& kernel_config(const StepConfig& c) const { return c; }

 protected:
  Particles particles_;
  Grid grid_;
  std::vector<MaterialParams> materials_;
  std::vector<double> lengths_;
  // Staggered in their pages (staggered_allocator.hpp), as the particles'.
  StaggeredArray xi_start_, xi_local_, xi_average_;  // nonlocal runs only
};

}  // namespace runout
