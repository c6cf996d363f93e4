// Regularised softening (nonlocal.hpp, docs/strength.md "Regularised
// softening"):
// - the operator against its defining property: a thin band carrying the
//   plastic displacement delta gives its centre delta / t_s, wherever it
//   lies between lattice nodes, for two lengths l, inside the body and
//   along its edge; a periodic lattice closes on itself; materials apart;
//   the same bits on 1 and 2 threads;
// - a softening layer in simple shear: the shear stress against the top's
//   displacement is the analytic curve of a band of thickness t_s, and the
//   same at three cells, two particle counts and two lengths, and the work
//   it dissipates is the analytic value; the local law fails both;
// - a small softening slide runs out as far on three cells, two particle
//   counts and two lengths; the local law does not.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "runout/measure/morphology.hpp"
#include "runout/mpm/nonlocal.hpp"
#include "runout/mpm/nonlocal_by_elements.hpp"
#include "runout/scene/scene_parser.hpp"
#include "runout/mpm/simulation.hpp"
#include "scene_builders.hpp"
#include "small_case4.hpp"

using namespace runout;

namespace {

// A square lattice of nx x ny particles of spacing a (volume a^2), one
// material, its lower left particle at (x0, y0).
struct Lattice {
  int nx, ny;
  double a;
  std::vector<double> x, y, vol;
  std::vector<int> material;

  Lattice(int nx_, int ny_, double a_, double x0 = 0.0, double y0 = 0.0)
      : nx(nx_), ny(ny_), a(a_) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        x.push_back(x0 + i * a);
        y.push_back(y0 + j * a);
        vol.push_back(a * a);
        material.push_back(0);
      }
    }
  }
  int size() const { return nx * ny; }
  int at(int i, int j) const { return j * nx + i; }
  NonlocalPoints points() const {
    return {size(), x.data(), y.data(), vol.data(), material.data()};
  }
};

// One row of particles of a lattice (a band one particle thick) with the
// increment a: the band carries delta = a times the spacing.
std::vector<double> band_row(const Lattice& L, int row, double a) {
  std::vector<double> in(L.size(), 0.0);
  for (int i = 0; i < L.nx; ++i) in[L.at(i, row)] = a;
  return in;
}

}  // namespace

// The discrete operator's own factor varies with where the band lies
// between nodes by at most 0.2 % (quadratic B-splines); linear weights
// would give 5 % at this spacing.
TEST(NonlocalAverage, TheBandPeakDoesNotDependOnWhereTheBandLies) {
  const double d = 1.0 / kLatticePerLength;
  const double p0 = NonlocalAverage::band_peak(d, 0.0);
  for (double s = -0.5; s < 0.5; s += 0.05)
    EXPECT_NEAR(NonlocalAverage::band_peak(d, s) / p0, 1.0, 2.5e-3) << s;
}

// A thin band carrying delta, inside the body, along a no-slip base (the
// particles' images in it), and across the body ending at its free
// surfaces: each remoulds by delta / t_s within 1 % (at its ends within
// 3 %), for two lengths and for bands at several offsets from the
// lattice's nodes; the particles beside a band, which do not yield, keep
// their xi.
TEST(NonlocalAverage, AThinBandRemouldsAfterItsDisplacementOverTs) {
  const double a = 0.02, t_s = 0.05, dxi = 0.01, delta = dxi * a;
  for (double l : {0.2, 0.35}) {
    for (double shift : {0.0, 0.013, 0.031, 0.05}) {
      const Lattice L(121, 121, a, 0.0, shift);
      BaseView base;
      base.kind = BaseKind::Planar;
      base.y0 = shift - 0.5 * a;  // the body's lower edge
      NonlocalAverage avg({Regularisation{l, t_s}}, 0.0, 0.0, base);
      std::vector<double> out(L.size());
      for (int row : {60, 0}) {
        const std::vector<double> in = band_row(L, row, dxi);
        avg.apply(L.points(), in.data(), out.data());
        EXPECT_NEAR(out[L.at(60, row)] / (delta / t_s), 1.0, 0.01)
            << "l " << l << " shift " << shift << " row " << row;
        EXPECT_EQ(out[L.at(60, row + 1)], 0.0);
      }
      std::vector<double> in(L.size(), 0.0);  // a band from the base to the top
      for (int j = 0; j < L.ny; ++j) in[L.at(60, j)] = dxi;
      NonlocalAverage free_edges({Regularisation{l, t_s}});
      free_edges.apply(L.points(), in.data(), out.data());
      for (int j : {0, 60, 120})
        EXPECT_NEAR(out[L.at(60, j)] / (delta / t_s), 1.0, j == 60 ? 0.01 : 0.03)
            << "l " << l << " shift " << shift << " end " << j;
    }
  }
}

// Yield spread over a zone wider than the averaging keeps its own strain:
// no band concentrates it.
TEST(NonlocalAverage, DiffuseYieldKeepsItsOwnStrain) {
  const Lattice L(100, 100, 0.02);
  NonlocalAverage avg({Regularisation{0.2, 0.05}});
  const std::vector<double> in(L.size(), 0.003);
  std::vector<double> out(L.size());
  avg.apply(L.points(), in.data(), out.data());
  for (int p = 0; p < L.size(); ++p) ASSERT_NEAR(out[p], 0.003, 1e-12) << p;
}

TEST(NonlocalAverage, APeriodicLatticeClosesOnItself) {
  const double a = 0.02, t_s = 0.05;
  const Lattice L(20, 81, a);  // period 0.4 m, far less than 6 l
  NonlocalAverage avg({Regularisation{0.3, t_s}}, 20 * a, -0.5 * a);
  const std::vector<double> in = band_row(L, 40, 0.01);
  std::vector<double> out(L.size());
  avg.apply(L.points(), in.data(), out.data());
  for (int i = 0; i < L.nx; ++i) {
    EXPECT_NEAR(out[L.at(i, 40)] / (0.01 * a / t_s), 1.0, 0.005) << i;
    EXPECT_NEAR(out[L.at(i, 40)], out[L.at(0, 40)], 1e-12);
  }
}

TEST(NonlocalAverage, OnlyRegularisedMaterialsAndOnlyTheirOwnParticles) {
  Lattice L(40, 40, 0.05);
  for (int p = 0; p < L.size(); ++p) L.material[p] = L.x[p] < 1.0 ? 0 : 1;
  NonlocalAverage avg({Regularisation{0.3, 0.1}, Regularisation{}});
  std::vector<double> in(L.size(), 0.0), out(L.size());
  for (int j = 0; j < L.ny; ++j) in[L.at(25, j)] = 1.0;  // a band in material 1
  avg.apply(L.points(), in.data(), out.data());
  for (int p = 0; p < L.size(); ++p) {
    if (L.material[p] == 0) EXPECT_EQ(out[p], 0.0) << p;
    else EXPECT_EQ(out[p], in[p]) << p;
  }
}

// The box, the images, the convolutions and the gather split over the
// threads, the spread runs in particle order: checked on the open lattice,
// with images in a no-slip base, and wrapping.
TEST(NonlocalAverage, TheSameBitsOnOneTwoAndThreeThreads) {
  const Lattice L(240, 120, 0.05);  // above the size that runs in parallel
  std::vector<double> in(L.size());
  for (int p = 0; p < L.size(); ++p) in[p] = std::fabs(std::sin(0.37 * p) * std::sin(0.11 * p));
  BaseView base;
  base.kind = BaseKind::Planar;
  base.y0 = -0.5 * L.a;
  const int threads = omp_get_max_threads();
  for (NonlocalAverage avg : {NonlocalAverage({Regularisation{0.3, 0.1}}),
                              NonlocalAverage({Regularisation{0.3, 0.1}}, 0.0, 0.0, base),
                              NonlocalAverage({Regularisation{0.3, 0.1}}, L.nx * L.a, -0.5 * L.a)}) {
    std::vector<double> one(L.size()), more(L.size());
    omp_set_num_threads(1);
    avg.apply(L.points(), in.data(), one.data());
    for (int t : {2, 3}) {
      omp_set_num_threads(t);
      avg.apply(L.points(), in.data(), more.data());
      for (int p = 0; p < L.size(); ++p) ASSERT_EQ(one[p], more[p]) << t << " threads, " << p;
    }
  }
  omp_set_num_threads(threads);
}

namespace {

// A backend for average_by_elements on the host that runs every stage in
// reverse order (the device's atomics take the particles in any order).
struct ReversedBackend : HostNonlocalLattice {
  template <class Stage>
  void for_each(int count, Stage stage) {
    for (int i = count - 1; i >= 0; --i) stage(i);
  }
};

struct Add {
  void operator()(double* a, int n, double v) const { a[n] += v; }
};

// The average as the device backends take it (nonlocal_by_elements.hpp).
std::vector<double> elementwise_average(const NonlocalAverage& avg, const Lattice& L,
                                        const std::vector<double>& in) {
  std::vector<double> out(in);
  std::vector<double> x(L.x), y(L.y), vol(L.vol);
  std::vector<int> material(L.material);
  ParticleView P{};
  P.n = L.size();
  P.x = x.data();
  P.y = y.data();
  P.vol = vol.data();
  P.material = material.data();
  const auto [xmin, xmax] = std::minmax_element(x.begin(), x.end());
  const auto [ymin, ymax] = std::minmax_element(y.begin(), y.end());
  ReversedBackend b;
  average_by_elements(b, avg, P, ParticleBox{*xmin, *xmax, *ymin, *ymax, 0}, avg.mirror(),
                      in.data(), out.data(), Add{});
  return out;
}

}  // namespace

// The element-wise stages the CUDA backend runs give what the host's
// average gives, to rounding: along a no-slip base (images), on a periodic
// lattice, and with a second, unregularised material.
TEST(NonlocalAverage, TheDeviceStagesGiveTheHostsAverage) {
  const auto check = [](const NonlocalAverage& avg, const Lattice& L,
                        const std::vector<double>& in) {
    std::vector<double> host(L.size());
    NonlocalAverage copy = avg;
    copy.apply(L.points(), in.data(), host.data());
    const std::vector<double> device = elementwise_average(avg, L, in);
    double largest = 0.0;
    for (double v : host) largest = std::max(largest, std::fabs(v));
    ASSERT_GT(largest, 0.0);
    for (int p = 0; p < L.size(); ++p)
      ASSERT_NEAR(device[p], host[p], 1e-12 * largest) << p;
  };
  Lattice L(90, 40, 0.05, 0.0, 0.025);
  std::vector<double> in(L.size(), 0.0);
  for (int i = 0; i < L.nx; ++i) in[L.at(i, 0)] = 0.01;                 // along the base
  for (int j = 0; j < L.ny; ++j) in[L.at(30 + j / 2, j)] = 0.02;        // a dipping band
  for (int p = 0; p < L.size(); p += 7) in[p] += 0.001 * (p % 5);       // scattered yield
  BaseView base;
  base.kind = BaseKind::Planar;
  base.y0 = 0.0;
  check(NonlocalAverage({Regularisation{0.3, 0.05}}, 0.0, 0.0, base), L, in);
  check(NonlocalAverage({Regularisation{0.3, 0.05}}, L.nx * L.a, -0.5 * L.a, base), L, in);
  for (int p = 0; p < L.size(); ++p) L.material[p] = L.x[p] < 3.0 ? 0 : 1;
  check(NonlocalAverage({Regularisation{0.25, 0.05}, Regularisation{}}), L, in);
}

namespace {

// The clay of the simple-shear column: the case 4 clay (su0 = 5 kPa, St =
// 40, xi95 = 5, E = 100 su0, no rate effect) with nu = 0.3 for a longer
// time step; a band 5 cm thick, so delta95 = 0.25 m.
constexpr double kSu0 = 5000, kE = 5e5, kNu = 0.3, kRho = 600, kSt = 40, kXi95 = 5;
constexpr double kG = kE / (2 * (1 + kNu));
constexpr double kH = 1.0, kWidth = 0.4, kTs = 0.05;  // column height, width; band thickness
constexpr double kSpeed = 0.1, kRamp = 0.5, kEndDisplacement = 0.4;
// The imperfection where the band starts: clay softened in advance in a
// layer about kSeedWidth thick at mid-height (a property of the clay, the
// same on every mesh), so that the band forms at the peak, as the analytic
// curve assumes, instead of after a stretch of diffuse yield.
constexpr double kSeedXi = 0.1, kSeedWidth = 0.05;
double seed_xi(double y) { return kSeedXi * std::exp(-std::pow((y - 0.5 * kH) / kSeedWidth, 2)); }

struct ShearCurve {
  std::vector<double> u, tau;  // the column's shear displacement [m], its shear stress [Pa]
};

// A periodic column of clay kH high on a no-slip base, under an elastic
// plate driven along x at kSpeed (reached by a linear ramp over kRamp s):
// the plate's particles are given that velocity before every step. The
// column's shear displacement is the integral of F_xy over the clay's
// initial volume per unit width (what the plate's travel is, less any slip
// at the plate and the base), its shear stress the clay's volume-weighted
// mean sxy. t_s 0: local softening.
ShearCurve simple_shear(double h, int ppc, double t_s, double l) {
  const double plate = 2 * h;
  Scene s = fixtures::block_scene({0.0, 0.0}, {kWidth, kH}, {0.0, 0.0}, {kWidth, kH + 0.5}, h, ppc,
                                  kRho, kE, kNu);
  s.boundary.left = s.boundary.right = BoundaryKind::Periodic;
  s.base.kind = BaseKind::Planar;
  s.base.interface = InterfaceKind::NoSlip;
  s.materials.push_back(s.materials[0]);  // the plate's, elastic
  s.materials[1].name = "plate";
  MaterialSpec& clay = s.materials[0];
  fixtures::make_softening_clay(clay, kSu0, kSt, kXi95, t_s);
  clay.nonlocal_length = t_s > 0.0 ? l : 0.0;
  BodySpec top = s.bodies[0];
  top.name = "plate";
  top.material = 1;
  top.polygon = {{0.0, kH}, {kWidth, kH}, {kWidth, kH + plate}, {0.0, kH + plate}};
  s.bodies.push_back(top);

  Simulation sim(s);
  Particles& start = sim.particles();
  for (int p = 0; p < start.size(); ++p)
    if (start.material[p] == 0) start.xi[p] = seed_xi(start.y[p]);
  ShearCurve curve;
  constexpr double kSample = 0.01;  // [s]
  for (double u = 0; u < kEndDisplacement + 0.01;) {
    const double t_next = sim.time() + kSample;
    while (sim.time() < t_next - 1e-12) {
      const double speed = kSpeed * std::min(1.0, sim.time() / kRamp);
      Particles& P = sim.particles();
      for (int p = 0; p < P.size(); ++p)
        if (P.material[p] == 1) {
          P.vx[p] = speed;
          P.vy[p] = 0.0;
        }
      sim.step(std::min(sim.stable_dt(), t_next - sim.time()));
    }
    const Particles& P = sim.particles();
    double stress = 0, vol = 0, shear = 0;
    for (int p = 0; p < P.size(); ++p)
      if (P.material[p] == 0) {
        stress += P.vol[p] * P.sxy[p];
        vol += P.vol[p];
        shear += P.vol0[p] * P.fxy[p];
      }
    u = shear / kWidth;
    curve.u.push_back(u);
    curve.tau.push_back(stress / vol);
  }
  return curve;
}

// The analytic curve of a band of thickness t_s through the seed in a
// column that is elastic elsewhere: u = tau H / G + delta(tau), where past
// the peak tau = su0 S(xi_seed + delta / t_s) (strength.hpp), so
// delta = -t_s ((xi95 / 3) ln((tau / su0 - d) / (1 - d)) + xi_seed);
// before it tau = G u / H.
double analytic_tau(double u, double t_s) {
  const double d = 1 / kSt;
  const double peak = kSu0 * (d + (1 - d) * std::exp(-3 * kSeedXi / kXi95));
  if (u <= peak * kH / kG) return kG * u / kH;
  double lo = d * kSu0, hi = peak;  // u(tau) falls as tau rises: bisect
  for (int it = 0; it < 100; ++it) {
    const double tau = 0.5 * (lo + hi);
    const double delta = -t_s * ((kXi95 / 3) * std::log((tau / kSu0 - d) / (1 - d)) + kSeedXi);
    (tau * kH / kG + delta > u ? lo : hi) = tau;
  }
  return 0.5 * (lo + hi);
}

// The plastic displacement delta = u - tau H / G at the end of a curve.
double plastic_displacement(const ShearCurve& c) { return c.u.back() - c.tau.back() * kH / kG; }

// The work of the shear stress on the plastic displacement, per unit area
// of band [J/m2], and its analytic value past the seed:
// su0 t_s (d x + (1 - d) (xi95 / 3) e^(-3 xi_seed / xi95) (1 - e^(-3 x / xi95))),
// x = delta / t_s.
double softening_work(const ShearCurve& c) {
  double work = 0;
  for (std::size_t k = 1; k < c.u.size(); ++k) {
    const double d0 = c.u[k - 1] - c.tau[k - 1] * kH / kG, d1 = c.u[k] - c.tau[k] * kH / kG;
    work += 0.5 * (c.tau[k - 1] + c.tau[k]) * (d1 - d0);
  }
  return work;
}
double analytic_work(double delta, double t_s) {
  const double d = 1 / kSt, x = delta / t_s;
  return kSu0 * t_s *
         (d * x + (1 - d) * (kXi95 / 3) * std::exp(-3 * kSeedXi / kXi95) *
                      (1 - std::exp(-3 * x / kXi95)));
}

double tau_at(const ShearCurve& c, double u) {
  for (std::size_t k = 1; k < c.u.size(); ++k)
    if (c.u[k] >= u)
      return c.tau[k - 1] + (c.tau[k] - c.tau[k - 1]) * (u - c.u[k - 1]) / (c.u[k] - c.u[k - 1]);
  return c.tau.back();
}

// Once the band has formed (u from 0.1 m, four times the elastic
// displacement at the peak, to the end): the largest |tau_a(u) - tau_b(u)|
// over su0.
template <class Reference>
double largest_gap(const ShearCurve& c, Reference reference) {
  double worst = 0;
  for (double u = 0.1; u <= kEndDisplacement; u += 0.005)
    worst = std::max(worst, std::fabs(tau_at(c, u) - reference(u)));
  return worst / kSu0;
}

}  // namespace

// The curves of three cells, two particle counts and two lengths lie
// within 3 % of su0 of each other and of the analytic curve once the band
// has formed (measured: within 2.2 %), and dissipate the analytic work
// within 5 % (measured: 2.7 to 4.9 % above it, most of it as the band
// forms, over the first centimetres past the peak, at a stress above the
// analytic curve's).
TEST(Regularisation, SimpleShearFollowsTheBandOfThicknessTs) {
  struct Run {
    double h;
    int ppc;
    double l;
  };
  const std::vector<Run> runs = {{0.1, 2, 0.3}, {0.05, 2, 0.15}, {0.025, 2, 0.075},
                                 {0.05, 3, 0.15}, {0.05, 2, 0.25}};
  const auto analytic = [](double u) { return analytic_tau(u, kTs); };
  std::vector<ShearCurve> curves;
  for (const Run& r : runs) {
    const ShearCurve c = simple_shear(r.h, r.ppc, kTs, r.l);
    const double work = softening_work(c), expected = analytic_work(plastic_displacement(c), kTs);
    std::printf("h %.3f ppc %d l %.3f: tau/su0 at u 0.1, 0.2, 0.3, 0.4 m: %.4f %.4f %.4f %.4f "
                "(analytic %.4f %.4f %.4f %.4f), largest gap %.4f su0, work %.1f J/m2 "
                "(analytic %.1f)\n",
                r.h, r.ppc, r.l, tau_at(c, 0.1) / kSu0, tau_at(c, 0.2) / kSu0,
                tau_at(c, 0.3) / kSu0, tau_at(c, 0.4) / kSu0, analytic(0.1) / kSu0,
                analytic(0.2) / kSu0, analytic(0.3) / kSu0, analytic(0.4) / kSu0,
                largest_gap(c, analytic), work, expected);
    EXPECT_LT(largest_gap(c, analytic), 0.03);
    EXPECT_NEAR(work / expected, 1.0, 0.05);
    curves.push_back(c);
  }
  for (std::size_t a = 0; a < curves.size(); ++a)
    for (std::size_t b = a + 1; b < curves.size(); ++b)
      EXPECT_LT(largest_gap(curves[a], [&](double u) { return tau_at(curves[b], u); }), 0.03)
          << a << " " << b;
}

// The local law on the same three cells: its band is about one cell thick,
// so it remoulds after a displacement proportional to the cell (measured:
// tau/su0 at u = 0.1 m 0.62, 0.36, 0.13; the work 2.0, 1.0 and 0.5 times
// that of a 5 cm band).
TEST(Regularisation, LocalSofteningInSimpleShearDependsOnTheCell) {
  std::vector<ShearCurve> curves;
  std::vector<double> works;
  for (double h : {0.1, 0.05, 0.025}) {
    curves.push_back(simple_shear(h, 2, 0.0, 0.0));
    const ShearCurve& c = curves.back();
    works.push_back(softening_work(c));
    std::printf("local h %.3f: tau/su0 at u 0.1, 0.2, 0.3, 0.4 m: %.4f %.4f %.4f %.4f, work %.1f "
                "J/m2\n",
                h, tau_at(c, 0.1) / kSu0, tau_at(c, 0.2) / kSu0, tau_at(c, 0.3) / kSu0,
                tau_at(c, 0.4) / kSu0, works.back());
  }
  EXPECT_GT(largest_gap(curves[0], [&](double u) { return tau_at(curves[2], u); }), 0.2);
  EXPECT_GT(works[0] / works[2], 1.5);
}

namespace {

// A smaller case 4 slide: the case 4 clay (St = 40, xi95 = 5, su0 = 5 kPa,
// the scene's t_s) and interface (tau = 1 kPa) on the 2-degree slope, a
// trapezoid 24 m long and 5 m high with 30-degree faces, nu = 0.3 for a
// longer time step. Returns the runout at t = 12 s, well before rest but
// after the spreading has set the front going. t_s 0: local softening.
double small_case4_runout(double h, int ppc, double t_s, double l) {
  Scene s = fixtures::small_case4_scene(80.0);
  s.materials[0].band_thickness = t_s;
  s.materials[0].nonlocal_length = t_s > 0.0 ? l : 0.0;
  apply_overrides(s, h, ppc);
  Simulation sim(s);
  const BaseView base = sim.base().view();
  const double spacing = sim.particle_spacing();
  const double toe0 = measure_slide(sim.particles(), base, spacing).toe_s;
  sim.advance_to(12.0);
  return runout_distance(measure_slide(sim.particles(), base, spacing), toe0);
}

double spread(const std::vector<double>& v) {
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  double mean = 0;
  for (double x : v) mean += x / v.size();
  return (*hi - *lo) / mean;
}

double scene_band_thickness() {
  return load_scene_file(std::string(RUNOUT_SOURCE_DIR) + "/scenes/case4_spreading.toml")
      .materials[0]
      .band_thickness;
}

}  // namespace

// Regularised (t_s of the scene, l three cells) on three cells with 2 x 2
// particles: runouts within 5 % of each other (measured 38.33, 37.02 and
// 36.96 m: 3.7 %). The local law on the same cells runs out far less
// (24.38, 26.95, 26.82 m): its bands, a cell or two thick, need several
// times the displacement of a 0.1 m band to remould. With 3 x 3 particles
// at 0.35 m the regularised slide runs 14 % further (42.05 m): the open
// part of docs/strength.md, "What is not converged", not asserted here.
// scripts/regularisation_chart.py draws what this test prints.
TEST(Regularisation, ASmallSlideRunsAsFarOnEveryCell) {
  const double t_s = scene_band_thickness();
  ASSERT_GT(t_s, 0.0);
  const std::vector<double> cells = {0.5, 0.35, 0.25};
  std::vector<double> regularised, local;
  for (double h : cells) {
    regularised.push_back(small_case4_runout(h, 2, t_s, kRegularisationCells * h));
    local.push_back(small_case4_runout(h, 2, 0.0, 0.0));
    std::printf("h = %.3f m, 2 x 2: runout regularised %.2f m, local %.2f m\n", h,
                regularised.back(), local.back());
  }
  std::printf("spread (max - min) / mean: regularised %.3f, local %.3f\n", spread(regularised),
              spread(local));
  EXPECT_LT(spread(regularised), 0.05);
  for (std::size_t k = 0; k < cells.size(); ++k) EXPECT_GT(regularised[k], 1.25 * local[k]);
}

// The averaging length is numerical: l of 3 and 4.5 cells at 0.35 m run
// out within 2 % of each other (measured 37.02 and 36.77 m: 0.7 %).
TEST(Regularisation, ASmallSlideRunsAsFarWithEitherAveragingLength) {
  const double t_s = scene_band_thickness(), h = 0.35;
  ASSERT_GT(t_s, 0.0);
  std::vector<double> runouts;
  for (double cells : {kRegularisationCells, 1.5 * kRegularisationCells}) {
    runouts.push_back(small_case4_runout(h, 2, t_s, cells * h));
    std::printf("h = %.3f m, 2 x 2, l = %.3f m: regularised %.2f m\n", h, cells * h,
                runouts.back());
  }
  EXPECT_LT(spread(runouts), 0.02);
}
