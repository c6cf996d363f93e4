#pragma once
// Constitutive models behind one interface: a plain parameter record and a
// stress update that switches on the model, so the same call compiles for
// the host and for CUDA without virtual functions.
#include <cmath>

#include "runout/host_device.hpp"
#include "runout/kinds.hpp"

namespace runout {

struct MaterialParams {
  MaterialModel model = MaterialModel::Elastic;
  double density = 0;  // initial density [kg/m3]
  double bulk = 0;     // K = E / (3 (1 - 2 nu))
  double shear = 0;    // G = E / (2 (1 + nu))
};

inline MaterialParams elastic_params(double density, double youngs, double poisson) {
  MaterialParams m;
  m.model = MaterialModel::Elastic;
  m.density = density;
  m.bulk = youngs / (3.0 * (1.0 - 2.0 * poisson));
  m.shear = youngs / (2.0 * (1.0 + poisson));
  return m;
}

// Constrained (P-wave) modulus K + 4G/3: the stiffness that sets the
// fastest wave speed sqrt(M / rho) in the CFL condition.
RUNOUT_HD inline double p_wave_modulus(const MaterialParams& m) {
  return m.bulk + 4.0 * m.shear / 3.0;
}

// Stress and internal variables of one material point.
struct StressPoint {
  double sxx, syy, sxy, szz;  // Cauchy stress, tension positive
  double xi;                  // accumulated plastic shear strain
  double su;                  // current strength (0 for elastic)
};

// Plane-strain strain increment (tensor components; dezz = 0) and the
// shear strain rate of the step.
struct StrainIncrement {
  double dexx, deyy, dexy;
  double gamma_dot;
  double dt;
};

// Hypoelastic update: dsigma = lambda tr(de) I + 2 G de with de_zz = 0, so
// sigma_zz picks up lambda tr(de) (plane strain). The objective (Jaumann)
// rotation is applied by the caller before this.
RUNOUT_HD inline void elastic_update(const MaterialParams& m, const StrainIncrement& d,
                                     StressPoint& s) {
  const double lambda = m.bulk - 2.0 * m.shear / 3.0;
  const double tr = d.dexx + d.deyy;
  s.sxx += lambda * tr + 2.0 * m.shear * d.dexx;
  s.syy += lambda * tr + 2.0 * m.shear * d.deyy;
  s.szz += lambda * tr;
  s.sxy += 2.0 * m.shear * d.dexy;
}

RUNOUT_HD inline void update_stress(const MaterialParams& m, const StrainIncrement& d,
                                    StressPoint& s) {
  switch (m.model) {
    case MaterialModel::Elastic:
      elastic_update(m, d, s);
      break;
  }
}

}  // namespace runout
