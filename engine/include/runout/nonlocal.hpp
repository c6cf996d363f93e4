#pragma once
// Nonlocal averaging of a per-particle field over a material length l
// (docs/strength.md, "Nonlocal softening"): the regularisation of strain
// softening. The MPM driver gives it the increment of the softening
// variable xi of one step, as the return mapping found it particle by
// particle, and adds the average to xi instead:
//
//   a*_p = sum_q w(r_pq) V_q a_q / sum_q w(r_pq) V_q,   w(r) = exp(-(r / l)^2)
//
// over the particles q of p's material within kNonlocalCutoff l of p
// (Brinkgreve 1994, PhD thesis, TU Delft; Galavi & Schweiger 2010, Int. J.
// Geomech. 10(1); in MPM Burghardt, Brannon & Guilkey 2012, Int. J. Numer.
// Anal. Meth. Geomech. 36). A softening band then cannot be thinner than
// about l whatever the cell size, so the energy it dissipates, and the
// runout, stop depending on h once h is well below l.
//
// The weight is the Gaussian rather than Galavi & Schweiger's
// (r / l) exp(-(r / l)^2): that one gives a particle no weight of its own,
// so a band one particle wide would hand its whole increment to its
// neighbours and stop softening where it yields; the Gaussian keeps the
// largest share where the plastic strain is made and is the usual kernel of
// integral-type nonlocal models (Bazant & Jirasek 2002, J. Eng. Mech. 128).
//
// The sums over q are evaluated by binning: the particles of the material
// are gathered into square bins of side l / kNonlocalBinsPerLength, fixed
// in physical size, and each bin enters the denominator as its volume at
// its volume centroid and the numerator as its sum of V a at the centroid
// of V a (a >= 0: plastic increments). The first moments are exact, so the
// error is second order in the bin size, and since the bins scale with l,
// not with the cell size, it does not bring back a mesh dependence; the
// cost is about a hundred bins per particle whatever the particle spacing,
// where pairs would be (l / spacing)^2 times more.
//
// Properties (tests/test_regularisation.cpp): a uniform field stays
// uniform (the weights are normalised per particle); a spike at q
// becomes w(r) V_q a_q / sum w V, and the sum is close to pi l^2 (1 - e^-9)
// per unit volume inside a body; the volume integral sum_p V_p a_p is kept
// inside a body where the weight sums of all particles within reach agree;
// near an edge the particles further in take a smaller share of an
// increment made at the edge, so part of it is lost.
#include <vector>

namespace runout {

constexpr double kNonlocalCutoff = 3.0;  // in l: exp(-9) = 1.2e-4 of the weight is left out
constexpr double kNonlocalBinsPerLength = 2.0;

struct NonlocalPoints {
  int n = 0;
  const double *x = nullptr, *y = nullptr;  // positions [m]
  const double* vol = nullptr;              // volumes [m2 per m out of plane]
  const int* material = nullptr;            // material index
};

class NonlocalAverage {
 public:
  // lengths[m] > 0: the averaging length l [m] of material m; 0: its
  // particles are not averaged.
  explicit NonlocalAverage(std::vector<double> lengths = {});

  bool active() const { return active_; }
  double length(int material) const { return lengths_[material]; }

  // out[p] = a*_p for the particles of a material with a length, in[p]
  // otherwise; in >= 0. The sums run in a fixed order, so the result does
  // not depend on the number of threads.
  void apply(const NonlocalPoints& points, const double* in, double* out);

 private:
  // Moments of one bin's points with masses m (the volumes, or V a): the
  // total, then the centroid and the central second moments.
  struct Moments {
    double mass = 0, x = 0, y = 0, xx = 0, xy = 0, yy = 0;
    void add(double m, double u, double v);
    void centre(double cx, double cy);
    double weighted(double px, double py, double inv_l2) const;
  };
  struct Bin {
    Moments vol, sum;
  };
  void aggregate(const NonlocalPoints& points, const double* in, int material);
  int bin_index(double x, double y) const;
  double average_at(double x, double y, double l, double own_value) const;

  std::vector<double> lengths_;
  bool active_ = false;
  // The bins of the material being averaged, over its particles' bounding box.
  double bin_ = 0, x0_ = 0, y0_ = 0;
  int bins_x_ = 0, bins_y_ = 0;
  std::vector<Bin> bins_;
};

}  // namespace runout
