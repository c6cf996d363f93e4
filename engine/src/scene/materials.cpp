#include "runout/scene/materials.hpp"

namespace runout {

StrengthParams strength_params(const MaterialSpec& m) {
  if (m.model != MaterialModel::Tresca) return StrengthParams{};
  return {m.su0, 1.0 / m.sensitivity, m.xi95, m.eta, m.rate_exponent, m.reference_rate,
          m.strength_form, m.band_thickness > 0.0, m.band_thickness};
}

MaterialParams material_params(const MaterialSpec& m) {
  MaterialParams params = elastic_params(m.density, m.youngs_modulus, m.poisson_ratio);
  params.model = m.model;
  params.strength = strength_params(m);
  return params;
}

std::vector<MaterialParams> make_materials(const Scene& s) {
  std::vector<MaterialParams> out;
  for (const auto& m : s.materials) out.push_back(material_params(m));
  return out;
}

}  // namespace runout
