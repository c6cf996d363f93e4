#include "runout/mpm/grid.hpp"

namespace runout {

const GridView& Grid::fit(const GridView& placed) {
  GridView& g = view_;
  g = placed;
  const std::size_t n = static_cast<std::size_t>(g.nx) * g.ny;
  if (n > m_.size()) {
    for (auto* a : {&m_, &vol_, &px_, &py_, &fx_, &fy_, &v0x_, &v0y_, &vx_, &vy_, &dvx_, &dvy_,
                    &vmx_, &vmy_, &fbase_, &gap_, &stuck_, &qx_, &qy_, &xvx_, &xvy_, &band_su_,
                    &band_slip_})
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
  g.dvx = dvx_.data();
  g.dvy = dvy_.data();
  g.vmx = vmx_.data();
  g.vmy = vmy_.data();
  g.fbase = fbase_.data();
  g.gap = gap_.data();
  g.stuck = stuck_.data();
  g.qx = qx_.data();
  g.qy = qy_.data();
  g.xvx = xvx_.data();
  g.xvy = xvy_.data();
  g.band_su = band_su_.data();
  g.band_slip = band_slip_.data();
  return g;
}

}  // namespace runout
