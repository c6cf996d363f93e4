#include "runout/measure/remoulded_mass.hpp"

namespace runout {

double remoulded_mass(const Particles& P, const std::vector<MaterialParams>& materials) {
  double mass = 0.0;
  for (int p = 0; p < P.size(); ++p) {
    const MaterialParams& m = materials[P.material[p]];
    if (m.model == MaterialModel::Tresca && m.strength.d_rem < 1.0 && P.xi[p] >= m.strength.xi95)
      mass += P.mass[p];
  }
  return mass;
}

}  // namespace runout
