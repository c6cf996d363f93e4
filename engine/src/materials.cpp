#include "runout/materials.hpp"

namespace runout {

StrengthParams strength_params(const MaterialSpec& m) {
  if (m.model != MaterialModel::Tresca) return StrengthParams{};
  return {m.su0, 1.0 / m.sensitivity, m.xi95, m.eta, m.rate_exponent, m.reference_rate,
          m.strength_form};
}

// Softening localises plastic strain into bands about as thick as the
// bands the grid can resolve, t = c h with c a fixed number of cells. What
// remoulds a band is the shear displacement across it, delta = xi t, so a
// law in xi alone softens a band of a finer grid after less displacement,
// and the runout depends on h. Holding delta95 = xi95 t fixed at its value
// on the reference grid gives xi95(h) = xi95 h_ref / h: the element-size
// scaling of the softening modulus of Pietruszczak & Mroz (1981), Int. J.
// Numer. Meth. Eng. 17, as used with delta95 for sensitive-clay spreads by
// Dey, Hawlader, Phillips & Soga (2015), Geotechnique 65(8).
double mesh_adjusted_xi95(const MaterialSpec& m, double cell_size) {
  if (m.xi95_reference_cell <= 0.0) return m.xi95;
  return m.xi95 * m.xi95_reference_cell / cell_size;
}

MaterialParams material_params(const MaterialSpec& m, double cell_size) {
  MaterialParams params = elastic_params(m.density, m.youngs_modulus, m.poisson_ratio);
  params.model = m.model;
  params.strength = strength_params(m);
  if (m.model == MaterialModel::Tresca) params.strength.xi95 = mesh_adjusted_xi95(m, cell_size);
  return params;
}

}  // namespace runout
