// The staggered allocator (staggered_allocator.hpp): the arrays a step
// allocates together start at distinct offsets in their 4 KiB pages, each
// on a cache line, and behave as plain vectors (grow, copy, swap, free).
#include <gtest/gtest.h>

#include <cstdint>
#include <set>
#include <utility>
#include <vector>

#include "runout/mpm/grid.hpp"
#include "runout/mpm/particles.hpp"

using namespace runout;

namespace {

std::uintptr_t page_offset(const double* p) { return reinterpret_cast<std::uintptr_t>(p) % 4096; }

}  // namespace

TEST(StaggeredAllocator, AParticlesArraysStartAtDistinctCacheLinesOfAPage) {
  Particles particles;
  particles.resize(100000);  // 800 kB an array: mapped whole pages when allocated plainly
  std::set<std::uintptr_t> offsets;
  for (const auto* a : particles.double_arrays()) {
    EXPECT_EQ(page_offset(a->data()) % 64, 0u);
    offsets.insert(page_offset(a->data()));
  }
  EXPECT_EQ(offsets.size(), static_cast<std::size_t>(kParticleDoubles));
}

TEST(StaggeredAllocator, TheGridsArraysStartAtDistinctOffsets) {
  Grid grid;
  GridView placed;
  placed.nx = 600;
  placed.ny = 70;
  placed.h = 0.1;
  const GridView g = grid.fit(placed);
  const double* arrays[] = {g.m,   g.vol, g.px,    g.py,  g.fx,    g.fy,  g.v0x,
                            g.v0y, g.vx,  g.vy,    g.dvx, g.dvy,   g.vmx, g.vmy,
                            g.fbase, g.gap, g.stuck, g.qx, g.qy,   g.xvx, g.xvy};
  std::set<std::uintptr_t> offsets;
  for (const double* a : arrays) offsets.insert(page_offset(a));
  EXPECT_EQ(offsets.size(), std::size(arrays));
}

TEST(StaggeredAllocator, ArraysGrowCopyAndSwapAsVectorsDo) {
  StaggeredArray a(10, 1.5);
  for (int k = 0; k < 100000; ++k) a.push_back(k);
  StaggeredArray b = a;
  EXPECT_EQ(b.size(), 100010u);
  EXPECT_EQ(b[9], 1.5);
  EXPECT_EQ(b[100009], 99999.0);
  StaggeredArray c;
  c.swap(b);
  EXPECT_TRUE(b.empty());
  EXPECT_EQ(c, a);
  c.clear();
  c.shrink_to_fit();
  EXPECT_TRUE(c.empty());
}
