#pragma once
// The driver's backend contract (driver.hpp), as concepts: what a Backend
// offers the step, what the group of cells that for_cell_groups hands the
// driver's stages 6 and 7 offers (CellGroupPasses), and the two ways of
// taking that group's cell means (MeansInPasses, MeansAfterPasses).
// Driver<B> takes only a Backend, and each backend's header checks its own
// with a static_assert: OpenMpBackend (backend_openmp.hpp),
// SerialDeviceBackend (backend_serial.hpp), CudaBackend
// (engine/cuda/backend_cuda.cuh, where nvcc compiles it).
//
// A backend's loops are templates over the driver's stage functors
// (driver.hpp, namespace stage), so the concepts call them with the
// stand-ins of backend_probe: they check names, arguments and results;
// the driver's instantiations (simulation.cpp, cuda_simulation.cu) check
// the bodies with the real stages.
#include <concepts>
#include <vector>

#include "runout/mpm/base.hpp"
#include "runout/mpm/grid.hpp"
#include "runout/mpm/material.hpp"
#include "runout/mpm/nonlocal.hpp"
#include "runout/mpm/particles.hpp"
#include "runout/mpm/step_config.hpp"
#include "runout/mpm/step_views.hpp"

namespace runout {

// Declared only: the concepts use them unevaluated.
namespace backend_probe {

struct IndexStage {  // stage(i): a node, a node row or a particle
  void operator()(int) const;
};
struct ScatterStage {  // stage(p, stencil, add, lower): adds p's shares to its nodes
  template <class St, class Add, class Lower>
  void operator()(int, const St&, Add, Lower) const;
  bool derivatives() const;  // whether it reads the stencil's derivatives
};
struct StencilStage {  // stage(p, stencil)
  template <class St>
  void operator()(int, const St&) const;
};
struct SpeedStage {  // p's signal speed, -1 where p fails a guard
  double operator()(int) const;
  bool four(int, double speeds[4]) const;  // p .. p + 3 at once, where it can (the CPU's)
};
struct Value {  // a particle's value, whose cell means are taken
  double operator()(int) const;
};
struct GroupPass {  // the driver's stages 6 and 7 on one group of cells
  template <class Cells>
  SpeedMax operator()(Cells&) const;
};

}  // namespace backend_probe

// What for_cell_groups hands the driver: a group of whole cells, its
// particles' L and displacements, and the loops over its particles.
template <class C>
concept CellGroupLoops = requires(C& cells, const GridView& g, const StepConfig& c,
                                  backend_probe::IndexStage each,
                                  backend_probe::StencilStage stencil,
                                  backend_probe::SpeedStage speed) {
  { cells.gradients() } -> std::convertible_to<GradientView>;
  { cells.scratch() } -> std::convertible_to<StepScratch>;
  cells.for_each_particle(each);                    // stage(p)
  cells.for_each_particle_stencil(g, c, stencil);  // stage(p, stencil)
  // The largest stage(p), and how many were negative (faults).
  { cells.max_speed(speed) } -> std::same_as<SpeedMax>;
};

// The cells' volume-weighted means of value(p), in a loop of their own
// after the pass that set what value(p) reads.
template <class C>
concept MeansAfterPasses = requires(C& cells, const GridView& g, backend_probe::Value value) {
  { cells.cell_means(g, value) } -> std::convertible_to<CellMeanView>;
};

// The same means taken in the pass itself, each particle's share added
// right after the stage has run on it (the CPU's): the driver prefers
// these where a group has them.
template <class C>
concept MeansInPasses = requires(C& cells, const GridView& g, const StepConfig& c,
                                 backend_probe::StencilStage stencil,
                                 backend_probe::SpeedStage speed, backend_probe::Value value,
                                 CellMeanView& means) {
  { cells.for_each_particle_stencil(g, c, stencil, value) } -> std::convertible_to<CellMeanView>;
  { cells.max_speed(speed, value, means) } -> std::same_as<SpeedMax>;  // the means into means
};

template <class C>
concept CellGroupPasses = CellGroupLoops<C> && (MeansInPasses<C> || MeansAfterPasses<C>);

// How a backend runs the driver's step: the particles and the grid box in
// its memory, and its loops.
template <class B>
concept Backend =
    std::constructible_from<B, Particles, const std::vector<MaterialParams>&, const Base&,
                            const std::vector<double>&> &&  // particles, materials, base, l
    requires(B& b, const GridView& g, const StepConfig& c, long step, double* a,
             const double* in, double v, NonlocalAverage& nonlocal,
             backend_probe::IndexStage each, backend_probe::ScatterStage scatter,
             backend_probe::GroupPass pass) {
      { b.particles() } -> std::convertible_to<ParticleView>;     // in the backend's memory
      { b.bounding_box() } -> std::convertible_to<ParticleBox>;   // and the non-finite count
      { b.fit_grid(g) } -> std::convertible_to<GridView>;         // the box's arrays, cleared
      b.bin(g, c, step);            // whatever scatter needs (blocks, a sort)
      b.scatter(g, c, scatter);     // stage(p, stencil, add, lower) per particle
      b.for_each(0, each);          // stage(i) per node row
      b.for_each_node(g, each);     // stage(n) per node the particles reach (or every node)
      b.for_each_particle(each);    // stage(p)
      { b.sum_nodes(g, in) } -> std::convertible_to<double>;  // over the box's nodes
      b.fill_nodes(g, a, v);        // a = v where for_each_node goes
      // f(cells) for groups of whole cells (CellGroupPasses, which the
      // driver's f asks of them); the sum of the SpeedMax they return.
      { b.for_cell_groups(g, c, pass) } -> std::same_as<SpeedMax>;
      // Regularised softening (nonlocal.hpp): xi at the step's start, its
      // local increment and the increment's nonlocal average, per particle
      // (allocated in regularised runs only).
      { b.xi_start() } -> std::same_as<double*>;
      { b.xi_local() } -> std::same_as<double*>;
      { b.xi_average() } -> std::same_as<double*>;
      b.nonlocal_average(nonlocal, in, a);
      { b.nonlocal_lengths() } -> std::convertible_to<const double*>;  // per material
      { b.materials() } -> std::convertible_to<const MaterialParams*>;
      { b.kernel_config(c) } -> std::convertible_to<StepConfig>;  // c with the backend's base
      { b.host_particles() } -> std::convertible_to<const Particles&>;  // for the guards' report
    };

}  // namespace runout
