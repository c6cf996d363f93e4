// A fixed-free elastic bar released in its first mode, v(x) = v0 sin(pi x
// / 2L): it vibrates with period 4 L / c, c = sqrt(E / rho) (nu = 0, so
// plane strain is the 1D bar). The period is read from the zero crossings
// of the bar's momentum over two periods.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "runout/measure/diagnostics.hpp"
#include "runout/mpm/simulation.hpp"
#include "scene_builders.hpp"

using namespace runout;

TEST(VibratingBar, FirstModePeriodIsFourLOverC) {
  const double L = 25.0, E = 100.0, rho = 1.0, h = 0.5, v0 = 0.01;
  Scene s = fixtures::block_scene({0.0, 0.0}, {L, h}, {0.0, 0.0}, {2.0 * L, h}, h, 2, rho, E,
                                 0.0);
  s.boundary = {BoundaryKind::Fixed, BoundaryKind::Free, BoundaryKind::Slip, BoundaryKind::Slip};
  s.solver.pic_cells = 0.0;  // pure FLIP (the default)
  Simulation sim(s);
  Particles& P = sim.particles();
  for (int p = 0; p < P.size(); ++p) P.vx[p] = v0 * std::sin(M_PI * P.x[p] / (2.0 * L));

  const double c = std::sqrt(E / rho), period = 4.0 * L / c;
  std::vector<double> crossings;
  double t_prev = 0, m_prev = particle_totals(P).momentum_x;
  while (sim.time() < 2.2 * period) {
    sim.step(sim.stable_dt());
    const double m = particle_totals(P).momentum_x;
    if ((m_prev > 0) != (m > 0))
      crossings.push_back(t_prev + (sim.time() - t_prev) * m_prev / (m_prev - m));
    t_prev = sim.time();
    m_prev = m;
  }
  ASSERT_GE(crossings.size(), 4u);
  // Crossings are half a period apart; the first is a quarter period in.
  const double measured = (crossings[3] - crossings[0]) / 1.5;
  std::printf("bar: period %.6g s, 4L/c = %.6g s\n", measured, period);
  EXPECT_NEAR(measured, period, 0.02 * period);
}
