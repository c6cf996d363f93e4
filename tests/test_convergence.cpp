// Runouts that do not depend on the numerics (docs/convergence.md):
// - the time step: the column collapse and coarse case 2 run out within 2 %
//   of each other at Courant 0.1, 0.2 and 0.25, the limit (at 0.3 case 2
//   runs 2.7 % further, which is why 0.3 is refused);
// - energy: an elastic bar vibrating in its first mode keeps its total
//   energy within 1 % over 10 periods with the default transfer, where PIC
//   loses most of it;
// - stability at rest: coarse case 2, stopped, keeps under 5 % of its peak
//   kinetic energy from 30 to 60 s with the default transfer (FLIP with
//   XPIC(5) every 40 cell crossings: 3.2 %), where pure FLIP keeps over
//   10 % (22 %) in noise next to the base;
// - numerical fracture: in a bar stretched to three times its length the
//   widest gap between neighbouring particle domains along a row is a
//   fifth of uGIMP's or less with deforming domains (0.011 against 0.77
//   cells);
// - mesh convergence of the non-softening cases 2 and 3 at 1, 0.5 and
//   0.25 m cells: the runout differences shrink, with the observed order
//   printed (1.70 for case 2, 2.00 for case 3 at 9776f13); case 3 is
//   within 2 % of its 0.25 m runout at 0.5 m. On finer cells case 2's
//   runout stays in a band of +-3 % with no order (docs/convergence.md,
//   "Mesh trend"), so the three cells here do not show its convergence.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include "runout/measure/diagnostics.hpp"
#include "runout/measure/morphology.hpp"
#include "runout/scene/scene_parser.hpp"
#include "runout/mpm/simulation.hpp"
#include "scene_builders.hpp"

using namespace runout;

namespace {

Scene reference(const std::string& name) {
  return load_scene_file(std::string(RUNOUT_SOURCE_DIR) + "/scenes/" + name + ".toml");
}

double toe(const Simulation& sim) {
  return measure_slide(sim.particles(), sim.base().view(), sim.particle_spacing()).toe_s;
}

// Toe runout at time t.
double runout_at(Scene s, double t) {
  Simulation sim(s);
  const double start = toe(sim);
  sim.advance_to(t);
  return toe(sim) - start;
}

double spread(const std::vector<double>& v) {
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return (*hi - *lo) / *lo;
}

std::vector<double> runouts_over_courant(Scene s, double t) {
  std::vector<double> out;
  for (double courant : {0.1, 0.2, 0.25}) {
    s.time.courant = courant;
    out.push_back(runout_at(s, t));
    std::printf("Courant %.2f: runout %.4f m\n", courant, out.back());
  }
  return out;
}

// Elastic strain energy of the particles, from their stress through the
// plane-strain compliance: w = (s:s - nu/(1+nu) tr(s)^2) / (4 G) per volume.
double strain_energy(const Particles& P, double E, double nu) {
  const double G = E / (2.0 * (1.0 + nu));
  double W = 0;
  for (int p = 0; p < P.size(); ++p) {
    const double tr = P.sxx[p] + P.syy[p] + P.szz[p];
    const double ss = P.sxx[p] * P.sxx[p] + P.syy[p] * P.syy[p] + P.szz[p] * P.szz[p] +
                      2.0 * P.sxy[p] * P.sxy[p];
    W += P.vol[p] * (ss - nu / (1.0 + nu) * tr * tr) / (4.0 * G);
  }
  return W;
}

// Total energy of a fixed-free bar released in its first mode, as a
// fraction of the initial, after 10 periods.
SolverSpec transfer(TransferKind kind, double flip = 1.0, double xpic_cells = 0.0) {
  SolverSpec s;
  s.transfer = kind;
  s.flip = flip;
  s.xpic_cells = xpic_cells;
  return s;
}

double bar_energy_kept(const SolverSpec& solver) {
  const double L = 25.0, E = 100.0, rho = 1.0, h = 0.5, v0 = 0.01, nu = 0.0;
  Scene s = fixtures::block_scene({0.0, 0.0}, {L, h}, {0.0, 0.0}, {2.0 * L, h}, h, 2, rho, E, nu);
  s.boundary = {BoundaryKind::Fixed, BoundaryKind::Free, BoundaryKind::Slip, BoundaryKind::Slip};
  s.solver = solver;
  Simulation sim(s);
  Particles& P = sim.particles();
  for (int p = 0; p < P.size(); ++p) P.vx[p] = v0 * std::sin(M_PI * P.x[p] / (2.0 * L));
  const auto energy = [&] { return particle_totals(P).kinetic_energy + strain_energy(P, E, nu); };
  const double initial = energy();
  sim.advance_to(10.0 * 4.0 * L / std::sqrt(E / rho));
  return energy() / initial;
}

// The widest gap between the domains of neighbours along the rows of a
// stretched bar (positive: they no longer touch), in cells.
double widest_row_gap(const Simulation& sim) {
  Particles copy = sim.particles();
  const ParticleView P = copy.view();
  const double h = sim.grid().view().h;
  std::map<double, std::vector<std::pair<double, double>>> rows;  // y0 -> (x, lx)
  for (int p = 0; p < P.n; ++p) {
    double lx, ly;
    domain_half_widths(P, p, sim.config(), h, lx, ly);
    rows[P.y0[p]].push_back({P.x[p], lx});
  }
  double widest = -1e9;
  for (auto& [y0, row] : rows) {
    std::sort(row.begin(), row.end());
    for (std::size_t k = 1; k < row.size(); ++k)
      widest = std::max(widest, (row[k].first - row[k].second) -
                                    (row[k - 1].first + row[k - 1].second));
  }
  return widest / h;
}

// A soft Tresca bar, 4 m by 0.5 m at 4 x 4 particles per cell, given the
// velocity of a uniform stretch v_x = x (1/s): it yields at once, thins as
// it stretches, and by 2.4 s is over three times its length.
Simulation stretched_bar(DomainKind domain) {
  Scene s = fixtures::block_scene({-2.0, 0.0}, {2.0, 0.5}, {-8.0, 0.0}, {8.0, 1.0}, 0.25, 4,
                                  1000.0, 1e5, 0.3);
  s.materials[0].model = MaterialModel::Tresca;
  s.materials[0].su0 = 10.0;
  s.grid.domain = domain;
  Simulation sim(s);
  Particles& P = sim.particles();
  for (int p = 0; p < P.size(); ++p) P.vx[p] = P.x[p];
  sim.advance_to(2.4);
  return sim;
}

double length(const Simulation& sim) {
  const auto [lo, hi] = std::minmax_element(sim.particles().x.begin(), sim.particles().x.end());
  return *hi - *lo;
}

}  // namespace

TEST(Convergence, ColumnCollapseRunoutDoesNotMoveWithTheCourantNumber) {
  const std::vector<double> r = runouts_over_courant(reference("column_collapse_tresca"), 1.0);
  EXPECT_GT(r[0], 0.2);  // it collapses: 0.39 m
  EXPECT_LT(spread(r), 0.02);
}

TEST(Convergence, CoarseCase2RunoutDoesNotMoveWithTheCourantNumber) {
  Scene s = reference("case2_elongation_noslip");
  apply_overrides(s, 0.5, 2);
  const std::vector<double> r = runouts_over_courant(s, 12.0);
  EXPECT_GT(r[0], 5.0);
  EXPECT_LT(spread(r), 0.02);
}

TEST(Convergence, ElasticBarKeepsItsEnergyWithTheDefaultTransferAndPicLosesIt) {
  const double filtered = bar_energy_kept(SolverSpec{});  // FLIP, XPIC(5) every 40 crossings
  const double flip = bar_energy_kept(transfer(TransferKind::Flip));
  const double apic = bar_energy_kept(transfer(TransferKind::Apic));
  const double xpic = bar_energy_kept(transfer(TransferKind::Xpic));
  const double pic = bar_energy_kept(transfer(TransferKind::PicFlip, 0.0));
  std::printf("bar energy after 10 periods: default (FLIP, XPIC(5) every 40 cell crossings) "
              "%.5f, pure FLIP %.5f, APIC %.5f, XPIC(5) every step %.5f, PIC %.5f\n",
              filtered, flip, apic, xpic, pic);
  EXPECT_NEAR(flip, 1.0, 0.01);
  EXPECT_NEAR(filtered, 1.0, 0.01);
  EXPECT_LT(pic, 0.5);
}

// Coarse case 2 (1 m cells) run on after it has stopped: the kinetic
// energy left (from 30 to 60 s) as a share of its peak, and the fastest
// particle at 60 s. Pure FLIP keeps noise next to the no-slip base that
// no grid mode holds, and gains energy while the slide stands.
struct AtRest {
  double energy_share, fastest;
};

AtRest case2_at_rest(double xpic_cells) {
  Scene s = reference("case2_elongation_noslip");
  apply_overrides(s, 1.0, 2);
  s.solver.xpic_cells = xpic_cells;
  Simulation sim(s);
  double peak = 0.0, late = 0.0;
  for (int t = 1; t <= 60; ++t) {
    sim.advance_to(t);
    const double e = particle_totals(sim.particles()).kinetic_energy;
    peak = std::max(peak, e);
    if (t >= 30) late = std::max(late, e);
  }
  const Particles& P = sim.particles();
  double fastest = 0.0;
  for (int p = 0; p < P.size(); ++p) fastest = std::max(fastest, std::hypot(P.vx[p], P.vy[p]));
  return {late / peak, fastest};
}

TEST(Convergence, StoppedSlideKeepsNoKineticEnergyWithTheDefaultTransfer) {
  const AtRest filtered = case2_at_rest(SolverSpec{}.xpic_cells);
  const AtRest flip = case2_at_rest(0.0);
  std::printf("case 2 at rest, 30 to 60 s: largest kinetic energy %.2f %% of the peak, fastest "
              "particle %.2f m/s (default); pure FLIP %.2f %%, %.2f m/s\n",
              100.0 * filtered.energy_share, filtered.fastest, 100.0 * flip.energy_share,
              flip.fastest);
  // Measured: 3.2 % and 0.41 m/s with the default, 22 % and 4.8 m/s with
  // pure FLIP (2026-12-02).
  EXPECT_LT(filtered.energy_share, 0.05);
  EXPECT_LT(filtered.fastest, 1.0);
  EXPECT_GT(flip.energy_share, 0.1);  // what the filter is for
}

TEST(Convergence, StretchedBarPartsFarLessWithDeformingDomains) {
  const Simulation deforming = stretched_bar(DomainKind::Deforming);
  const Simulation fixed = stretched_bar(DomainKind::Fixed);
  const double gap = widest_row_gap(deforming), fixed_gap = widest_row_gap(fixed);
  std::printf("stretched bar: %.2f times its length; widest gap between neighbours' domains "
              "%.3f cells (deforming), %.3f cells (fixed)\n",
              length(deforming) / 4.0, gap, fixed_gap);
  EXPECT_GT(length(deforming), 3.0 * 4.0);
  EXPECT_GT(fixed_gap, 0.5);  // uGIMP domains part by over half a cell
  EXPECT_LT(gap, 0.2 * fixed_gap);
}

TEST(Convergence, NonSofteningCasesConvergeWithTheCellSize) {
  for (const char* name : {"case2_elongation_noslip", "case3_block_sliding"}) {
    std::vector<double> r;
    for (double cell : {1.0, 0.5, 0.25}) {
      Scene s = reference(name);
      apply_overrides(s, cell, 2);
      r.push_back(runout_at(s, 10.0));
    }
    const double d1 = std::fabs(r[0] - r[1]), d2 = std::fabs(r[1] - r[2]);
    std::printf("%s at 10 s: runout %.3f, %.3f, %.3f m at 1, 0.5, 0.25 m cells; observed order "
                "%.2f\n",
                name, r[0], r[1], r[2], std::log2(d1 / d2));
    EXPECT_LT(d2, d1) << name;
    if (std::string(name) == "case3_block_sliding") {
      EXPECT_LT(d2, 0.02 * r[2]);
    }
  }
}
