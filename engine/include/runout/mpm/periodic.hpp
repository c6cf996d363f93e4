#pragma once
// The periodic seam along x: the ghost columns' exchange after each grid
// stage and the particles' wrap.
#include <cmath>

#include "runout/mpm/grid.hpp"
#include "runout/mpm/host_device.hpp"
#include "runout/mpm/particles.hpp"
#include "runout/mpm/step_config.hpp"

namespace runout {

// Periodic along x, as halo exchange in a domain-decomposed MPM (ExaMPM,
// Cabana's periodic halos): the box spans the period and one ghost column
// below it and two above (global columns -1, N and N+1 of N cells), and
// the spare column of the stencil rows (N+2, never written but by zeros), where
// the stencils of particles near the seam reach. After a scatter each
// ghost's sums are added into the column it repeats (N - 1, 0 and 1) and
// copied back, so the nodes on both sides of the seam hold the same sums;
// after a node stage the results are copied out again, so that every
// stage downstream reads one value per physical node. The scatter itself
// is unchanged (the CPU's colouring and the GPU's atomics never wrap).
// periodic_span gives place_box the span of such a box; the rest are
// called for each node row j.
inline void periodic_span(const StepConfig& c, double h, double& xmin, double& xmax) {
  xmin = c.domain_x0;
  xmax = c.domain_x0 + c.period - 0.5 * h;  // in the last cell: box columns -1 .. N + 2
}

// The box columns of the ghosts, and of the columns they repeat.
struct PeriodicColumns {
  int ghost[3], image[3];
};

RUNOUT_HD inline PeriodicColumns periodic_columns(const GridView& g) {
  const int n = g.nx - 4;  // cells in the period; box column k is global k - 1
  return {{0, n + 1, n + 2}, {n, 1, 2}};
}

// After a node stage: the ghosts take their columns' values.
RUNOUT_HD inline void copy_periodic(const GridView& g, int j, double* a) {
  const PeriodicColumns k = periodic_columns(g);
  for (int q = 0; q < 3; ++q) a[g.index(k.ghost[q], j)] = a[g.index(k.image[q], j)];
}

// After a scatter: the row's ghost sums into their columns, and back.
// lower: the array is a minimum (the gap), not a sum.
RUNOUT_HD inline void fold_periodic(const GridView& g, int j, double* a, bool lower = false) {
  const PeriodicColumns k = periodic_columns(g);
  for (int q = 0; q < 3; ++q) {
    double& into = a[g.index(k.image[q], j)];
    const double ghost = a[g.index(k.ghost[q], j)];
    into = lower ? std::fmin(into, ghost) : into + ghost;
  }
  copy_periodic(g, j, a);
}

// The periodic exchange after each grid stage, per node row. The base
// force of a ghost is zeroed after the copy, so that its sum counts each
// node once.
enum class Exchange { AfterP2g, AfterGridUpdate, AfterMomentum, AfterXpicTerm, AfterRemap };

RUNOUT_HD inline void exchange_periodic(const GridView& g, int j, Exchange after) {
  switch (after) {
    case Exchange::AfterP2g: {
      double* const sums[] = {g.m, g.vol, g.px, g.py, g.fx, g.fy, g.band_su};
      for (double* a : sums) fold_periodic(g, j, a);
      fold_periodic(g, j, g.gap, true);
      break;
    }
    case Exchange::AfterGridUpdate: {
      double* const results[] = {g.v0x, g.v0y, g.vx, g.vy, g.dvx, g.dvy, g.stuck, g.band_slip};
      for (double* a : results) copy_periodic(g, j, a);
      const PeriodicColumns k = periodic_columns(g);
      for (int q = 0; q < 3; ++q) g.fbase[g.index(k.ghost[q], j)] = 0.0;
      break;
    }
    case Exchange::AfterMomentum:
      fold_periodic(g, j, g.px);
      fold_periodic(g, j, g.py);
      break;
    case Exchange::AfterXpicTerm: {
      double* const results[] = {g.qx, g.qy, g.xvx, g.xvy};
      for (double* a : results) copy_periodic(g, j, a);
      break;
    }
    case Exchange::AfterRemap: {
      double* const results[] = {g.vx, g.vy, g.vmx, g.vmy};
      for (double* a : results) copy_periodic(g, j, a);
      break;
    }
  }
}

// A particle that has left the period re-enters on the other side. Its
// initial position moves with it, so its displacement x - x0 stays the
// distance it travelled.
RUNOUT_HD inline void wrap_periodic(const ParticleView& P, int p, const StepConfig& c) {
  if (!(c.period > 0.0)) return;
  const double shift = c.period * std::floor((P.x[p] - c.domain_x0) / c.period);
  P.x[p] -= shift;
  P.x0[p] -= shift;
}

}  // namespace runout
