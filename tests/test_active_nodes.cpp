// The CPU backend's node loops over the nodes the particles reach
// (active_nodes.hpp): every node a stencil touches is in a run, the sum
// over the runs is the sum over the box, and nodes the particles have left
// read as empty.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <vector>

#include "runout/mpm/active_nodes.hpp"
#include "runout/mpm/simulation.hpp"
#include "runout/mpm/stencil.hpp"
#include "scene_builders.hpp"

using namespace runout;

namespace {

constexpr int kBlock = OpenMpBackend::kBlock;

// Particles along a diagonal strip, 1 m thick, from (0, 0) to (60, 30).
std::vector<Eigen::Vector2d> diagonal_strip(int n) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> s(0.0, 1.0), t(0.0, 1.0);
  std::vector<Eigen::Vector2d> out;
  for (int k = 0; k < n; ++k) {
    const double a = s(rng);
    out.push_back({60.0 * a, 30.0 * a + t(rng)});
  }
  return out;
}

struct Lattice {
  GridView g;
  int blocks_x, blocks_y;
  std::vector<char> occupied;
};

Lattice lattice_of(const std::vector<Eigen::Vector2d>& points, double h) {
  Lattice L;
  double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
  for (const auto& p : points) {
    xmin = std::min(xmin, p.x());
    xmax = std::max(xmax, p.x());
    ymin = std::min(ymin, p.y());
    ymax = std::max(ymax, p.y());
  }
  place_box(L.g, xmin, xmax, ymin, ymax, -5.0, -5.0, h);
  L.blocks_x = (L.g.nx - 1 + kBlock - 1) / kBlock;
  L.blocks_y = (L.g.ny - 1 + kBlock - 1) / kBlock;
  L.occupied.assign(static_cast<std::size_t>(L.blocks_x) * L.blocks_y, 0);
  for (const auto& p : points) {
    const int ci = cell_of(p.x(), L.g.ox, h), cj = cell_of(p.y(), L.g.oy, h);
    L.occupied[(cj / kBlock) * L.blocks_x + ci / kBlock] = 1;
  }
  return L;
}

std::vector<char> covered(const ActiveNodes& active, int size) {
  std::vector<char> in(size, 0);
  active.for_each([&](int n) { in[n] = 1; });
  return in;
}

}  // namespace

TEST(ActiveNodes, CoverEveryNodeAStencilReaches) {
  const double h = 0.25;
  const auto points = diagonal_strip(20000);
  Lattice L = lattice_of(points, h);
  ActiveNodes active;
  active.find(L.g, kBlock, L.blocks_x, L.blocks_y,
              [&](int bi, int by) { return L.occupied[by * L.blocks_x + bi]; });
  const std::vector<char> in = covered(active, L.g.size());
  for (ShapeKind shape : {ShapeKind::Gimp, ShapeKind::Linear}) {
    StepConfig c;
    c.shape = shape;
    for (const auto& p : points) {
      Stencil2D s;
      stencil_at(L.g, c, p.x(), p.y(), 0.25 * h, 0.25 * h, s);
      for (int b = 0; b < 3; ++b)
        for (int a = 0; a < kStencilNodes; ++a)
          ASSERT_TRUE(in[L.g.index(s.w.first_x + a, s.w.first_y + b)])
              << "particle at " << p.x() << ", " << p.y();
    }
  }
  // The strip crosses its box diagonally: most of the box is left out.
  EXPECT_LT(active.nodes(), L.g.size() / 4);
  EXPECT_GT(active.nodes(), 0);
}

TEST(ActiveNodes, SumOverRunsIsTheBoxSumOnAnyThreadCount) {
  const double h = 0.25;
  Lattice L = lattice_of(diagonal_strip(5000), h);
  ActiveNodes active;
  active.find(L.g, kBlock, L.blocks_x, L.blocks_y,
              [&](int bi, int by) { return L.occupied[by * L.blocks_x + bi]; });
  const std::vector<char> in = covered(active, L.g.size());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> a(L.g.size(), 0.0);
  long double exact = 0;
  for (int n = 0; n < L.g.size(); ++n)
    if (in[n]) {
      a[n] = u(rng);
      exact += a[n];
    }
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const double one = active.sum(a.data(), L.g.size());
  omp_set_num_threads(2);
  const double two = active.sum(a.data(), L.g.size());
  omp_set_num_threads(threads);
  EXPECT_EQ(one, two);
  EXPECT_NEAR(one, static_cast<double>(exact), 1e-12);
}

// Two blocks flying apart along a diagonal: the box grows and moves every
// step, and most of it is empty. Where no particle is, the grid must read
// as empty (no mass, volume or momentum, the gap at +infinity), and its
// totals must be the particles'.
TEST(ActiveNodes, NodesTheParticlesLeaveReadAsEmpty) {
  Scene s = fixtures::block_scene({10.0, 10.0}, {12.0, 12.0}, {0.0, 0.0}, {60.0, 60.0}, 0.25, 2,
                                  1500.0, 1e6, 0.3);
  s.bodies[0].velocity = {-20.0, -20.0};
  BodySpec far = s.bodies[0];
  far.name = "far";
  far.polygon = {{40.0, 40.0}, {42.0, 40.0}, {42.0, 42.0}, {40.0, 42.0}};
  far.velocity = {20.0, 20.0};
  s.bodies.push_back(far);
  Simulation sim(s);
  double mass = 0;
  for (int p = 0; p < sim.particles().size(); ++p) mass += sim.particles().mass[p];
  for (int k = 0; k < 40; ++k) {
    sim.step(5e-3);  // 0.1 m a step: the box moves every few steps
    const GridView& g = sim.grid().view();
    double grid_mass = 0;
    int empty = 0;
    for (int n = 0; n < g.size(); ++n) {
      grid_mass += g.m[n];
      if (g.m[n] != 0.0) continue;
      ++empty;
      ASSERT_EQ(g.vol[n], 0.0) << "step " << k << ", node " << n;
      ASSERT_EQ(g.px[n], 0.0) << "step " << k << ", node " << n;
      ASSERT_EQ(g.py[n], 0.0) << "step " << k << ", node " << n;
      ASSERT_EQ(g.fbase[n], 0.0) << "step " << k << ", node " << n;
      ASSERT_EQ(g.gap[n], std::numeric_limits<double>::infinity()) << "step " << k;
    }
    EXPECT_NEAR(grid_mass, mass, 1e-12 * mass) << "step " << k;
    EXPECT_GT(empty, g.size() / 2) << "step " << k;
  }
}
