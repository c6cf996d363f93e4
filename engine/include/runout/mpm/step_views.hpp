#pragma once
// What the driver (driver.hpp) and its backends hand each other: views of
// per-particle arrays and the results of reductions, in the backend's
// memory (host or device).
#include <cmath>

#include "runout/mpm/host_device.hpp"
#include "runout/mpm/stages.hpp"

namespace runout {

// L of particle p at index p - first of each array, structure of arrays
// (first as in StepScratch).
struct GradientView {
  double *xx, *xy, *yx, *yy;
  int first = 0;
  RUNOUT_HD int at(int p) const { return p - first; }
  RUNOUT_HD VelocityGradient load(int p) const {
    const int i = at(p);
    return {xx[i], xy[i], yx[i], yy[i]};
  }
  RUNOUT_HD void store(int p, const VelocityGradient& l) const {
    const int i = at(p);
    xx[i] = l.xx;
    xy[i] = l.xy;
    yx[i] = l.yx;
    yy[i] = l.yy;
  }
};
struct CellMeanView {  // the mean of the cell particle p is in (mean null: none)
  const double* mean;
  const int* cell;
  RUNOUT_HD double operator()(int p) const { return mean[cell[p]]; }
};
struct SpeedMax {
  double max = 0;  // the largest signal speed
  int bad = 0;     // particles at fault (a negative or non-finite speed)
  void take(double speed) {  // the host backends
    if (speed >= 0.0 && std::isfinite(speed))
      max = max < speed ? speed : max;
    else
      ++bad;
  }
};
struct ParticleBox {
  double xmin, xmax, ymin, ymax;
  int non_finite;
};

}  // namespace runout
