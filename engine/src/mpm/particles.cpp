#include "runout/mpm/particles.hpp"

namespace runout {

std::array<StaggeredArray*, kParticleDoubles> Particles::double_arrays() {
  return {&x,   &y,   &vx,  &vy,  &mass, &vol0, &vol, &sxx, &syy, &sxy, &szz, &xi,
          &gamma_dot, &su, &band_xi, &band_rate, &x0, &y0, &cxx, &cxy, &cyx, &cyy, &fxx, &fxy,
          &fyx, &fyy};
}

std::array<const StaggeredArray*, kParticleDoubles> Particles::double_arrays() const {
  const auto a = const_cast<Particles*>(this)->double_arrays();
  std::array<const StaggeredArray*, kParticleDoubles> out;
  for (std::size_t k = 0; k < a.size(); ++k) out[k] = a[k];
  return out;
}

void Particles::resize(int n) {
  for (auto* a : double_arrays()) a->assign(n, 0.0);
  fxx.assign(n, 1.0);
  fyy.assign(n, 1.0);
  body.assign(n, 0);
  material.assign(n, 0);
  id.assign(n, 0);
}

namespace {

// On every thread: the OpenMP backend reorders its particles every few
// dozen steps (kReorderInterval), and done on one thread the copies held
// the others waiting 2.6 ms each time at 1e5 particles, 1 % of a
// two-thread run.
template <class Array>
void gather(Array& a, const std::vector<int>& order, Array& scratch) {
  scratch.resize(a.size());
  const long n = static_cast<long>(order.size());
#pragma omp parallel for schedule(static) if (n > 65536)
  for (long k = 0; k < n; ++k) scratch[k] = a[order[k]];
  a.swap(scratch);
}

}  // namespace

void Particles::permute(const std::vector<int>& order) {
  StaggeredArray d;
  for (auto* a : double_arrays()) gather(*a, order, d);
  std::vector<int> i;
  gather(body, order, i);
  gather(material, order, i);
  std::vector<std::int64_t> l;
  gather(id, order, l);
}

ParticleView Particles::view() {
  return ParticleView{size(),        x.data(),    y.data(),   vx.data(),
                      vy.data(),     mass.data(), vol0.data(), vol.data(),
                      sxx.data(),    syy.data(),  sxy.data(), szz.data(),
                      xi.data(),     gamma_dot.data(), su.data(), band_xi.data(),
                      band_rate.data(), x0.data(),
                      y0.data(),     cxx.data(),  cxy.data(), cyx.data(),
                      cyy.data(),    fxx.data(),  fxy.data(), fyx.data(),
                      fyy.data(),    body.data(), material.data(), id.data()};
}

}  // namespace runout
