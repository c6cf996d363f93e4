#pragma once
// Particle state in structure-of-arrays, double precision. Particles owns
// the storage (host); ParticleView is the plain-pointer handle the
// per-particle stage functions take, so the same functions run in CUDA
// kernels on device copies.
#include <array>
#include <cstdint>
#include <vector>

#include "runout/mpm/staggered_allocator.hpp"

namespace runout {

struct ParticleView {
  int n = 0;
  double *x, *y;          // current position [m]
  double *vx, *vy;        // velocity [m/s]
  double *mass;           // [kg per metre out of plane]
  double *vol0, *vol;     // initial and current volume [m2 per metre]
  double *sxx, *syy, *sxy, *szz;  // Cauchy stress, tension positive [Pa]
  double *xi;             // accumulated plastic shear strain
  double *gamma_dot;      // shear strain rate [1/s]
  double *su;             // current undrained strength [Pa] (0 for elastic)
  // The clay's basal band under StepConfig::clay_band (band_softening):
  // the slip it has carried over its thickness t_s, and that slip's rate
  // over t_s in the last step (0 off the band).
  double *band_xi, *band_rate;
  double *x0, *y0;        // initial position [m]
  // Affine velocity C = dv/dx carried by the particle (APIC, Jiang et al.
  // 2015); zero under the PIC/FLIP transfer.
  double *cxx, *cxy, *cyx, *cyy;
  // Deformation gradient F (identity at the start): it shapes the particle's
  // GIMP domain (stencil.hpp, domain_half_widths).
  double *fxx, *fxy, *fyx, *fyy;
  int *body;              // body index in the scene
  int *material;          // material index in the scene
  std::int64_t *id;       // stable particle id
};

// The number of double arrays a particle carries.
constexpr int kParticleDoubles = 26;

struct Particles {
  // Staggered in their pages (staggered_allocator.hpp): the stress update
  // loads and stores a dozen of them at one index.
  StaggeredArray x, y, vx, vy, mass, vol0, vol, sxx, syy, sxy, szz, xi, gamma_dot, su, band_xi,
      band_rate, x0, y0, cxx, cxy, cyx, cyy, fxx, fxy, fyx, fyy;
  std::vector<int> body, material;
  std::vector<std::int64_t> id;

  int size() const { return static_cast<int>(x.size()); }
  // The double arrays, always in this order (x .. fyy as declared).
  std::array<StaggeredArray*, kParticleDoubles> double_arrays();
  std::array<const StaggeredArray*, kParticleDoubles> double_arrays() const;
  // n particles at rest, undeformed (F = I), everything else zero.
  void resize(int n);
  ParticleView view();
  // Reorders every array so that particle k becomes order[k].
  void permute(const std::vector<int>& order);
};

}  // namespace runout
