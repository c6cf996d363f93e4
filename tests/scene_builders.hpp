#pragma once
// Scenes built in code for the physics tests, so that they do not depend on
// the scene parser.
#include "runout/mpm/particles.hpp"
#include "runout/scene/scene.hpp"

namespace runout::fixtures {

inline Scene block_scene(Eigen::Vector2d body_min, Eigen::Vector2d body_max,
                         Eigen::Vector2d domain_min, Eigen::Vector2d domain_max, double h,
                         int ppc, double density, double youngs, double poisson) {
  Scene s;
  s.name = "test";
  s.grid.cell_size = h;
  s.grid.min = domain_min;
  s.grid.max = domain_max;
  s.grid.ppc = ppc;
  s.boundary = {BoundaryKind::Free, BoundaryKind::Free, BoundaryKind::Free, BoundaryKind::Free};
  s.gravity.vector = {0.0, 0.0};
  MaterialSpec m;
  m.name = "m";
  m.density = density;
  m.youngs_modulus = youngs;
  m.poisson_ratio = poisson;
  s.materials.push_back(m);
  BodySpec b;
  b.name = "block";
  b.polygon = {{body_min.x(), body_min.y()}, {body_max.x(), body_min.y()},
               {body_max.x(), body_max.y()}, {body_min.x(), body_max.y()}};
  s.bodies.push_back(b);
  return s;
}

// A column of width 1 m between slip walls on a fixed base, settling under
// gravity g with local damping: the self-weight problem.
inline Scene column_scene(double height, double h, double density, double youngs, double g) {
  Scene s = block_scene({0.0, 0.0}, {1.0, height}, {0.0, 0.0}, {1.0, 2.0 * height}, h, 2,
                        density, youngs, 0.3);
  s.boundary = {BoundaryKind::Slip, BoundaryKind::Slip, BoundaryKind::Fixed, BoundaryKind::Free};
  s.gravity.vector = {0.0, -g};
  s.solver.damping = 0.5;
  // Settling to a static state: a per-step PIC share filters the particle
  // velocity noise that Cundall damping, acting on nodal forces, leaves.
  s.solver.transfer = TransferKind::PicFlip;
  s.solver.flip = 0.99;
  return s;
}

// Geostatic stress of a layer whose top is at y = top under the gravity
// component g_normal into the base (sigma_yy = -rho g_n (top - y),
// sigma_xx = sigma_zz = K0 sigma_yy), so that a test starts in equilibrium
// instead of ringing from a sudden load.
inline void set_geostatic(Particles& P, double rho, double g_normal, double top, double K0) {
  for (int p = 0; p < P.size(); ++p) {
    P.syy[p] = -rho * g_normal * (top - P.y[p]);
    P.sxx[p] = P.szz[p] = K0 * P.syy[p];
    P.sxy[p] = 0.0;
  }
}

// A sensitive clay: Tresca with the multiplicative softening to su0 / St
// by xi95, regularised over a band t_s thick (t_s = 0: the local law).
inline void make_softening_clay(MaterialSpec& m, double su0, double sensitivity, double xi95,
                                double band_thickness) {
  m.model = MaterialModel::Tresca;
  m.su0 = su0;
  m.sensitivity = sensitivity;
  m.xi95 = xi95;
  m.band_thickness = band_thickness;
}

}  // namespace runout::fixtures
