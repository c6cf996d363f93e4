// Where methods fail, tested (issue "speed against accuracy, stability"):
// - standard linear MPM rings with cell-crossing noise where particles
//   cross cells (a soft column settling by a cell or two) and GIMP does not:
//   its stress error is several times larger (measured: 0.35 against 0.04
//   of rho g H);
// - a time step far above the CFL limit blows up, and the step that does
//   so is caught and reported within a few steps (measured: 2 at 20 x the
//   limit), before any state with a non-finite value can be written.
#include <gtest/gtest.h>

#include <cmath>

#include "runout/simulation.hpp"
#include "scene_builders.hpp"

using namespace runout;

namespace {

constexpr double kRho = 1000.0, kG = 10.0, kH = 2.0;

// A soft column (E such that the base strains about 20 %) settling under
// its own weight, slip sides, fixed base, local damping: its particles cross
// one or two cells on the way down. The weight above a material point does
// not depend on how the column deforms, so sigma_yy = -rho g (H - Y), Y the
// initial height, whatever the strain. Returns the largest particle error /
// (rho g H) over 0.2 H <= Y <= 0.8 H once settled.
double soft_column_stress_error(ShapeKind shape) {
  const double height = 10.0;
  Scene s = fixtures::column_scene(height, 0.5, kRho, 3.7e5, kG);
  s.grid.shape = shape;
  Simulation sim(s);
  sim.advance_to(20.0);
  const Particles& P = sim.particles();
  double worst = 0;
  for (int p = 0; p < P.size(); ++p) {
    if (P.y0[p] < 0.2 * height || P.y0[p] > 0.8 * height) continue;
    const double exact = -kRho * kG * (height - P.y0[p]);
    worst = std::max(worst, std::fabs(P.syy[p] - exact) / (kRho * kG * height));
  }
  return worst;
}

}  // namespace

TEST(Stability, LinearMpmCellCrossingNoiseIsSeveralTimesGimps) {
  const double gimp = soft_column_stress_error(ShapeKind::Gimp);
  const double linear = soft_column_stress_error(ShapeKind::Linear);
  std::printf("soft column, largest stress error / (rho g H): GIMP %.3g, linear %.3g\n", gimp,
              linear);
  EXPECT_GT(linear, 3.0 * gimp);
}

TEST(Stability, AStepFarAboveTheCflLimitIsCaughtWithinAFewSteps) {
  Scene s = fixtures::block_scene({1.0, 0.0}, {5.0, kH}, {0.0, 0.0}, {20.0, 6.0}, 0.25, 2, kRho,
                                  1e7, 0.3);
  s.boundary = {BoundaryKind::Free, BoundaryKind::Free, BoundaryKind::Fixed, BoundaryKind::Free};
  s.gravity.vector = {0.0, -kG};
  Simulation sim(s);
  const double dt = 20.0 * sim.stable_dt();
  int steps = 0;
  try {
    for (; steps < 50; ++steps) sim.step(dt);
    FAIL() << "50 steps at 20 x the CFL limit did not blow up";
  } catch (const NumericalFailure& e) {
    std::printf("caught after %d steps: %s\n", steps, e.what());
    EXPECT_LT(steps, 10);
    const std::string what = e.what();
    EXPECT_TRUE(what.find("blow-up") != std::string::npos ||
                what.find("left the grid domain") != std::string::npos)
        << what;
  }
}
