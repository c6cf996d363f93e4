// The CUDA driver: the one step of driver.hpp over the CUDA backend
// (backend_cuda.cuh), whose primitives are defined here. See docs/cuda.md.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "backend_cuda.cuh"
#include "runout/mpm/cuda_simulation.hpp"
#include "runout/mpm/seeding.hpp"

namespace runout {
namespace cuda {
namespace {

// ParticleView's double pointers, in the order of Particles::double_arrays.
ParticleView view_of(const Fields& f, int n) {
  ParticleView v;
  v.n = n;
  double** const out[kParticleDoubles] = {&v.x,   &v.y,   &v.vx,  &v.vy,  &v.mass, &v.vol0,
                                          &v.vol, &v.sxx, &v.syy, &v.sxy, &v.szz,  &v.xi,
                                          &v.gamma_dot, &v.su, &v.band_xi, &v.band_rate,
                                          &v.x0, &v.y0,
                                          &v.cxx, &v.cxy, &v.cyx, &v.cyy,
                                          &v.fxx, &v.fxy, &v.fyx, &v.fyy};
  for (int k = 0; k < kParticleDoubles; ++k) *out[k] = f.d[k];
  v.body = f.body;
  v.material = f.material;
  v.id = f.id;
  return v;
}

__global__ void fill_kernel(double* a, int n, double v) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) a[i] = v;
}

__global__ void bin_kernel(ParticleView P, GridView g, int cells_x, int* key, int* value) {
  const int p = blockIdx.x * blockDim.x + threadIdx.x;
  if (p >= P.n) return;
  const int ci = cell_of(P.x[p], g.ox, g.h), cj = cell_of(P.y[p], g.oy, g.h);
  key[p] = cj * cells_x + ci;
  value[p] = p;
}

// dst[q] = src[order[q]], every field: the particles in cell order.
__global__ void gather_kernel(int n, Fields src, Fields dst, const int* order) {
  const int q = blockIdx.x * blockDim.x + threadIdx.x;
  if (q >= n) return;
  const int p = order[q];
  for (int k = 0; k < kParticleDoubles; ++k) dst.d[k][q] = src.d[k][p];
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
  for (int k = 0; k < kParticleDoubles; ++k) dst.d[k][p] = src.d[k][q];
  dst.body[p] = src.body[q];
  dst.material[p] = src.material[q];
  dst.id[p] = src.id[q];
  dst.origin[p] = p;
}

// The cell means of the volumetric smoothing, from the scattered sums.
__global__ void divide_kernel(int cells, const double* vol, const double* sum, double* mean) {
  const int c = blockIdx.x * blockDim.x + threadIdx.x;
  if (c < cells) mean[c] = vol[c] > 0.0 ? sum[c] / vol[c] : 0.0;
}

int bits_for(int values) {  // bits of the largest key values - 1
  int bits = 1;
  while (bits < 31 && (1 << bits) < values) ++bits;
  return bits;
}

template <class T>
void upload(Buffer<T>& dst, const T* src, std::size_t count) {
  dst.reserve(count > 0 ? count : 1);
  if (count > 0)
    RUNOUT_CUDA_CHECK(cudaMemcpy(dst.get(), src, count * sizeof(T), cudaMemcpyHostToDevice));
}

template <class T>
void download_array(T* dst, const T* src, std::size_t count) {
  if (count > 0)
    RUNOUT_CUDA_CHECK(cudaMemcpy(dst, src, count * sizeof(T), cudaMemcpyDeviceToHost));
}

}  // namespace

void ParticleSet::reserve(int n) {
  for (auto& b : d) b.reserve(n);
  body.reserve(n);
  material.reserve(n);
  origin.reserve(n);
  id.reserve(n);
}

Fields ParticleSet::fields() const {
  Fields f;
  for (int k = 0; k < kParticleDoubles; ++k) f.d[k] = d[k].get();
  f.body = body.get();
  f.material = material.get();
  f.id = id.get();
  f.origin = origin.get();
  return f;
}

}  // namespace cuda

using cuda::blocks_for;
using cuda::kThreads;

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

// ---- CudaBackend ----------------------------------------------------------

CudaBackend::CudaBackend(Particles P, const std::vector<MaterialParams>& materials,
                         const Base& base, const std::vector<double>& nonlocal_lengths)
    : n_(P.size()) {
  std::string why;
  if (!cuda_device_available(why)) throw std::runtime_error(why);
  const BaseView bv = base.view();
  if (bv.kind == BaseKind::Polyline) {
    cuda::upload(base_px_, bv.px, bv.n);
    cuda::upload(base_py_, bv.py, bv.n);
    cuda::upload(base_ps_, bv.ps, bv.n);
    cuda::upload(base_seg_, bv.seg, bv.n - 1);
  }
  cuda::upload(materials_, materials.data(), materials.size());
  cuda::upload(lengths_, nonlocal_lengths.data(), nonlocal_lengths.size());

  // Everything per particle is allocated here, once.
  const int cap = n_ > 0 ? n_ : 1;
  for (auto& s : sets_) s.reserve(cap);
  for (auto* b : {&dx_, &dy_, &lxx_, &lxy_, &lyx_, &lyy_, &speed_}) b->reserve(cap);
  if (std::any_of(nonlocal_lengths.begin(), nonlocal_lengths.end(), [](double l) { return l > 0; }))
    for (auto* b : {&xi_start_, &xi_local_, &xi_average_}) b->reserve(cap);
  for (auto* b : {&keys_in_, &keys_out_, &values_in_, &values_out_}) b->reserve(cap);
  partials_.reserve(cuda::kReduceBlocks * 64);
  static_assert(sizeof(ParticleBox) <= 64 && sizeof(SpeedMax) <= 64 && sizeof(cuda::Sum) <= 64,
                "reduction partials hold 64 bytes a block");
  box_.reserve(1);
  speed_max_.reserve(1);
  sum_.reserve(1);

  cuda::ParticleSet& s = sets_[0];
  const auto doubles = P.double_arrays();
  for (int k = 0; k < kParticleDoubles; ++k) cuda::upload(s.d[k], doubles[k]->data(), n_);
  cuda::upload(s.body, P.body.data(), n_);
  cuda::upload(s.material, P.material.data(), n_);
  cuda::upload(s.id, P.id.data(), n_);
  std::vector<int> origin(n_);
  for (int p = 0; p < n_; ++p) origin[p] = p;
  cuda::upload(s.origin, origin.data(), n_);
}

ParticleView CudaBackend::particles() const {
  return cuda::view_of(sets_[current_].fields(), n_);
}

ParticleBox CudaBackend::bounding_box() {
  const ParticleView P = particles();
  cuda::reduce(n_, cuda::BoxOp{P.x, P.y}, reinterpret_cast<ParticleBox*>(partials_.get()),
               box_.get());
  ParticleBox b;
  RUNOUT_CUDA_CHECK(cudaMemcpy(&b, box_.get(), sizeof b, cudaMemcpyDeviceToHost));
  return b;
}

GridView CudaBackend::fit_grid(const GridView& placed) {
  GridView g = placed;
  const std::size_t nodes = static_cast<std::size_t>(g.nx) * g.ny;
  for (auto& a : grid_arrays_) a.reserve(nodes);  // grow-only
  double** const ptrs[kGridArrays] = {&g.m,   &g.vol, &g.px,  &g.py,  &g.fx,    &g.fy,
                                      &g.band_su, &g.v0x, &g.v0y, &g.vx,  &g.vy,  &g.dvx,
                                      &g.dvy, &g.vmx, &g.vmy, &g.fbase, &g.gap, &g.stuck,
                                      &g.qx,  &g.qy,  &g.xvx, &g.xvy, &g.band_slip};
  for (int k = 0; k < kGridArrays; ++k) *ptrs[k] = grid_arrays_[k].get();
  for (int k = 0; k < 7; ++k)  // m, vol, p, f, the band's strength: the accumulated ones
    RUNOUT_CUDA_CHECK(cudaMemsetAsync(grid_arrays_[k].get(), 0, nodes * sizeof(double)));
  // The gap, a minimum: +infinity where no particle is.
  fill_nodes(g, g.gap, std::numeric_limits<double>::infinity());
  cells_ = (g.nx - 1) * (g.ny - 1);
  for (auto* b : {&cell_vol_, &cell_sum_, &cell_mean_}) b->reserve(cells_);
  return g;
}

// Particles sorted by cell (stable radix sort, so the order is the same on
// every run), and the sorted particle arrays gathered into the other set.
// Neighbouring threads then touch neighbouring nodes: coalesced particle
// reads, and the scatters' atomics hit a few cache lines per warp.
void CudaBackend::bin(const GridView& g, const StepConfig&, long) {
  const ParticleView P = particles();
  cuda::bin_kernel<<<blocks_for(n_), kThreads>>>(P, g, g.nx - 1, keys_in_.get(),
                                                 values_in_.get());
  RUNOUT_CUDA_LAUNCHED("bin");
  const int end_bit = cuda::bits_for(cells_);
  std::size_t bytes = 0;
  RUNOUT_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(nullptr, bytes, keys_in_.get(),
                                                    keys_out_.get(), values_in_.get(),
                                                    values_out_.get(), n_, 0, end_bit));
  sort_temp_.reserve(bytes > 0 ? bytes : 1);  // grow-only
  RUNOUT_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(sort_temp_.get(), bytes, keys_in_.get(),
                                                    keys_out_.get(), values_in_.get(),
                                                    values_out_.get(), n_, 0, end_bit));
  const int other = 1 - current_;
  cuda::gather_kernel<<<blocks_for(n_), kThreads>>>(n_, sets_[current_].fields(),
                                                    sets_[other].fields(), values_out_.get());
  RUNOUT_CUDA_LAUNCHED("gather");
  current_ = other;
  // keys_out_ now holds each (sorted) particle's cell.
}

SpeedMax CudaBackend::reduce_speed() {
  cuda::reduce(n_, cuda::SpeedOp{speed_.get()}, reinterpret_cast<SpeedMax*>(partials_.get()),
               speed_max_.get());
  SpeedMax out;
  RUNOUT_CUDA_CHECK(cudaMemcpy(&out, speed_max_.get(), sizeof out, cudaMemcpyDeviceToHost));
  return out;
}

double CudaBackend::sum_nodes(const GridView& g, const double* a) {
  const int count = g.size();
  cuda::reduce(count, cuda::SumOp{a}, reinterpret_cast<cuda::Sum*>(partials_.get()), sum_.get());
  cuda::Sum out;
  RUNOUT_CUDA_CHECK(cudaMemcpy(&out, sum_.get(), sizeof out, cudaMemcpyDeviceToHost));
  return out.v;
}

void CudaBackend::fill_nodes(const GridView& g, double* a, double v) {
  const int count = g.size();
  if (v == 0.0) {
    RUNOUT_CUDA_CHECK(cudaMemsetAsync(a, 0, count * sizeof(double)));
    return;
  }
  cuda::fill_kernel<<<blocks_for(count), kThreads>>>(a, count, v);
  RUNOUT_CUDA_LAUNCHED("fill");
}

void CudaBackend::clear_cells() {
  RUNOUT_CUDA_CHECK(cudaMemsetAsync(cell_vol_.get(), 0, cells_ * sizeof(double)));
  RUNOUT_CUDA_CHECK(cudaMemsetAsync(cell_sum_.get(), 0, cells_ * sizeof(double)));
}

CellMeanView CudaBackend::divide_cells() {
  cuda::divide_kernel<<<blocks_for(cells_), kThreads>>>(cells_, cell_vol_.get(), cell_sum_.get(),
                                                        cell_mean_.get());
  RUNOUT_CUDA_LAUNCHED("cell means");
  return {cell_mean_.get(), keys_out_.get()};
}

void CudaBackend::nonlocal_average(NonlocalAverage& nonlocal, const double* in, double* out) {
  RUNOUT_CUDA_CHECK(cudaMemcpy(out, in, n_ * sizeof(double), cudaMemcpyDeviceToDevice));
  if (n_ == 0) return;
  const ParticleBox box = bounding_box();
  if (box.non_finite > 0) return;  // the step's guards report it
  average_by_elements(*this, nonlocal, particles(), box, on_device(nonlocal.mirror()), in, out,
                      cuda::AtomicAdd{});
}

NonlocalLatticeArrays CudaBackend::lattice_arrays(int nodes) {
  lattice_inc_.reserve(nodes);
  lattice_vol_.reserve(nodes);
  lattice_pass_.reserve(nodes);
  RUNOUT_CUDA_CHECK(cudaMemset(lattice_inc_.get(), 0, nodes * sizeof(double)));
  RUNOUT_CUDA_CHECK(cudaMemset(lattice_vol_.get(), 0, nodes * sizeof(double)));
  return {lattice_inc_.get(), lattice_vol_.get(), lattice_pass_.get()};
}

NonlocalTaps CudaBackend::lattice_taps(const NonlocalAverage& nonlocal, int m) {
  if (taps_at_.empty()) {  // the taps depend on l alone: uploaded once
    std::vector<double> taps;
    for (int k = 0; k < nonlocal.materials(); ++k) {
      const NonlocalAverage::Taps& t = nonlocal.taps(k);
      taps_at_.push_back(static_cast<long>(taps.size()));
      taps.insert(taps.end(), t.x.begin(), t.x.end());
      taps.insert(taps.end(), t.y.begin(), t.y.end());
    }
    cuda::upload(taps_, taps.data(), taps.size());
  }
  const double* x = taps_.get() + taps_at_[m];
  return {x, x + nonlocal.taps(m).x.size()};
}

StepConfig CudaBackend::kernel_config(const StepConfig& c) const {
  StepConfig d = c;
  d.base = on_device(c.base);
  return d;
}

BaseView CudaBackend::on_device(BaseView base) const {
  if (base.kind == BaseKind::Polyline) {
    base.px = base_px_.get();
    base.py = base_py_.get();
    base.ps = base_ps_.get();
    base.seg = base_seg_.get();
  }
  return base;
}

void CudaBackend::download(Particles& out) const {
  out.resize(n_);
  if (n_ == 0) return;
  // Unsort into the spare set, then copy each array straight into out.
  const cuda::ParticleSet& spare = sets_[1 - current_];
  cuda::scatter_back_kernel<<<blocks_for(n_), kThreads>>>(n_, sets_[current_].fields(),
                                                          spare.fields());
  RUNOUT_CUDA_LAUNCHED("download");
  const auto doubles = out.double_arrays();
  for (int k = 0; k < kParticleDoubles; ++k)
    cuda::download_array(doubles[k]->data(), spare.d[k].get(), n_);
  cuda::download_array(out.body.data(), spare.body.get(), n_);
  cuda::download_array(out.material.data(), spare.material.get(), n_);
  cuda::download_array(out.id.data(), spare.id.get(), n_);
  // The spare set is in the given order now: make it the current one, so
  // that the next step sorts from there (same result, one gather fewer).
  current_ = 1 - current_;
}

const Particles& CudaBackend::host_particles() {
  download(host_);
  return host_;
}

template class Driver<CudaBackend>;

// ---- CudaSimulation -------------------------------------------------------

struct CudaSimulation::Impl {
  Impl(const Scene& scene, Particles particles) : driver(scene, std::move(particles)) {}
  Driver<CudaBackend> driver;
};

CudaSimulation::CudaSimulation(const Scene& scene)
    : CudaSimulation(scene, seed_particles(scene)) {}
CudaSimulation::CudaSimulation(const Scene& scene, const Particles& particles)
    : impl_(std::make_unique<Impl>(scene, particles)) {}
CudaSimulation::~CudaSimulation() = default;
CudaSimulation::CudaSimulation(CudaSimulation&&) noexcept = default;
CudaSimulation& CudaSimulation::operator=(CudaSimulation&&) noexcept = default;

double CudaSimulation::stable_dt() const { return impl_->driver.stable_dt(); }
void CudaSimulation::step(double dt) { impl_->driver.step(dt); }
void CudaSimulation::advance_to(double t) { impl_->driver.advance_to(t); }
StepCounters CudaSimulation::counters() const { return impl_->driver.counters(); }
void CudaSimulation::restore(const StepCounters& c) { impl_->driver.restore(c); }
double CudaSimulation::time() const { return impl_->driver.time(); }
long CudaSimulation::steps() const { return impl_->driver.steps(); }
double CudaSimulation::last_dt() const { return impl_->driver.last_dt(); }
double CudaSimulation::basal_shear_force() const { return impl_->driver.basal_shear_force(); }
const Base& CudaSimulation::base() const { return impl_->driver.base(); }
double CudaSimulation::particle_spacing() const { return impl_->driver.particle_spacing(); }
const std::vector<MaterialParams>& CudaSimulation::materials() const {
  return impl_->driver.materials();
}
const StepConfig& CudaSimulation::config() const { return impl_->driver.config(); }
int CudaSimulation::size() const { return impl_->driver.backend().size(); }
void CudaSimulation::download(Particles& out) const { impl_->driver.backend().download(out); }

}  // namespace runout
