// A vertical cut in undrained Tresca clay stands below its critical height
// and collapses above it. The critical height of an unsupported vertical cut
// is Hc = 3.83 su / (rho g) (the upper-bound value, e.g. Chen 1975; the
// lower bound is 2.83 su / (rho g)), so H = 0.7 Hc (below the lower bound)
// must stand and H = 1.4 Hc must collapse. Plane strain, nu = 0.49 and
// E = 100 su as in the reference scenes, 10 cells over the height (enough
// with the volumetric smoothing: the crest moves 0.24 H at 10 and at 16
// cells, as with nu = 0; without it, 10 cells lock and it moves half as
// far). Gravity is applied at once: the standing cut yields locally at its
// toe under the dynamic overshoot (xi about 0.25) but stands; the tall one
// slumps by about a quarter of its height with plastic strains of 400 %.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "runout/measure/diagnostics.hpp"
#include "runout/mpm/simulation.hpp"
#include "scene_builders.hpp"

using namespace runout;

namespace {

constexpr double kSu = 10e3, kRho = 1000.0, kG = 9.81;
const double kHc = 3.83 * kSu / (kRho * kG);

struct CutResult {
  double crest;   // horizontal displacement of the crest, in cut heights
  double max_xi;  // largest plastic shear strain
};

CutResult run_cut(double height, double seconds) {
  const double h = height / 10.0, width = 3.0 * height;
  Scene s = fixtures::block_scene({0.0, 0.0}, {width, height}, {0.0, 0.0},
                                  {3.0 * width, 2.0 * height}, h, 2, kRho, 100.0 * kSu, 0.49);
  s.materials[0].model = MaterialModel::Tresca;
  s.materials[0].su0 = kSu;
  s.boundary = {BoundaryKind::Slip, BoundaryKind::Free, BoundaryKind::Fixed, BoundaryKind::Free};
  s.gravity.vector = {0.0, -kG};
  Simulation sim(s);
  const Particles& P = sim.particles();
  int crest = 0;
  for (int p = 1; p < P.size(); ++p)
    if (P.x[p] + P.y[p] > P.x[crest] + P.y[crest]) crest = p;
  const std::int64_t crest_id = P.id[crest];  // the engine reorders particles in memory
  sim.advance_to(seconds);
  double max_xi = 0, crest_dx = 0;
  for (int p = 0; p < P.size(); ++p) {
    max_xi = std::max(max_xi, P.xi[p]);
    if (P.id[p] == crest_id) crest_dx = P.x[p] - P.x0[p];
  }
  return {crest_dx / height, max_xi};
}

}  // namespace

TEST(VerticalCut, StandsBelowAndCollapsesAboveTheCriticalHeight) {
  const CutResult stands = run_cut(0.7 * kHc, 3.0);
  const CutResult collapses = run_cut(1.4 * kHc, 3.0);
  std::printf("vertical cut: crest moves %.3g H (max xi %.3g) at 0.7 Hc, %.3g H (max xi %.3g) "
              "at 1.4 Hc\n", stands.crest, stands.max_xi, collapses.crest, collapses.max_xi);
  EXPECT_LT(stands.crest, 0.04);     // elastic settlement and local yield only
  EXPECT_LT(stands.max_xi, 0.5);
  EXPECT_GT(collapses.crest, 0.15);  // the face has failed
  EXPECT_GT(collapses.max_xi, 1.0);
}
