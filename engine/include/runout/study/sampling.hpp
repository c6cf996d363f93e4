#pragma once
// `runout study --sample N --seed S --vary KEY=DISTRIBUTION`: the
// distributions a scene key's value may be drawn from, and the sampling
// designs (docs/study.md). Deterministic for a seed on every platform: the
// generator is std::mt19937_64 and every conversion from its integers is
// this file's, not the standard library's implementation-defined ones.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace runout::sampling {

// uniform(lo,hi); normal(mean,sd); lognormal(median,sigma), ln x being
// normal(ln median, sigma); normal and lognormal truncated to [lo, hi]
// with two more arguments: normal(mean,sd,lo,hi).
struct Distribution {
  enum class Kind { Uniform, Normal, Lognormal } kind = Kind::Uniform;
  double p1 = 0, p2 = 1;  // lo, hi | mean, sd | median, sigma
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
};

// Throws SceneError "--vary KEY=TEXT: why" for an unknown name, a wrong
// number of arguments, a non-number, or parameters that cannot be sampled
// (sd <= 0, hi <= lo, a median <= 0, a truncation holding no probability).
Distribution parse_distribution(const std::string& key, const std::string& text);

// The value at probability u in (0, 1) of the (truncated) distribution.
double quantile(const Distribution& d, double u);

enum class Design { LatinHypercube, MonteCarlo };

// n points in (0, 1)^dims, point-major. Latin hypercube: each dimension's
// n strata [k/n, (k+1)/n) hold one point each, in an independent random
// order, at a uniform place within the stratum; Monte Carlo: independent
// uniform draws.
std::vector<std::vector<double>> unit_design(int n, int dims, std::uint64_t seed, Design design);

}  // namespace runout::sampling
