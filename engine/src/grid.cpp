#include "runout/grid.hpp"

#include <algorithm>
#include <limits>

namespace runout {

void Grid::fit(int i_lo, int i_hi, int j_lo, int j_hi, double domain_x,
               double domain_y, double h) {
  GridView& g = view_;
  g.nx = i_hi - i_lo + 1;
  g.ny = j_hi - j_lo + 1;
  g.i0 = i_lo;
  g.j0 = j_lo;
  g.h = h;
  g.ox = domain_x + i_lo * h;
  g.oy = domain_y + j_lo * h;
  const std::size_t n = static_cast<std::size_t>(g.nx) * g.ny;
  if (n > m_.size()) {
    for (auto* a : {&m_, &vol_, &px_, &py_, &fx_, &fy_, &v0x_, &v0y_, &vx_, &vy_, &vmx_, &vmy_,
                    &fbase_, &gap_})
      a->resize(n);
  }
  g.m = m_.data();
  g.vol = vol_.data();
  g.px = px_.data();
  g.py = py_.data();
  g.fx = fx_.data();
  g.fy = fy_.data();
  g.v0x = v0x_.data();
  g.v0y = v0y_.data();
  g.vx = vx_.data();
  g.vy = vy_.data();
  g.vmx = vmx_.data();
  g.vmy = vmy_.data();
  g.fbase = fbase_.data();
  g.gap = gap_.data();
  for (auto* a : {&m_, &vol_, &px_, &py_, &fx_, &fy_}) std::fill_n(a->begin(), n, 0.0);
  std::fill_n(gap_.begin(), n, std::numeric_limits<double>::infinity());
}

}  // namespace runout
