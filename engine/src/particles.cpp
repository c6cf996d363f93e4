#include "runout/particles.hpp"

namespace runout {

void Particles::resize(int n) {
  for (auto* a : {&x, &y, &vx, &vy, &mass, &vol0, &vol, &sxx, &syy, &sxy, &szz,
                  &xi, &gamma_dot, &su, &x0, &y0})
    a->assign(n, 0.0);
  body.assign(n, 0);
  material.assign(n, 0);
  id.assign(n, 0);
}

ParticleView Particles::view() {
  return ParticleView{size(),        x.data(),    y.data(),   vx.data(),
                      vy.data(),     mass.data(), vol0.data(), vol.data(),
                      sxx.data(),    syy.data(),  sxy.data(), szz.data(),
                      xi.data(),     gamma_dot.data(), su.data(), x0.data(),
                      y0.data(),     body.data(), material.data(), id.data()};
}

}  // namespace runout
