#include "runout/mpm/guards.hpp"

#include <algorithm>
#include <sstream>

#include "runout/scene/scene_quantities.hpp"

namespace runout {

GuardLimits guard_limits(const Scene& scene, const std::vector<MaterialParams>& materials,
                         const Particles& particles) {
  const double h = scene.grid.cell_size;
  GuardLimits g;
  g.xmin = scene.grid.min.x() - h;
  g.ymin = scene.grid.min.y() - h;
  g.xmax = scene.grid.max.x() + h;
  g.ymax = scene.grid.max.y() + h;
  const double diagonal = (scene.grid.max - scene.grid.min).norm();
  const double free_fall = std::sqrt(2.0 * scene.gravity.vector.norm() * diagonal);
  double wave = 0.0;
  for (const MaterialParams& m : materials)
    if (m.density > 0.0) wave = std::max(wave, p_wave_speed(m));
  double start = 0.0;
  for (int p = 0; p < particles.size(); ++p)
    start = std::max(start, std::hypot(particles.vx[p], particles.vy[p]));
  g.max_speed = 2.0 * (free_fall + wave + start);
  g.min_j = kMinVolumeRatio;
  g.max_j = kMaxVolumeRatio;
  return g;
}

namespace {

const char* fault_title(Fault f) {
  switch (f) {
    case Fault::NonFinite: return "numerical blow-up";
    case Fault::Outside: return "particles left the grid domain";
    case Fault::Runaway: return "runaway velocity";
    case Fault::Volume: return "inverted or collapsed volume";
    case Fault::None: break;
  }
  return "no fault";
}

void describe_fault(std::ostream& out, Fault f, const ParticleView& P, int p,
                    const GuardLimits& g) {
  switch (f) {
    case Fault::NonFinite:
      out << "a non-finite stress, volume, velocity or position";
      break;
    case Fault::Outside:
      out << "more than a cell outside the grid domain (x " << g.xmin << ".." << g.xmax << ", y "
          << g.ymin << ".." << g.ymax
          << " with the cell); enlarge [grid] min/max if the slide really goes there";
      break;
    case Fault::Runaway:
      out << "speed " << std::hypot(P.vx[p], P.vy[p]) << " m/s, above the bound " << g.max_speed
          << " m/s (twice free fall over the domain plus the P-wave speed and the start speed)";
      break;
    case Fault::Volume:
      out << "volume ratio J = vol / vol0 = " << P.vol[p] / P.vol0[p] << " outside [" << g.min_j
          << ", " << g.max_j << "]";
      break;
    case Fault::None:
      break;
  }
}

}  // namespace

std::string describe_faults(const Particles& particles, const GuardLimits& limits, long step,
                            double time, double dt) {
  // view() hands out mutable pointers; nothing here writes through them.
  const ParticleView P = const_cast<Particles&>(particles).view();
  int count = 0, worst = -1;
  Fault fault = Fault::None;
  for (int p = 0; p < P.n; ++p) {
    const Fault f = particle_fault(P, p, limits);
    if (f == Fault::None) continue;
    ++count;
    // The gravest kind first (the enum's order), then the lowest id.
    if (worst < 0 || f < fault || (f == fault && P.id[p] < P.id[worst])) {
      worst = p;
      fault = f;
    }
  }
  std::ostringstream msg;
  msg.precision(10);
  if (worst < 0) {
    msg << "numerical failure at step " << step << " (t = " << time
        << " s) that no particle check pins down";
    return msg.str();
  }
  msg << fault_title(fault) << " at step " << step << " (t = " << time << " s, dt = " << dt
      << " s): particle id " << P.id[worst] << " at (" << P.x[worst] << ", " << P.y[worst]
      << ") has ";
  describe_fault(msg, fault, P, worst, limits);
  msg << "; " << count << " particle(s) at fault in all";
  return msg.str();
}

}  // namespace runout
