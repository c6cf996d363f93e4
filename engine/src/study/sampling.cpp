#include "runout/study/sampling.hpp"

#include <cmath>
#include <cstdlib>
#include <random>
#include <sstream>

#include "runout/scene/scene_parser.hpp"

namespace runout::sampling {
namespace {

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

// z with normal_cdf(z) = p, by bisection: normal_cdf is monotone, and 200
// halvings of [-40, 40] reach the spacing of doubles.
double normal_quantile(double p) {
  double lo = -40.0, hi = 40.0;
  for (int k = 0; k < 200 && hi - lo > 0; ++k) {
    const double mid = 0.5 * (lo + hi);
    (normal_cdf(mid) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The distribution's variable as a standard normal z (normal, lognormal)
// or as itself (uniform).
double standardised(const Distribution& d, double x) {
  switch (d.kind) {
    case Distribution::Kind::Normal: return (x - d.p1) / d.p2;
    case Distribution::Kind::Lognormal:
      return x <= 0 ? -std::numeric_limits<double>::infinity() : std::log(x / d.p1) / d.p2;
    case Distribution::Kind::Uniform: break;
  }
  return x;
}

double cdf(const Distribution& d, double x) {
  if (d.kind == Distribution::Kind::Uniform)
    return std::min(1.0, std::max(0.0, (x - d.p1) / (d.p2 - d.p1)));
  return normal_cdf(standardised(d, x));
}

// A double in [0, 1) from the generator's top 53 bits.
double unit(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

[[noreturn]] void refuse(const std::string& key, const std::string& text, const std::string& why) {
  throw SceneError("--vary " + key + "=" + text + ": " + why, 0);
}

}  // namespace

Distribution parse_distribution(const std::string& key, const std::string& text) {
  const auto refuse = [&](const std::string& why) { sampling::refuse(key, text, why); };
  const std::size_t open = text.find('(');
  if (open == std::string::npos || text.back() != ')')
    sampling::refuse(key, text, "expected uniform(lo,hi), normal(mean,sd[,lo,hi]) or lognormal(median,sigma[,lo,hi])");
  const std::string name = text.substr(0, open);
  std::vector<double> args;
  std::stringstream in(text.substr(open + 1, text.size() - open - 2));
  for (std::string arg; std::getline(in, arg, ',');) {
    char* end = nullptr;
    const double v = std::strtod(arg.c_str(), &end);
    if (arg.empty() || *end != '\0' || std::isnan(v)) refuse("'" + arg + "' is not a number");
    args.push_back(v);
  }
  Distribution d;
  if (name == "uniform") {
    if (args.size() != 2) refuse("uniform takes 2 numbers: lo, hi");
    d.kind = Distribution::Kind::Uniform;
  } else if (name == "normal" || name == "lognormal") {
    if (args.size() != 2 && args.size() != 4)
      refuse(name + " takes 2 numbers, or 4 when truncated: " +
             (name == "normal" ? "mean, sd[, lo, hi]" : "median, sigma[, lo, hi]"));
    d.kind = name == "normal" ? Distribution::Kind::Normal : Distribution::Kind::Lognormal;
    if (args.size() == 4) {
      d.lo = args[2];
      d.hi = args[3];
    }
  } else {
    refuse("unknown distribution '" + name + "' (uniform, normal, lognormal)");
  }
  d.p1 = args[0];
  d.p2 = args[1];
  if (!std::isfinite(d.p1) || !std::isfinite(d.p2)) refuse("its parameters must be finite");
  if (d.kind == Distribution::Kind::Uniform && !(d.p2 > d.p1)) refuse("needs lo < hi");
  if (d.kind != Distribution::Kind::Uniform && !(d.p2 > 0))
    refuse(std::string(d.kind == Distribution::Kind::Normal ? "sd" : "sigma") + " must be > 0");
  if (d.kind == Distribution::Kind::Lognormal && !(d.p1 > 0)) refuse("the median must be > 0");
  if (!(d.hi > d.lo)) refuse("the truncation needs lo < hi");
  // A truncation so far in a tail that no double falls inside it.
  if (!(cdf(d, d.hi) - cdf(d, d.lo) > 1e-12))
    refuse("the truncation [" + std::to_string(d.lo) + ", " + std::to_string(d.hi) +
           "] holds no probability");
  return d;
}

double quantile(const Distribution& d, double u) {
  const double p = cdf(d, d.lo) + u * (cdf(d, d.hi) - cdf(d, d.lo));
  double x = 0;
  switch (d.kind) {
    case Distribution::Kind::Uniform: x = d.p1 + p * (d.p2 - d.p1); break;
    case Distribution::Kind::Normal: x = d.p1 + d.p2 * normal_quantile(p); break;
    case Distribution::Kind::Lognormal: x = d.p1 * std::exp(d.p2 * normal_quantile(p)); break;
  }
  return std::min(d.hi, std::max(d.lo, x));  // the bisection's last bit stays inside
}

std::vector<std::vector<double>> unit_design(int n, int dims, std::uint64_t seed, Design design) {
  std::mt19937_64 rng(seed);
  std::vector<std::vector<double>> points(n, std::vector<double>(dims));
  for (int j = 0; j < dims; ++j) {
    std::vector<int> stratum(n);
    for (int k = 0; k < n; ++k) stratum[k] = k;
    if (design == Design::LatinHypercube)  // Fisher-Yates with the generator's own integers
      for (int k = n - 1; k > 0; --k) std::swap(stratum[k], stratum[rng() % (k + 1)]);
    for (int k = 0; k < n; ++k) {
      const double w = unit(rng);
      points[k][j] = design == Design::LatinHypercube ? (stratum[k] + w) / n : w;
    }
  }
  // (0, 1) open: a quantile at 0 or 1 is infinite for an untruncated normal.
  for (auto& p : points)
    for (double& u : p) u = std::min(std::max(u, 0x1.0p-60), 1.0 - 0x1.0p-53);
  return points;
}

}  // namespace runout::sampling
