#pragma once
// What the driver (driver.hpp) and its backends hand each other: views of
// per-particle arrays and the results of reductions, in the backend's
// memory (host or device).
#include <cmath>

#include "runout/host_device.hpp"
#include "runout/stages.hpp"

namespace runout {

struct GradientView {  // L per particle, structure of arrays
  double *xx, *xy, *yx, *yy;
  RUNOUT_HD VelocityGradient load(int p) const { return {xx[p], xy[p], yx[p], yy[p]}; }
  RUNOUT_HD void store(int p, const VelocityGradient& l) const {
    xx[p] = l.xx;
    xy[p] = l.xy;
    yx[p] = l.yx;
    yy[p] = l.yy;
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
