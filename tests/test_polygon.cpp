// The outline check of polygon bodies: the edge-grid search against every
// pair of edges on random outlines, and its cost on 1e5 vertices (testing
// every pair took 136 s there).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <random>
#include <utility>

#include "runout/scene/polygon.hpp"

using namespace runout;

namespace {

// Every pair of edges that share no vertex: the reference the grid must
// agree with, pair for pair.
std::pair<std::size_t, std::size_t> meeting_edges_by_all_pairs(const Polygon& p) {
  const std::size_t n = p.size();
  const auto turn = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
  };
  const auto on = [&](const Eigen::Vector2d& q, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return turn(a, b, q) == 0.0 && q.x() >= std::min(a.x(), b.x()) &&
           q.x() <= std::max(a.x(), b.x()) && q.y() >= std::min(a.y(), b.y()) &&
           q.y() <= std::max(a.y(), b.y());
  };
  const auto sgn = [](double v) { return (v > 0) - (v < 0); };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;
      const auto &a = p[i], &b = p[(i + 1) % n], &c = p[j], &d = p[(j + 1) % n];
      const bool cross = sgn(turn(a, b, c)) * sgn(turn(a, b, d)) < 0 &&
                         sgn(turn(c, d, a)) * sgn(turn(c, d, b)) < 0;
      if (cross || on(c, a, b) || on(d, a, b) || on(a, c, d) || on(b, c, d)) return {i, j};
    }
  return {n, n};
}

// A star-shaped outline of n vertices (simple: the angle grows along it).
Polygon star(std::size_t n) {
  Polygon p;
  for (std::size_t k = 0; k < n; ++k) {
    const double a = 2 * M_PI * double(k) / double(n);
    const double r = 10 + 3 * std::sin(7 * a) + std::cos(1000 * a);
    p.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  return p;
}

}  // namespace

TEST(Polygon, EdgeGridFindsThePairsEveryPairTestFinds) {
  std::mt19937 rng(16);
  // Small integer coordinates, so that touching, collinear overlaps and
  // shared vertices come up often.
  std::uniform_int_distribution<int> coordinate(0, 6);
  std::uniform_int_distribution<int> size(3, 12);
  int meeting = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    Polygon p(size(rng));
    for (auto& v : p) v = Eigen::Vector2d(coordinate(rng), coordinate(rng));
    const auto expected = meeting_edges_by_all_pairs(p);
    ASSERT_EQ(first_meeting_edges(p), expected) << "trial " << trial;
    meeting += expected.first < p.size();
  }
  EXPECT_GT(meeting, 1000);  // the trials test meeting edges, not only simple outlines
  EXPECT_LT(meeting, 19000);
}

TEST(Polygon, AHundredThousandVerticesInWellUnderASecond) {
  Polygon p = star(100000);
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(outline_defect(p), "");
  const double simple = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // Two neighbours swapped make a bow tie of edges 49999 and 50001.
  std::swap(p[50000], p[50001]);
  EXPECT_EQ(outline_defect(p),
            "self-intersecting polygon: edge 49999 (vertices 49999, 50000) meets edge 50001 "
            "(vertices 50001, 50002)");
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("1e5 vertices: %.3f s simple, %.3f s both\n", simple, total);
  EXPECT_LT(total, 1.0);  // a complexity bound: testing every pair took 136 s
}

TEST(Polygon, LongParallelEdgesInACellCostASortNotEveryPair) {
  // A comb of 2e4 teeth, every tooth's edges across the whole height: the
  // grid's cells then hold many edges each.
  Polygon p;
  const int teeth = 20000;
  for (int k = 0; k < teeth; ++k) {
    p.emplace_back(2.0 * k, 0.0);
    p.emplace_back(2.0 * k, 100.0);
    p.emplace_back(2.0 * k + 1, 100.0);
    p.emplace_back(2.0 * k + 1, 1.0);
  }
  p.emplace_back(2.0 * teeth, 1.0);
  p.emplace_back(2.0 * teeth, -1.0);
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(outline_defect(p), "");
  p[4 * 500 + 1].x() = 2.0 * 500 + 2.5;  // tooth 500's left edge now leans across tooth 501
  EXPECT_NE(outline_defect(p).find("self-intersecting polygon: edge 2000 "), std::string::npos)
      << outline_defect(p);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("comb of %zu vertices, twice: %.3f s\n", p.size(), wall);
  EXPECT_LT(wall, 1.0);  // a complexity bound: the cells' pairs took 13 s
}
