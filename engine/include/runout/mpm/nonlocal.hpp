#pragma once
// Regularised softening (docs/strength.md, "Regularised softening"): the
// increment of the softening variable xi of one step, as the return
// mapping found it particle by particle (a_p), replaced by the plastic
// shear displacement delta that the band through the particle carries,
// over the physical band thickness t_s of the clay, where the particle is
// in a band:
//
//   delta_p / t_s = (sum_q w_pq V_q a_q / sum_q w_pq V_q) W_inf / (t_s K_line),
//   w(r) = exp(-(r / l)^2),
//
// over the particles q of p's material, W_inf = pi l^2 the weight sum deep
// inside a body and K_line = sqrt(pi) l the integral of w along a line
// through its centre.
//
// Why this form. Remoulding in a band is governed by the displacement
// across it (Einav & Randolph 2005; the crack band of Bazant & Oh 1983; in
// MPM the regularised Mohr-Coulomb of Tran & Solowski 2019, which scales
// the band's strain by t_FE / t_shear). A computed band of any numerical
// width b well below l carrying delta (per unit length along it: the sum
// over the band of V a is delta) gives delta K_line / W_inf as the
// normalised average at its centre, so the above is delta / t_s whatever
// the cell, the particles per cell and l (to O((b / l)^2): 2 % at
// b = l / 2). The band's width is then measured, b = delta / a_p, rather
// than assumed: a zone that yields over the averaging width or more is
// diffuse yield, which no band concentrates, and keeps its own strain
// (localised_increment in nonlocal_lattice.hpp). The normalisation keeps a band
// that ends at a free surface whole up to the surface; a band along a
// no-slip base, where the clay's shear gathers, keeps the whole kernel
// across it by the volumes of the particles' images in the base (the
// base given to the constructor). l is numerical, kRegularisationCells
// cells unless nonlocal_length sets it: the answer does not depend on it
// (tests/test_regularisation.cpp).
//
// How it is evaluated, in O(N): the particles' V a and V are spread onto a
// lattice of spacing l / 3 with quadratic B-spline weights, the lattice is
// convolved with w along x and then along y (w is separable), and each
// particle takes the two sums back with the same weights. Quadratic
// B-splines reproduce the second moment about any point, so the centre
// value of a band moves by at most 0.2 % with where it lies between
// lattice nodes (5 % with linear weights); the lattice is fixed in space,
// its spacing set by l, not by the cell. It wraps along x in a periodic
// scene. The sums run in a fixed order, so the result does not depend on
// the number of threads. The CUDA backend takes the same lattice
// (lattice()) and the element-wise stages of nonlocal_lattice.hpp on the
// device.
#include <vector>

#include "runout/mpm/base.hpp"
#include "runout/mpm/nonlocal_lattice.hpp"

namespace runout {

constexpr double kNonlocalCutoff = 3.0;         // in l: exp(-9) = 1.2e-4 of the weight is left out
constexpr double kLatticePerLength = 3.0;       // lattice nodes per l
constexpr double kRegularisationCells = 3.0;    // the default l, in cells

struct NonlocalPoints {
  int n = 0;
  const double *x = nullptr, *y = nullptr;  // positions [m]
  const double* vol = nullptr;              // volumes [m2 per m out of plane]
  const int* material = nullptr;            // material index
};

// Per material: l [m] (0: not regularised) and t_s [m].
struct Regularisation {
  double length = 0;
  double band_thickness = 0;
};

class NonlocalAverage {
 public:
  // period > 0: the scene is periodic along x with that period from x0.
  // mirror: a no-slip base (BaseKind::None: none).
  explicit NonlocalAverage(std::vector<Regularisation> materials = {}, double period = 0,
                           double x0 = 0, BaseView mirror = {});

  bool active() const { return active_; }
  std::vector<double> lengths() const;  // l per material, 0 where not regularised

  // out[p] = the regularised increment for the particles of a regularised
  // material, in[p] otherwise; in >= 0.
  void apply(const NonlocalPoints& points, const double* in, double* out);

  // The centre value of a band at offset s (in lattice spacings) from a
  // node, over the value of an infinitely thin band's: the discrete
  // operator's own factor, which apply divides out at s = 0.
  static double band_peak(double spacing_over_length, double s);

  // For a backend that averages on its own (CUDA): material m's settings,
  // the lattice over a box that holds its particles and their images (the
  // taps point into this object), how far above the base a particle has an
  // image, and the factor that turns the normalised average into
  // delta / t_s.
  const Regularisation& regularisation(int m) const { return materials_[m]; }
  int materials() const { return static_cast<int>(materials_.size()); }
  const BaseView& mirror() const { return mirror_; }
  NonlocalLattice lattice(int m, double xmin, double xmax, double ymin, double ymax) const;
  double image_reach(int m) const { return kNonlocalCutoff * materials_[m].length; }
  double band_scale(int m) const;
  // Material m's kernel sampled along each axis of its lattice.
  struct Taps {
    std::vector<double> x, y;             // w at 0, 1, 2, ... spacings along each axis
    double spacing_x = 0, spacing_y = 0;  // [m]
    int wrap = 0;                         // nodes along a periodic x; 0: not periodic
  };
  const Taps& taps(int m) const { return taps_[m]; }  // empty where m is not regularised

 private:
  void convolve(std::vector<double>& field, const LatticeAxis& ax, const LatticeAxis& ay);
  void average_material(const NonlocalPoints& P, const double* in, double* out, int material);

  std::vector<Regularisation> materials_;
  std::vector<Taps> taps_;  // per material
  double period_, x0_;
  BaseView mirror_;
  bool active_ = false;
  std::vector<double> increments_, volumes_, pass_;  // the spread V a and V, and the x pass
  struct Span {
    int first = 0, last = 0;  // the columns [first, last) of a row of the x pass that are not zero
  };
  std::vector<Span> spans_;  // per row; first == last: the row is zero
  // Chunk c: the particles c kSpreadChunk onwards by index, kSpreadChunk
  // of them (the last fewer); the box of the material's particles among
  // them [m], and the lattice nodes they and their images spread onto, at
  // chunk_sums_[at] (V a, then V; ni x nj each).
  struct Chunk {
    double xmin, xmax, ymin, ymax;
    int i0 = 0, j0 = 0, ni = 0, nj = 0;
    std::size_t at = 0;
  };
  static constexpr int kSpreadChunk = 8192;
  void spread(const NonlocalPoints& P, const double* in, int material, double reach, double pad,
              const NonlocalLattice& g);
  void spread_chunk(const NonlocalPoints& P, const double* in, int material, double reach,
                    const NonlocalLattice& g, int c);
  std::vector<Chunk> chunks_;
  std::vector<double> chunk_sums_;
};

}  // namespace runout
