#pragma once
// The CUDA backend of the driver (driver.hpp): the particles and the grid
// on the device, one thread per particle or node. Each primitive is one
// generic kernel that calls the driver's stage functor, so the GPU runs the
// step the CPU tests exercise; the serial device backend
// (backend_serial.hpp) runs this backend's order of work on the CPU.
// Only nvcc includes this file (cuda_simulation.cu).
#include <cub/device/device_radix_sort.cuh>
#include <math_constants.h>

#include <cstdint>
#include <limits>
#include <vector>

#include "cuda_simulation.cuh"
#include "runout/mpm/base.hpp"
#include "runout/mpm/driver.hpp"
#include "runout/mpm/nonlocal_by_elements.hpp"

namespace runout {
namespace cuda {

// Raw device pointers of one copy of the particle arrays, plus origin: the
// particle's index in the order it was given, which download() restores.
struct Fields {
  double* d[kParticleDoubles];
  int* body;
  int* material;
  std::int64_t* id;
  int* origin;
};

// Device storage of the particles, twice: the step sorts them by cell from
// one copy into the other.
struct ParticleSet {
  Buffer<double> d[kParticleDoubles];
  Buffer<int> body, material, origin;
  Buffer<std::int64_t> id;
  void reserve(int n);
  Fields fields() const;
};

// ---- Reductions -----------------------------------------------------------

struct BoxOp {  // the bounding box, and how many positions are not finite
  using T = ParticleBox;
  const double *x, *y;
  __device__ T identity() const { return {CUDART_INF, -CUDART_INF, CUDART_INF, -CUDART_INF, 0}; }
  __device__ T combine(const T& a, const T& b) const {
    return {fmin(a.xmin, b.xmin), fmax(a.xmax, b.xmax), fmin(a.ymin, b.ymin),
            fmax(a.ymax, b.ymax), a.non_finite + b.non_finite};
  }
  __device__ T load(int i) const {
    const double xi = x[i], yi = y[i];
    if (!isfinite(xi) || !isfinite(yi)) {
      T b = identity();
      b.non_finite = 1;
      return b;
    }
    return {xi, xi, yi, yi, 0};
  }
};

struct SpeedOp {  // the largest speed; a negative or non-finite one is a fault
  using T = SpeedMax;
  const double* speed;
  __device__ T identity() const { return {0.0, 0}; }
  __device__ T combine(const T& a, const T& b) const { return {fmax(a.max, b.max), a.bad + b.bad}; }
  __device__ T load(int i) const {
    const double s = speed[i];
    return isfinite(s) && s >= 0.0 ? T{s, 0} : T{0.0, 1};
  }
};

struct Sum {
  double v;
};
struct SumOp {
  using T = Sum;
  const double* a;
  __device__ Sum identity() const { return {0.0}; }
  __device__ Sum combine(const Sum& x, const Sum& y) const { return {x.v + y.v}; }
  __device__ Sum load(int i) const { return {a[i]}; }
};

// ---- Scatter functors -----------------------------------------------------

// Double atomicAdd (sm_60+). Particles are sorted by cell, so the threads
// of a warp mostly hit the same 3 x 3 to 4 x 4 nodes: the atomics contend
// but stay in L2. A faster version first sums a block's particles into a
// shared-memory tile of the nodes the block's cells touch and then adds the
// tile to global memory, or reduces runs of equal node indices within a
// warp (__match_any_sync) before one atomic per run.
struct AtomicAdd {
  __device__ void operator()(double* a, int n, double v) const { atomicAdd(a + n, v); }
  // A stencil row: one of its four lanes has zero weight (shape.hpp), so
  // three atomics; an exact zero added would change no sum.
  __device__ void operator()(double* a, int n0, const Lanes& v) const {
    for (int k = 0; k < 4; ++k)
      if (v.v[k] != 0.0) atomicAdd(a + n0 + k, v.v[k]);
  }
};

// The nodal gap's minimum: CUDA has no double atomicMin, so compare and
// swap until the stored value is at most v.
struct AtomicMin {
  __device__ void operator()(double* a, int n, double v) const {
    auto* address = reinterpret_cast<unsigned long long*>(a + n);
    unsigned long long old = *address;
    while (v < __longlong_as_double(static_cast<long long>(old))) {
      const unsigned long long assumed = old;
      old = atomicCAS(address, assumed, static_cast<unsigned long long>(__double_as_longlong(v)));
      if (old == assumed) break;
    }
  }
};

// ---- Generic kernels: the driver's stage functors, one thread each -------

// The stencil is recomputed in each kernel from the start-of-step position
// (the particle moves only in the stress stage, the last one): cheaper
// than storing 112 bytes per particle and reading them back four times.
__device__ inline Stencil2D stencil_of(const ParticleView& P, int p, const GridView& g,
                                       const StepConfig& c) {
  Stencil2D st;
  make_stencil(g, c, P, p, st);
  return st;
}

template <class Stage>
__global__ void for_each_kernel(int count, Stage stage) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < count) stage(i);
}

template <class Stage>
__global__ void scatter_kernel(ParticleView P, GridView g, StepConfig c, Stage stage) {
  const int p = blockIdx.x * blockDim.x + threadIdx.x;
  if (p < P.n) stage(p, stencil_of(P, p, g, c), AtomicAdd{}, AtomicMin{});
}

template <class Stage>
__global__ void stencil_kernel(ParticleView P, GridView g, StepConfig c, Stage stage) {
  const int p = blockIdx.x * blockDim.x + threadIdx.x;
  if (p < P.n) stage(p, stencil_of(P, p, g, c));
}

template <class Stage>
__global__ void speed_kernel(int n, Stage stage, double* speed) {
  const int p = blockIdx.x * blockDim.x + threadIdx.x;
  if (p < n) speed[p] = stage(p);
}

template <class Value>
__global__ void cell_sum_kernel(ParticleView P, const int* cell, Value value, double* vol,
                                double* sum) {
  const int p = blockIdx.x * blockDim.x + threadIdx.x;
  if (p >= P.n) return;
  atomicAdd(vol + cell[p], P.vol[p]);
  atomicAdd(sum + cell[p], P.vol[p] * value(p));
}

}  // namespace cuda

class CudaBackend {
 public:
  // Uploads the particles (in the order given), the materials and the base.
  // Throws std::runtime_error when no device can be used.
  CudaBackend(Particles particles, const std::vector<MaterialParams>& materials, const Base& base,
              const std::vector<double>& nonlocal_lengths);

  ParticleView particles() const;
  ParticleBox bounding_box();
  GridView fit_grid(const GridView& placed);
  void bin(const GridView& g, const StepConfig& c, long step);  // a stable sort by cell

  template <class Stage>
  void scatter(const GridView& g, const StepConfig& c, Stage stage) {
    cuda::scatter_kernel<<<cuda::blocks_for(n_), cuda::kThreads>>>(particles(), g, c, stage);
    RUNOUT_CUDA_LAUNCHED("scatter");
  }
  template <class Stage>
  void for_each(int count, Stage stage) {
    cuda::for_each_kernel<<<cuda::blocks_for(count), cuda::kThreads>>>(count, stage);
    RUNOUT_CUDA_LAUNCHED("for_each");
  }
  template <class Stage>
  void for_each_node(const GridView& g, Stage stage) {  // every node of the box
    for_each(g.size(), stage);
  }
  template <class Stage>
  void for_each_particle(Stage stage) {
    for_each(n_, stage);
  }
  template <class Stage>
  void for_each_particle_stencil(const GridView& g, const StepConfig& c, Stage stage) {
    cuda::stencil_kernel<<<cuda::blocks_for(n_), cuda::kThreads>>>(particles(), g, c, stage);
    RUNOUT_CUDA_LAUNCHED("for_each_particle_stencil");
  }
  template <class Stage>
  SpeedMax max_speed(Stage stage) {
    cuda::speed_kernel<<<cuda::blocks_for(n_), cuda::kThreads>>>(n_, stage, speed_.get());
    RUNOUT_CUDA_LAUNCHED("max_speed");
    return reduce_speed();
  }
  // One group: every cell.
  template <class F>
  SpeedMax for_cell_groups(const GridView&, const StepConfig&, F&& f) {
    return f(*this);
  }
  template <class Value>
  CellMeanView cell_means(const GridView&, Value value) {
    clear_cells();
    cuda::cell_sum_kernel<<<cuda::blocks_for(n_), cuda::kThreads>>>(
        particles(), keys_out_.get(), value, cell_vol_.get(), cell_sum_.get());
    RUNOUT_CUDA_LAUNCHED("cell sums");
    return divide_cells();
  }
  double sum_nodes(const GridView& g, const double* a);
  void fill_nodes(const GridView& g, double* a, double v);

  GradientView gradients() const { return {lxx_.get(), lxy_.get(), lyx_.get(), lyy_.get()}; }
  StepScratch scratch() const { return {dx_.get(), dy_.get()}; }
  double* xi_start() const { return xi_start_.get(); }
  double* xi_local() const { return xi_local_.get(); }
  double* xi_average() const { return xi_average_.get(); }
  // On the device, element by element (nonlocal_by_elements.hpp), the
  // spread with atomics; only the particles' box comes to the host.
  void nonlocal_average(NonlocalAverage& nonlocal, const double* in, double* out);
  NonlocalLatticeArrays lattice_arrays(int nodes);
  NonlocalTaps lattice_taps(const NonlocalAverage& nonlocal, int m);
  const double* nonlocal_lengths() const { return lengths_.get(); }
  const MaterialParams* materials() const { return materials_.get(); }
  StepConfig kernel_config(const StepConfig& c) const;  // the base's device arrays
  BaseView on_device(BaseView base) const;  // the polyline's arrays swapped for their device copies

  // The particles on the host, in the order they were given; host_particles
  // keeps its own copy (for the guards' report).
  void download(Particles& out) const;
  const Particles& host_particles();
  int size() const { return n_; }

 private:
  SpeedMax reduce_speed();
  void clear_cells();
  CellMeanView divide_cells();

  int n_;
  mutable int current_ = 0;  // the set that holds the particles
  mutable cuda::ParticleSet sets_[2];
  cuda::Buffer<double> dx_, dy_, lxx_, lxy_, lyx_, lyy_, speed_;
  cuda::Buffer<double> xi_start_, xi_local_, xi_average_;
  cuda::Buffer<int> keys_in_, keys_out_, values_in_, values_out_;
  cuda::Buffer<unsigned char> sort_temp_;
  static constexpr int kGridArrays = 23;  // the double arrays of GridView
  cuda::Buffer<double> grid_arrays_[kGridArrays];
  int cells_ = 0;
  cuda::Buffer<double> cell_vol_, cell_sum_, cell_mean_;
  cuda::Buffer<MaterialParams> materials_;
  cuda::Buffer<double> lengths_;
  cuda::Buffer<double> base_px_, base_py_, base_ps_;
  cuda::Buffer<BaseSegment> base_seg_;
  cuda::Buffer<unsigned char> partials_;  // a reduction's first pass
  cuda::Buffer<ParticleBox> box_;
  cuda::Buffer<SpeedMax> speed_max_;
  cuda::Buffer<cuda::Sum> sum_;
  Particles host_;
  cuda::Buffer<double> lattice_inc_, lattice_vol_, lattice_pass_;  // nonlocal_average's
  cuda::Buffer<double> taps_;   // per regularised material its taps along x, then y
  std::vector<long> taps_at_;  // where each material's start; empty: not uploaded yet
};

static_assert(Backend<CudaBackend> && CellGroupPasses<CudaBackend>);

}  // namespace runout
