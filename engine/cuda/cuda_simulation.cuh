#pragma once
// Device-side helpers of the CUDA driver (cuda_simulation.cu): error
// checks, grow-only device buffers and a two-pass block reduction. Only
// nvcc includes this file.
#include <cuda_runtime.h>

#include <cstddef>
#include <stdexcept>
#include <string>

namespace runout {
namespace cuda {

inline void check(cudaError_t err, const char* what) {
  if (err != cudaSuccess)
    throw std::runtime_error(std::string("CUDA: ") + what + ": " + cudaGetErrorString(err));
}
#define RUNOUT_CUDA_CHECK(call) ::runout::cuda::check((call), #call)
// After a launch: a bad configuration shows at once, a fault in the kernel
// at the next synchronising call.
#define RUNOUT_CUDA_LAUNCHED(name) ::runout::cuda::check(cudaGetLastError(), name)

// A device array that only grows: reserve() reallocates (discarding the
// contents) only when asked for more than it has, so the step loop never
// allocates once the scene has reached its largest grid box.
template <class T>
class Buffer {
 public:
  Buffer() = default;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  ~Buffer() { cudaFree(ptr_); }
  void reserve(std::size_t n) {
    if (n <= capacity_) return;
    cudaFree(ptr_);
    ptr_ = nullptr;
    capacity_ = 0;
    RUNOUT_CUDA_CHECK(cudaMalloc(&ptr_, n * sizeof(T)));
    capacity_ = n;
  }
  T* get() const { return ptr_; }
  std::size_t capacity() const { return capacity_; }

 private:
  T* ptr_ = nullptr;
  std::size_t capacity_ = 0;
};

constexpr int kThreads = 256;         // threads per block of every kernel
constexpr int kReduceBlocks = 1024;   // most blocks of a reduction's first pass

inline int blocks_for(int n) { return n > 0 ? (n + kThreads - 1) / kThreads : 1; }

// A reduction Op has a POD type T, identity(), combine(a, b) and load(i).
// Pass 1: each block reduces a grid-stride share into partials[block];
// pass 2 (one block) reduces the partials. The tree is fixed by the launch
// shape, so the result is the same on every run.
template <class Op>
__global__ void reduce_kernel(int n, Op op, typename Op::T* out) {
  using T = typename Op::T;
  __shared__ T buf[kThreads];
  T acc = op.identity();
  for (int i = blockIdx.x * blockDim.x + threadIdx.x; i < n; i += blockDim.x * gridDim.x)
    acc = op.combine(acc, op.load(i));
  buf[threadIdx.x] = acc;
  __syncthreads();
  for (int s = blockDim.x / 2; s > 0; s >>= 1) {
    if (threadIdx.x < s) buf[threadIdx.x] = op.combine(buf[threadIdx.x], buf[threadIdx.x + s]);
    __syncthreads();
  }
  if (threadIdx.x == 0) out[blockIdx.x] = buf[0];
}

// Pass 2's Op: the partials of pass 1, combined as Op does.
template <class Op>
struct PartialsOp {
  using T = typename Op::T;
  Op op;
  const T* partials;
  __device__ T identity() const { return op.identity(); }
  __device__ T combine(const T& a, const T& b) const { return op.combine(a, b); }
  __device__ T load(int i) const { return partials[i]; }
};

// Reduces op over 0..n-1 into *out (device), asynchronously. partials must
// hold kReduceBlocks values of Op::T.
template <class Op>
void reduce(int n, const Op& op, typename Op::T* partials, typename Op::T* out) {
  int blocks = blocks_for(n);
  if (blocks > kReduceBlocks) blocks = kReduceBlocks;
  reduce_kernel<<<blocks, kThreads>>>(n, op, partials);
  RUNOUT_CUDA_LAUNCHED("reduce (pass 1)");
  reduce_kernel<<<1, kThreads>>>(blocks, PartialsOp<Op>{op, partials}, out);
  RUNOUT_CUDA_LAUNCHED("reduce (pass 2)");
}

}  // namespace cuda
}  // namespace runout
