// `runout study --sample --vary`: the distributions' quantiles against
// known values, the Latin hypercube's strata, determinism for a seed, and
// the refusal of a distribution that cannot be sampled, naming the key.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "runout/study/sampling.hpp"
#include "runout/scene/scene_parser.hpp"

using namespace runout;
using namespace runout::sampling;

TEST(Sampling, QuantilesOfKnownDistributions) {
  const Distribution u = parse_distribution("k", "uniform(2000,3000)");
  EXPECT_DOUBLE_EQ(quantile(u, 0.25), 2250.0);
  const Distribution n = parse_distribution("k", "normal(2500,300)");
  EXPECT_NEAR(quantile(n, 0.5), 2500.0, 1e-9);
  // Phi(1) = 0.841344746068543, Phi(-1.959963984540054) = 0.025.
  EXPECT_NEAR(quantile(n, 0.841344746068543), 2800.0, 1e-6);
  EXPECT_NEAR(quantile(n, 0.025), 2500.0 - 1.959963984540054 * 300.0, 1e-6);
  const Distribution ln = parse_distribution("k", "lognormal(2500,0.2)");
  EXPECT_NEAR(quantile(ln, 0.5), 2500.0, 1e-9);  // the median
  EXPECT_NEAR(quantile(ln, 0.841344746068543), 2500.0 * std::exp(0.2), 1e-6);
  // Truncated to [2400, 2600]: the quantiles stay inside and the median of a
  // symmetric truncation is the mean.
  const Distribution t = parse_distribution("k", "normal(2500,300,2400,2600)");
  EXPECT_NEAR(quantile(t, 0.5), 2500.0, 1e-6);
  for (double p : {1e-12, 0.01, 0.99, 1 - 1e-12}) {
    EXPECT_GE(quantile(t, p), 2400.0);
    EXPECT_LE(quantile(t, p), 2600.0);
  }
  // One-sided: su0 > 0 of a wide normal.
  const Distribution pos = parse_distribution("k", "normal(1000,1000,0,inf)");
  EXPECT_GE(quantile(pos, 1e-9), 0.0);
}

TEST(Sampling, LatinHypercubeHoldsOnePointPerStratum) {
  const int n = 64, dims = 3;
  const auto u = unit_design(n, dims, 7, Design::LatinHypercube);
  ASSERT_EQ(u.size(), std::size_t(n));
  for (int j = 0; j < dims; ++j) {
    std::set<int> strata;
    for (const auto& p : u) {
      EXPECT_GT(p[j], 0.0);
      EXPECT_LT(p[j], 1.0);
      strata.insert(static_cast<int>(std::floor(p[j] * n)));
    }
    EXPECT_EQ(strata.size(), std::size_t(n)) << "dimension " << j;
  }
  // The dimensions are permuted independently: not the same order.
  int same = 0;
  for (const auto& p : u) same += std::floor(p[0] * n) == std::floor(p[1] * n);
  EXPECT_LT(same, n / 2);
}

TEST(Sampling, ASeedGivesTheSameDesignAnotherADifferentOne) {
  for (Design d : {Design::LatinHypercube, Design::MonteCarlo}) {
    EXPECT_EQ(unit_design(16, 2, 42, d), unit_design(16, 2, 42, d));
    EXPECT_NE(unit_design(16, 2, 42, d), unit_design(16, 2, 43, d));
  }
  // Monte Carlo draws are independent: some strata stay empty with 64 points
  // (the chance that none does is 64! / 64^64).
  std::set<int> strata;
  for (const auto& p : unit_design(64, 1, 5, Design::MonteCarlo))
    strata.insert(static_cast<int>(std::floor(p[0] * 64)));
  EXPECT_LT(strata.size(), 64u);
}

TEST(Sampling, RefusalsNameTheKey) {
  const auto refusal = [](const std::string& text) {
    try {
      parse_distribution("material.clay.su0", text);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string prefix = "--vary material.clay.su0=";
  EXPECT_EQ(refusal("normal(2500,-3)"), prefix + "normal(2500,-3): sd must be > 0");
  EXPECT_EQ(refusal("uniform(3,2)"), prefix + "uniform(3,2): needs lo < hi");
  EXPECT_EQ(refusal("lognormal(-1,0.2)"), prefix + "lognormal(-1,0.2): the median must be > 0");
  EXPECT_EQ(refusal("weibull(1,2)"),
            prefix + "weibull(1,2): unknown distribution 'weibull' (uniform, normal, lognormal)");
  EXPECT_EQ(refusal("normal(1,x)"), prefix + "normal(1,x): 'x' is not a number");
  EXPECT_EQ(refusal("normal(1,2,3)"),
            prefix + "normal(1,2,3): normal takes 2 numbers, or 4 when truncated: mean, sd[, lo, hi]");
  EXPECT_NE(refusal("normal(0,1,50,60)").find("holds no probability"), std::string::npos);
  EXPECT_NE(refusal("2500").find("expected uniform(lo,hi)"), std::string::npos);
  EXPECT_NE(refusal("").find("expected uniform(lo,hi)"), std::string::npos);
}
