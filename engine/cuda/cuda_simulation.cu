// The CUDA driver: the CPU driver's step (simulation.cpp) with the state on
// the device. Every kernel calls the stage functions of stages.hpp, one
// thread per particle or per node, so both backends have one source of the
// physics. See docs/cuda.md for the design and what a faster version does.
#include <cub/device/device_radix_sort.cuh>
#include <math_constants.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>

#include "cuda_simulation.cuh"
#include "runout/cuda_simulation.hpp"
#include "runout/materials.hpp"
#include "runout/scene_parser.hpp"  // SceneError
#include "runout/seeding.hpp"
#include "runout/stages.hpp"

namespace runout {
namespace {

using cuda::blocks_for;
using cuda::Buffer;
using cuda::kThreads;

// The 16 double fields of a particle, in ParticleView's order.
constexpr int kDoubleFields = kParticleDoubles;
using DoubleField = std::vector<double> Particles::*;
const DoubleField kHostDoubles[kDoubleFields] = {
    &Particles::x,   &Particles::y,   &Particles::vx,        &Particles::vy,
    &Particles::mass, &Particles::vol0, &Particles::vol,     &Particles::sxx,
    &Particles::syy, &Particles::sxy, &Particles::szz,       &Particles::xi,
    &Particles::gamma_dot, &Particles::su, &Particles::x0,   &Particles::y0,
    &Particles::cxx, &Particles::cxy, &Particles::cyx,      &Particles::cyy,
    &Particles::fxx, &Particles::fxy, &Particles::fyx,      &Particles::fyy};

// Raw device pointers of one copy of the particle arrays, plus origin: the
// particle's index in the order it was given, which download() restores.
struct Fields {
  double* d[kDoubleFields];
  int* body;
  int* material;
  std::int64_t* id;
  int* origin;
};

ParticleView view_of(const Fields& f, int n) {
  ParticleView v;
  v.n = n;
  double** const out[kDoubleFields] = {&v.x,   &v.y,   &v.vx,  &v.vy,  &v.mass, &v.vol0,
                                       &v.vol, &v.sxx, &v.syy, &v.sxy, &v.szz,  &v.xi,
                                       &v.gamma_dot, &v.su, &v.x0, &v.y0,
                                       &v.cxx, &v.cxy, &v.cyx, &v.cyy,
                                       &v.fxx, &v.fxy, &v.fyx, &v.fyy};
  for (int k = 0; k < kDoubleFields; ++k) *out[k] = f.d[k];
  v.body = f.body;
  v.material = f.material;
  v.id = f.id;
  return v;
}

// Device storage of the particles, twice: the step sorts them by cell from
// one copy into the other.
struct ParticleSet {
  Buffer<double> d[kDoubleFields];
  Buffer<int> body, material, origin;
  Buffer<std::int64_t> id;
  void reserve(int n) {
    for (auto& b : d) b.reserve(n);
    body.reserve(n);
    material.reserve(n);
    origin.reserve(n);
    id.reserve(n);
  }
  Fields fields() const {
    Fields f;
    for (int k = 0; k < kDoubleFields; ++k) f.d[k] = d[k].get();
    f.body = body.get();
    f.material = material.get();
    f.id = id.get();
    f.origin = origin.get();
    return f;
  }
};

// ---- Reductions -----------------------------------------------------------

// The particles' bounding box, and whether any position is not finite.
struct Box {
  double xmin, xmax, ymin, ymax;
  int bad;
};
struct BoxOp {
  using T = Box;
  const double *x, *y;
  __device__ Box identity() const { return {CUDART_INF, -CUDART_INF, CUDART_INF, -CUDART_INF, 0}; }
  __device__ Box combine(const Box& a, const Box& b) const {
    return {fmin(a.xmin, b.xmin), fmax(a.xmax, b.xmax), fmin(a.ymin, b.ymin),
            fmax(a.ymax, b.ymax), a.bad + b.bad};
  }
  __device__ Box load(int i) const {
    const double xi = x[i], yi = y[i];
    if (!isfinite(xi) || !isfinite(yi)) {
      Box b = identity();
      b.bad = 1;
      return b;
    }
    return {xi, xi, yi, yi, 0};
  }
};

// The largest signal speed and the number of particles at fault: a
// non-finite speed, or -1 where the particle failed a guard (guards.hpp).
struct SpeedStat {
  double max;
  int bad;
};
struct SpeedOp {
  using T = SpeedStat;
  const double* speed;
  __device__ SpeedStat identity() const { return {0.0, 0}; }
  __device__ SpeedStat combine(const SpeedStat& a, const SpeedStat& b) const {
    return {fmax(a.max, b.max), a.bad + b.bad};
  }
  __device__ SpeedStat load(int i) const {
    const double s = speed[i];
    return isfinite(s) && s >= 0.0 ? SpeedStat{s, 0} : SpeedStat{0.0, 1};
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

// What a step copies back at its end: one transfer.
struct StepScalars {
  SpeedStat speed;
  Sum basal;
};

// ---- Kernels --------------------------------------------------------------

// Scatter functor of stages.hpp: double atomicAdd (sm_60+). Particles are
// sorted by cell, so the threads of a warp mostly hit the same 3 x 3 to
// 4 x 4 nodes: the atomics contend but stay in L2. A faster version first
// sums a block's particles into a shared-memory tile of the nodes the
// block's cells touch (the cells of a sorted block are contiguous runs) and
// then adds the tile to global memory, or reduces runs of equal node
// indices within a warp (__match_any_sync) before one atomic per run.
struct AtomicAdd {
  __device__ void operator()(double* a, int n, double v) const { atomicAdd(a + n, v); }
};

// The minimum functor of stages.hpp (the nodal gap): CUDA has no double
// atomicMin, so compare-and-swap until the stored value is at most v.
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

__global__ void fill_kernel(double* a, int n, double v) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) a[i] = v;
}

__global__ void bin_kernel(ParticleView P, GridView g, int cells_x, int* key, int* value) {
  const int p = blockIdx.x * blockDim.x + threadIdx.x;
  if (p >= P.n) return;
  const int ci = static_cast<int>(floor((P.x[p] - g.ox) / g.h));
  const int cj = static_cast<int>(floor((P.y[p] - g.oy) / g.h));
  key[p] = cj * cells_x + ci;
  value[p] = p;
}

// dst[q] = src[order[q]], every field: the particles in cell order.
__global__ void gather_kernel(int n, Fields src, Fields dst, const int* order) {
  const int q = blockIdx.x * blockDim.x + threadIdx.x;
  if (q >= n) return;
  const int p = order[q];
  for (int k = 0; k < kDoubleFields; ++k) dst.d[k][q] = src.d[k][p];
  dst.body[q] = src.body[p];
  dst.material[q] = src.material[p];
  dst.id[q] = src.id[p];
  dst.origin[q] = src.origin[p];
}

// dst[origin[q]] = src[q]: back to the given order, for download().
__global__ void scatter_back_kernel(int n, Fields src, Fields dst) {
  const int q = blockIdx.x * blockDim.x + threadIdx.x;
  if (q >= n) return;
  const int p = src.origin[q];
  for (int k = 0; k < kDoubleFields; ++k) dst.d[k][p] = src.d[k][q];
  dst.body[p] = src.body[q];
  dst.material[p] = src.material[q];
  dst.id[p] = src.id[q];
  dst.origin[p] = p;
}

// The stencil is recomputed in each kernel from the start-of-step position
// (the particle moves only in stress_update, the last stage), exactly as
// the CPU's bin_particles computes it once: cheaper than storing 112 bytes
// per particle and reading them back four times.
__device__ inline Stencil2D stencil_of(const ParticleView& P, int p, const GridView& g,
                                       const StepConfig& c) {
  Stencil2D st;
  make_stencil(g, c, P, p, st);
  return st;
}

__global__ void p2g_kernel(ParticleView P, GridView g, StepConfig c) {
  const int p = blockIdx.x * blockDim.x + threadIdx.x;
  if (p >= P.n) return;
  p2g(P, p, stencil_of(P, p, g, c), g, c, AtomicAdd{}, AtomicMin{});
}

__global__ void grid_update_kernel(GridView g, StepConfig c, double dt) {
  const int n = blockIdx.x * blockDim.x + threadIdx.x;
  if (n < g.size()) grid_update(g, n, c, dt);
}

__global__ void xpic_start_kernel(GridView g, StepConfig c) {
  const int n = blockIdx.x * blockDim.x + threadIdx.x;
  if (n < g.size()) xpic_start(g, n, c);
}

__global__ void p2g_smoothed_kernel(ParticleView P, GridView g, StepConfig c) {
  const int p = blockIdx.x * blockDim.x + threadIdx.x;
  if (p < P.n) p2g_smoothed(P, p, stencil_of(P, p, g, c), g, AtomicAdd{});
}

__global__ void xpic_term_kernel(GridView g, StepConfig c, int k) {
  const int n = blockIdx.x * blockDim.x + threadIdx.x;
  if (n < g.size()) xpic_term(g, n, c, k);
}

// g2p reads only nodal velocities, so a particle's remap follows it in the
// same thread (as the CPU driver's fused pass).
__global__ void g2p_momentum_kernel(ParticleView P, GridView g, StepConfig c) {
  const int p = blockIdx.x * blockDim.x + threadIdx.x;
  if (p >= P.n) return;
  const Stencil2D st = stencil_of(P, p, g, c);
  g2p(P, p, st, g, c);
  p2g_momentum(P, p, st, g, AtomicAdd{});
}

__global__ void remap_kernel(GridView g, StepConfig c, double dt) {
  const int n = blockIdx.x * blockDim.x + threadIdx.x;
  if (n < g.size()) remap_velocity(g, n, c, dt);
}

// One thread per node row: the periodic exchange after a grid stage.
__global__ void exchange_kernel(GridView g, Exchange after) {
  const int j = blockIdx.x * blockDim.x + threadIdx.x;
  if (j < g.ny) exchange_periodic(g, j, after);
}

// Per-particle velocity gradients, in structure-of-arrays.
struct Gradients {
  double *xx, *xy, *yx, *yy;
};

// Per-cell sums of the volumetric smoothing: volume and volume * value.
struct CellSums {
  double *vol, *sum;
};

// L and the step displacement, and with smoothing the cell sums of V and
// V tr L (simulation.cpp's cell_means, with atomics instead of the CPU's
// block ownership).
__global__ void gradient_kernel(ParticleView P, GridView g, StepConfig c, double dt,
                                StepScratch s, Gradients L, const int* cell, CellSums cs,
                                bool smooth) {
  const int p = blockIdx.x * blockDim.x + threadIdx.x;
  if (p >= P.n) return;
  const Stencil2D st = stencil_of(P, p, g, c);
  const VelocityGradient l = velocity_gradient(st, g);
  displacement(p, st, g, dt, s);
  L.xx[p] = l.xx;
  L.xy[p] = l.xy;
  L.yx[p] = l.yx;
  L.yy[p] = l.yy;
  if (smooth) {
    atomicAdd(cs.vol + cell[p], P.vol[p]);
    atomicAdd(cs.sum + cell[p], P.vol[p] * (l.xx + l.yy));
  }
}

__device__ inline double cell_mean(const CellSums& cs, int c) {
  const double v = cs.vol[c];
  return v > 0.0 ? cs.sum[c] / v : 0.0;
}

__global__ void stress_kernel(ParticleView P, Gradients L, const int* cell, CellSums cs,
                              bool smooth, const MaterialParams* mats, double dt, StepScratch s,
                              StepConfig c, GuardLimits limits, double* speed) {
  const int p = blockIdx.x * blockDim.x + threadIdx.x;
  if (p >= P.n) return;
  VelocityGradient l{L.xx[p], L.xy[p], L.yx[p], L.yy[p]};
  if (smooth) set_volumetric_rate(l, cell_mean(cs, cell[p]));
  const double sp = stress_update(P, p, l, mats, dt, s);
  wrap_periodic(P, p, c);
  speed[p] = particle_fault(P, p, limits) == Fault::None ? sp : -1.0;
}

__device__ inline double mean_stress(const ParticleView& P, int p) {
  return (P.sxx[p] + P.syy[p] + P.szz[p]) / 3.0;
}

__global__ void mean_stress_sum_kernel(ParticleView P, const int* cell, CellSums cs) {
  const int p = blockIdx.x * blockDim.x + threadIdx.x;
  if (p >= P.n) return;
  atomicAdd(cs.vol + cell[p], P.vol[p]);
  atomicAdd(cs.sum + cell[p], P.vol[p] * mean_stress(P, p));
}

__global__ void mean_stress_apply_kernel(ParticleView P, const int* cell, CellSums cs) {
  const int p = blockIdx.x * blockDim.x + threadIdx.x;
  if (p >= P.n) return;
  const double shift = cell_mean(cs, cell[p]) - mean_stress(P, p);
  P.sxx[p] += shift;
  P.syy[p] += shift;
  P.szz[p] += shift;
}

int bits_for(int values) {  // bits of the largest key values - 1
  int bits = 1;
  while (bits < 31 && (1 << bits) < values) ++bits;
  return bits;
}

}  // namespace

bool cuda_device_available(std::string& why_not) {
  int count = 0;
  const cudaError_t err = cudaGetDeviceCount(&count);
  if (err != cudaSuccess) {
    why_not = std::string("no usable CUDA device: ") + cudaGetErrorString(err);
    return false;
  }
  if (count == 0) {
    why_not = "no CUDA device found";
    return false;
  }
  return true;
}

struct CudaSimulation::Impl {
  Impl(const Scene& scene, const Particles& particles);

  void fit_grid(double dt);
  void sort_by_cell();
  void step(double dt);
  void download(Particles& out);
  // The failure of the step about to end, with the particle at fault.
  [[noreturn]] void fail(double dt);

  // Host-side state.
  Base base;
  std::vector<MaterialParams> materials;
  StepConfig config;         // base view on the host arrays
  StepConfig device_config;  // base view on the device copies
  double xmin_domain, ymin_domain, xmax_domain, ymax_domain;
  double h, courant, spacing;
  bool smooth;
  int n;
  double max_signal_speed = 0;
  double time = 0, last_dt = 0, basal_shear_force = 0;
  long steps = 0;
  GuardLimits limits;

  // Device state.
  ParticleSet sets[2];
  int current = 0;  // the set that holds the particles
  Buffer<double> dx, dy, lxx, lxy, lyx, lyy, speed;
  Buffer<int> keys_in, keys_out, values_in, values_out;
  Buffer<unsigned char> sort_temp;
  static constexpr int kGridArrays = 19;  // the double arrays of GridView
  Buffer<double> grid_arrays[kGridArrays];
  GridView grid;  // device pointers
  int cells_x = 0, cells = 0;
  Buffer<double> cell_vol, cell_sum;
  Buffer<MaterialParams> device_materials;
  Buffer<double> base_px, base_py, base_ps;
  Buffer<unsigned char> partials;  // a reduction's first pass
  Buffer<Box> box;
  Buffer<StepScalars> scalars;

  ParticleView particles() const { return view_of(sets[current].fields(), n); }
};

namespace {

// The scene's step configuration and materials, exactly as the CPU driver
// makes them: a Simulation without particles.
std::pair<StepConfig, std::vector<MaterialParams>> cpu_setup(const Scene& scene) {
  const Simulation probe(scene, Particles{});
  return {probe.config(), probe.materials()};
}

template <class T>
void upload(Buffer<T>& dst, const T* src, std::size_t count) {
  dst.reserve(count > 0 ? count : 1);
  if (count > 0)
    RUNOUT_CUDA_CHECK(cudaMemcpy(dst.get(), src, count * sizeof(T), cudaMemcpyHostToDevice));
}

}  // namespace

CudaSimulation::Impl::Impl(const Scene& scene, const Particles& P)
    : base(scene.base, scene.grid.min.y()),
      xmin_domain(scene.grid.min.x()),
      ymin_domain(scene.grid.min.y()),
      xmax_domain(scene.grid.max.x()),
      ymax_domain(scene.grid.max.y()),
      h(scene.grid.cell_size),
      courant(scene.time.courant),
      spacing(scene.grid.cell_size / scene.grid.ppc),
      smooth(scene.solver.volumetric_smoothing),
      n(P.size()) {
  // A resumed run reaches here without the CLI's check of the scene.
  if (const std::string refusal = cuda_refusal(scene); !refusal.empty())
    throw SceneError(refusal, 0);
  std::string why;
  if (!cuda_device_available(why)) throw std::runtime_error(why);
  auto setup = cpu_setup(scene);
  config = setup.first;
  materials = std::move(setup.second);
  config.base = base.view();
  device_config = config;
  const BaseView bv = base.view();
  if (bv.kind == BaseKind::Polyline) {
    upload(base_px, bv.px, bv.n);
    upload(base_py, bv.py, bv.n);
    upload(base_ps, bv.ps, bv.n);
    device_config.base.px = base_px.get();
    device_config.base.py = base_py.get();
    device_config.base.ps = base_ps.get();
  }
  upload(device_materials, materials.data(), materials.size());

  // Everything per particle is allocated here, once.
  const int cap = n > 0 ? n : 1;
  for (auto& s : sets) s.reserve(cap);
  for (auto* b : {&dx, &dy, &lxx, &lxy, &lyx, &lyy, &speed}) b->reserve(cap);
  for (auto* b : {&keys_in, &keys_out, &values_in, &values_out}) b->reserve(cap);
  partials.reserve(cuda::kReduceBlocks * 64);
  static_assert(sizeof(Box) <= 64 && sizeof(SpeedStat) <= 64 && sizeof(Sum) <= 64,
                "reduction partials hold 64 bytes a block");
  box.reserve(1);
  scalars.reserve(1);

  ParticleSet& s = sets[0];
  for (int k = 0; k < kDoubleFields; ++k) upload(s.d[k], (P.*kHostDoubles[k]).data(), n);
  upload(s.body, P.body.data(), n);
  upload(s.material, P.material.data(), n);
  upload(s.id, P.id.data(), n);
  std::vector<int> origin(n);
  for (int p = 0; p < n; ++p) origin[p] = p;
  upload(s.origin, origin.data(), n);

  // The first CFL speed on the host, as the CPU driver does.
  Particles copy = P;
  const ParticleView hv = copy.view();
  double smax = 0;
  for (int p = 0; p < n; ++p) smax = std::max(smax, cfl_speed(hv, p, materials[hv.material[p]]));
  max_signal_speed = smax;
  limits = guard_limits(scene, materials, P);
}

void CudaSimulation::Impl::fail(double dt) {
  Particles host;
  download(host);
  throw NumericalFailure(describe_faults(host, limits, steps, time, dt));
}

void CudaSimulation::Impl::fit_grid(double dt) {
  const ParticleView P = particles();
  cuda::reduce(n, BoxOp{P.x, P.y}, reinterpret_cast<Box*>(partials.get()), box.get());
  Box b;
  RUNOUT_CUDA_CHECK(cudaMemcpy(&b, box.get(), sizeof b, cudaMemcpyDeviceToHost));
  // As the CPU driver: the end of every step checks the particles; this
  // catches particles given outside the domain.
  if (b.bad > 0 || !(b.xmin >= limits.xmin && b.ymin >= limits.ymin && b.xmax <= limits.xmax &&
                     b.ymax <= limits.ymax))
    fail(dt);
  GridView& g = grid;
  if (config.period > 0.0) periodic_span(config, h, b.xmin, b.xmax);
  place_box(g, b.xmin, b.xmax, b.ymin, b.ymax, xmin_domain, ymin_domain, h);
  const std::size_t nodes = static_cast<std::size_t>(g.nx) * g.ny;
  for (auto& a : grid_arrays) a.reserve(nodes);  // grow-only
  double** const ptrs[kGridArrays] = {&g.m,  &g.vol, &g.px,  &g.py,    &g.fx,  &g.fy,
                                       &g.v0x, &g.v0y, &g.vx, &g.vy,    &g.vmx, &g.vmy,
                                       &g.fbase, &g.gap, &g.stuck, &g.qx,  &g.qy,
                                       &g.xvx, &g.xvy};
  for (int k = 0; k < kGridArrays; ++k) *ptrs[k] = grid_arrays[k].get();
  for (int k = 0; k < 6; ++k)  // m, vol, p, f: the accumulated ones
    RUNOUT_CUDA_CHECK(cudaMemsetAsync(grid_arrays[k].get(), 0, nodes * sizeof(double)));
  // The gap, a minimum: +infinity where no particle is.
  fill_kernel<<<blocks_for(static_cast<int>(nodes)), kThreads>>>(
      g.gap, static_cast<int>(nodes), std::numeric_limits<double>::infinity());
  RUNOUT_CUDA_LAUNCHED("fill gap");
  cells_x = g.nx - 1;
  cells = cells_x * (g.ny - 1);
  cell_vol.reserve(cells);
  cell_sum.reserve(cells);
}

// Particles sorted by cell (stable radix sort, so the order is the same on
// every run), and the sorted particle arrays gathered into the other set.
// Neighbouring threads then touch neighbouring nodes: coalesced particle
// reads, and the scatters' atomics hit a few cache lines per warp.
void CudaSimulation::Impl::sort_by_cell() {
  const ParticleView P = particles();
  bin_kernel<<<blocks_for(n), kThreads>>>(P, grid, cells_x, keys_in.get(), values_in.get());
  RUNOUT_CUDA_LAUNCHED("bin");
  const int end_bit = bits_for(cells);
  std::size_t bytes = 0;
  RUNOUT_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(nullptr, bytes, keys_in.get(), keys_out.get(),
                                                    values_in.get(), values_out.get(), n, 0,
                                                    end_bit));
  sort_temp.reserve(bytes > 0 ? bytes : 1);  // grow-only
  RUNOUT_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(sort_temp.get(), bytes, keys_in.get(),
                                                    keys_out.get(), values_in.get(),
                                                    values_out.get(), n, 0, end_bit));
  const int other = 1 - current;
  gather_kernel<<<blocks_for(n), kThreads>>>(n, sets[current].fields(), sets[other].fields(),
                                             values_out.get());
  RUNOUT_CUDA_LAUNCHED("gather");
  current = other;
  // keys_out now holds each (sorted) particle's cell.
}

void CudaSimulation::Impl::step(double dt) {
  fit_grid(dt);
  sort_by_cell();
  const GridView g = grid;
  const ParticleView P = particles();
  configure_step(device_config, time, dt);
  const StepConfig& c = device_config;
  const StepScratch s{dx.get(), dy.get()};
  const int nodes = g.size();
  const int pb = blocks_for(n), nb = blocks_for(nodes);
  const int* cell = keys_out.get();
  const CellSums cs{cell_vol.get(), cell_sum.get()};
  const Gradients L{lxx.get(), lxy.get(), lyx.get(), lyy.get()};
  const auto exchange = [&](Exchange after, const char* what) {
    if (!(c.period > 0.0)) return;
    exchange_kernel<<<blocks_for(g.ny), kThreads>>>(g, after);
    RUNOUT_CUDA_LAUNCHED(what);
  };

  p2g_kernel<<<pb, kThreads>>>(P, g, c);
  RUNOUT_CUDA_LAUNCHED("p2g");
  exchange(Exchange::AfterP2g, "periodic exchange (p2g)");
  grid_update_kernel<<<nb, kThreads>>>(g, c, dt);
  RUNOUT_CUDA_LAUNCHED("grid_update");
  exchange(Exchange::AfterGridUpdate, "periodic exchange (grid_update)");
  const auto clear_momentum = [&] {  // px, py: the scatters after grid_update
    RUNOUT_CUDA_CHECK(cudaMemsetAsync(g.px, 0, nodes * sizeof(double)));
    RUNOUT_CUDA_CHECK(cudaMemsetAsync(g.py, 0, nodes * sizeof(double)));
  };
  if (c.xpic_now) {  // V* of XPIC(m), as Simulation::xpic_start_velocity
    xpic_start_kernel<<<nb, kThreads>>>(g, c);
    RUNOUT_CUDA_LAUNCHED("xpic_start");
    for (int k = 2; k <= c.xpic_order; ++k) {
      clear_momentum();
      p2g_smoothed_kernel<<<pb, kThreads>>>(P, g, c);
      RUNOUT_CUDA_LAUNCHED("p2g_smoothed");
      exchange(Exchange::AfterMomentum, "periodic exchange (p2g_smoothed)");
      xpic_term_kernel<<<nb, kThreads>>>(g, c, k);
      RUNOUT_CUDA_LAUNCHED("xpic_term");
      exchange(Exchange::AfterXpicTerm, "periodic exchange (xpic_term)");
    }
  }
  clear_momentum();
  g2p_momentum_kernel<<<pb, kThreads>>>(P, g, c);
  RUNOUT_CUDA_LAUNCHED("g2p and p2g_momentum");
  exchange(Exchange::AfterMomentum, "periodic exchange (p2g_momentum)");
  remap_kernel<<<nb, kThreads>>>(g, c, dt);
  RUNOUT_CUDA_LAUNCHED("remap_velocity");
  exchange(Exchange::AfterRemap, "periodic exchange (remap_velocity)");

  const auto clear_cells = [&] {
    RUNOUT_CUDA_CHECK(cudaMemsetAsync(cs.vol, 0, cells * sizeof(double)));
    RUNOUT_CUDA_CHECK(cudaMemsetAsync(cs.sum, 0, cells * sizeof(double)));
  };
  if (smooth) clear_cells();
  gradient_kernel<<<pb, kThreads>>>(P, g, c, dt, s, L, cell, cs, smooth);
  RUNOUT_CUDA_LAUNCHED("velocity_gradient");
  stress_kernel<<<pb, kThreads>>>(P, L, cell, cs, smooth, device_materials.get(), dt, s, c,
                                  limits, speed.get());
  RUNOUT_CUDA_LAUNCHED("stress_update");
  if (smooth) {
    clear_cells();
    mean_stress_sum_kernel<<<pb, kThreads>>>(P, cell, cs);
    RUNOUT_CUDA_LAUNCHED("mean stress (sum)");
    mean_stress_apply_kernel<<<pb, kThreads>>>(P, cell, cs);
    RUNOUT_CUDA_LAUNCHED("mean stress (apply)");
  }

  // The scalars' members on the device (offsets: out is a device pointer).
  StepScalars* out = scalars.get();
  char* const base_address = reinterpret_cast<char*>(out);
  auto* out_speed = reinterpret_cast<SpeedStat*>(base_address + offsetof(StepScalars, speed));
  auto* out_basal = reinterpret_cast<Sum*>(base_address + offsetof(StepScalars, basal));
  cuda::reduce(n, SpeedOp{speed.get()}, reinterpret_cast<SpeedStat*>(partials.get()), out_speed);
  if (c.base.kind != BaseKind::None) {
    cuda::reduce(nodes, SumOp{g.fbase}, reinterpret_cast<Sum*>(partials.get()), out_basal);
  } else {
    RUNOUT_CUDA_CHECK(cudaMemsetAsync(out_basal, 0, sizeof(Sum)));
  }
  StepScalars host;
  RUNOUT_CUDA_CHECK(cudaMemcpy(&host, out, sizeof host, cudaMemcpyDeviceToHost));
  if (host.speed.bad > 0) fail(dt);
  max_signal_speed = host.speed.max;
  basal_shear_force = host.basal.v;
  time += dt;
  last_dt = dt;
  ++steps;
}

CudaSimulation::CudaSimulation(const Scene& scene)
    : CudaSimulation(scene, seed_particles(scene)) {}
CudaSimulation::CudaSimulation(const Scene& scene, const Particles& particles)
    : impl_(std::make_unique<Impl>(scene, particles)) {}
CudaSimulation::~CudaSimulation() = default;
CudaSimulation::CudaSimulation(CudaSimulation&&) noexcept = default;
CudaSimulation& CudaSimulation::operator=(CudaSimulation&&) noexcept = default;

double CudaSimulation::stable_dt() const {
  return impl_->courant * impl_->h / impl_->max_signal_speed;
}
void CudaSimulation::step(double dt) { impl_->step(dt); }

void CudaSimulation::advance_to(double t) {
  // As Simulation::advance_to.
  while (impl_->time < t) {
    const double remaining = t - impl_->time;
    const double n = std::ceil(remaining / stable_dt());
    step(remaining / n);
    if (n <= 1.0) impl_->time = t;
  }
}

StepCounters CudaSimulation::counters() const {
  const Impl& m = *impl_;
  return StepCounters{m.time, m.steps, m.last_dt, m.basal_shear_force, m.max_signal_speed,
                      m.limits.max_speed};
}

void CudaSimulation::restore(const StepCounters& c) {
  Impl& m = *impl_;
  m.time = c.time;
  m.steps = c.steps;
  m.last_dt = c.last_dt;
  m.basal_shear_force = c.basal_shear_force;
  m.max_signal_speed = c.max_signal_speed;
  m.limits.max_speed = c.speed_limit;
}

double CudaSimulation::time() const { return impl_->time; }
long CudaSimulation::steps() const { return impl_->steps; }
double CudaSimulation::last_dt() const { return impl_->last_dt; }
double CudaSimulation::basal_shear_force() const { return impl_->basal_shear_force; }
const Base& CudaSimulation::base() const { return impl_->base; }
double CudaSimulation::particle_spacing() const { return impl_->spacing; }
const std::vector<MaterialParams>& CudaSimulation::materials() const { return impl_->materials; }
const StepConfig& CudaSimulation::config() const { return impl_->config; }
int CudaSimulation::size() const { return impl_->n; }

void CudaSimulation::download(Particles& out) const { impl_->download(out); }

void CudaSimulation::Impl::download(Particles& out) {
  Impl& m = *this;
  out.resize(m.n);
  if (m.n == 0) return;
  // Unsort into the spare set, then copy each array straight into out.
  const ParticleSet& spare = m.sets[1 - m.current];
  scatter_back_kernel<<<blocks_for(m.n), kThreads>>>(m.n, m.sets[m.current].fields(),
                                                     spare.fields());
  RUNOUT_CUDA_LAUNCHED("download");
  const auto get = [&](auto* dst, const auto* src) {
    RUNOUT_CUDA_CHECK(cudaMemcpy(dst, src, m.n * sizeof *dst, cudaMemcpyDeviceToHost));
  };
  for (int k = 0; k < kDoubleFields; ++k) get((out.*kHostDoubles[k]).data(), spare.d[k].get());
  get(out.body.data(), spare.body.get());
  get(out.material.data(), spare.material.get());
  get(out.id.data(), spare.id.get());
  // The spare set is in the given order now: make it the current one, so
  // that the next step sorts from there (same result, one gather fewer).
  m.current = 1 - m.current;
}

}  // namespace runout
