#include "runout/measure/basal_fill.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace runout {

double basal_fill(const Particles& P, const BaseView& base, double h) {
  const int n = P.size();
  if (n == 0) return NAN;
  std::vector<double> s(n), d(n);
  double lo = INFINITY, hi = -INFINITY;
  for (int p = 0; p < n; ++p) {
    const BasePoint b = locate_on_base(base, P.x[p], P.y[p]);
    s[p] = b.s;
    d[p] = b.d;
    lo = std::min(lo, b.s);
    hi = std::max(hi, b.s);
  }
  // Bins on a fixed lattice k h, so that a layer's bins do not move with
  // where its rear particle happens to lie.
  const double first = std::floor(lo / h);
  const int bins = static_cast<int>(std::floor(hi / h) - first) + 1;
  std::vector<double> all(bins, 0.0), low(bins, 0.0);
  for (int p = 0; p < n; ++p) {
    const int k = std::clamp(static_cast<int>(std::floor(s[p] / h) - first), 0, bins - 1);
    all[k] += P.vol[p];
    if (d[p] < h) low[k] += P.vol[p];
  }
  const auto thick = [&](int k) {
    return k >= 0 && k < bins && all[k] >= kBasalFillMinCells * h * h;
  };
  double filled = 0.0;
  int counted = 0;
  for (int k = 0; k < bins; ++k) {
    if (!(thick(k - 1) && thick(k) && thick(k + 1))) continue;
    filled += low[k];
    ++counted;
  }
  return counted > 0 ? filled / (counted * h * h) : NAN;
}

}  // namespace runout
