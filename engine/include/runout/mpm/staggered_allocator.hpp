#pragma once
// An allocator for the large per-particle and per-node arrays that the hot
// loops read and write at the same index: each allocation starts on a
// cache line at its own offset within a 4 KiB page, 128 bytes further than
// the one before, cycling through 31 of them. Allocated plainly, every large
// array began at the same offset in its page (the allocator maps whole pages
// for them), so element i of every array had addresses equal in their low 12
// bits. A load from one array just after a store to another at the same
// index (the stress update stores vol and loads F; p2g adds rows of m, px,
// py, fx, fy) is then taken by the processor for a load of the stored bytes
// until the full addresses compare ("4K aliasing"), and waits.
#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>
#include <vector>

namespace runout {

namespace staggered_detail {

constexpr std::size_t kPage = 4096, kStagger = 128, kOffsets = 31, kFirst = 64;
static_assert(kFirst + kStagger * (kOffsets - 1) < kPage, "offsets stay within a page");

// The next offset past a page boundary: kFirst leaves room for the pointer
// deallocate needs, and keeps the array on a cache line.
inline std::size_t next_offset() {
  static std::atomic<unsigned> next{0};
  return kFirst + kStagger * (next.fetch_add(1, std::memory_order_relaxed) % kOffsets);
}

inline void* allocate_bytes(std::size_t bytes) {
  const std::size_t offset = next_offset();
  const std::size_t total = (bytes + offset + kPage - 1) / kPage * kPage;
  void* raw = std::aligned_alloc(kPage, total);
  if (!raw) throw std::bad_alloc();
  char* const start = static_cast<char*>(raw) + offset;
  reinterpret_cast<void**>(start)[-1] = raw;
  return start;
}

inline void free_bytes(void* p) { std::free(static_cast<void**>(p)[-1]); }

}  // namespace staggered_detail

template <class T>
struct StaggeredAllocator {
  using value_type = T;
  StaggeredAllocator() = default;
  template <class U>
  StaggeredAllocator(const StaggeredAllocator<U>&) {}
  T* allocate(std::size_t n) {
    return static_cast<T*>(staggered_detail::allocate_bytes(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t) { staggered_detail::free_bytes(p); }
  template <class U>
  bool operator==(const StaggeredAllocator<U>&) const { return true; }
  template <class U>
  bool operator!=(const StaggeredAllocator<U>&) const { return false; }
};

// The double arrays of the particles, of the grid and of a step's scratch.
using StaggeredArray = std::vector<double, StaggeredAllocator<double>>;

}  // namespace runout
