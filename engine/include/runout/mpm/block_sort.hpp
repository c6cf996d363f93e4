#pragma once
// The CPU backend's stable counting sort of the particles by block
// (backend_openmp.hpp): within a block particles keep their index order,
// which fixes the order of the sums at every node whatever the number of
// threads.
#include <algorithm>
#include <cstddef>
#include <vector>

#include "runout/mpm/openmp_threads.hpp"

namespace runout {

// The counting sort's two passes over a thread's range, run by run of
// particles of one block: runs are long since the last reorder, and a count
// kept in a register does not wait on the store of the one before it.
inline void count_runs(const int* block, int p0, int p1, int* count) {
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
inline void place_runs(const int* block, int p0, int p1, int* next, int* order) {
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

// The n particles into order by their block (of blocks), block_start[b]
// where block b's start: each thread bins (bin(p0, p1), which sets
// block[p]), counts and places one contiguous range of the particles, the
// ranges in index order, so the order is the serial sort's on any number
// of threads. Binning and sorting share one parallel region, which wakes
// the other threads once. places: a thread's count in each block, then its
// next place there.
template <class Bin>
void sort_by_block(int n, int blocks, const int* block, Bin bin, bool parallel, int* order,
                   std::vector<int>& block_start, std::vector<int>& places) {
  block_start.assign(blocks + 1, 0);
  places.resize(static_cast<std::size_t>(openmp::max_threads()) * blocks);
#pragma omp parallel firstprivate(bin) if (parallel)
  {
    const int t = openmp::this_thread(), threads = openmp::team_threads();
    int* const next = places.data() + static_cast<std::size_t>(t) * blocks;
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
        block_start[b] = start;
        for (int u = 0; u < threads; ++u) {
          int& slot = places[static_cast<std::size_t>(u) * blocks + b];
          const int count = slot;
          slot = start;
          start += count;
        }
      }
      block_start[blocks] = start;
    }
    place_runs(block, p0, p1, next, order);
  }
}

}  // namespace runout
