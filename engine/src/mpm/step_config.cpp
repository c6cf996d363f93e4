// The step configuration a scene gives the driver.
#include <algorithm>
#include <cmath>

#include "runout/mpm/driver.hpp"
#include "runout/scene/materials.hpp"
#include "runout/scene/scene_quantities.hpp"

namespace runout {

StepConfig make_step_config(const Scene& s, const std::vector<MaterialParams>& materials) {
  const double h = s.grid.cell_size;
  StepConfig c;
  c.shape = s.grid.shape;
  c.domain = s.grid.domain;
  c.lp = particle_spacing(s) / 2.0;
  c.gx = s.gravity.vector.x();
  c.gy = s.gravity.vector.y();
  c.gravity_ramp = s.gravity.ramp;
  c.transfer = s.solver.transfer;
  c.flip = s.solver.flip;
  // The PIC share's time scale: pic_cells crossings of a cell by the
  // fastest P-wave, so it shrinks with the cell (the filtered sub-cell
  // velocity then carries less and less) but not with the time step.
  const double c_max = fastest_p_wave(materials).speed;
  c.pic_time = c_max > 0.0 ? s.solver.pic_cells * h / c_max : 0.0;
  double rho_max = 0;
  for (const auto& m : materials) rho_max = std::max(rho_max, m.density);
  c.min_node_mass = s.solver.mass_threshold * rho_max * h * h;
  c.damping = s.solver.damping;
  c.left = s.boundary.left;
  c.right = s.boundary.right;
  c.bottom = s.boundary.bottom;
  c.top = s.boundary.top;
  // The parser snaps max up to a node; the tolerance absorbs the rounding.
  c.domain_nx = static_cast<int>(std::ceil((s.grid.max.x() - s.grid.min.x()) / h - 1e-9));
  c.domain_ny = static_cast<int>(std::ceil((s.grid.max.y() - s.grid.min.y()) / h - 1e-9));
  if (s.boundary.left == BoundaryKind::Periodic) {
    c.period = c.domain_nx * h;
    c.domain_x0 = s.grid.min.x();
  }
  c.interface = s.base.interface;
  c.shear_strength = s.base.shear_strength;
  c.clay_band = s.base.clay_band;
  c.friction = s.base.friction;
  c.xpic_order = s.solver.xpic_order;
  // As pic_time: xpic_cells crossings of a cell by the fastest P-wave; a
  // schedule of FLIP's only. The parser refuses it with another transfer
  // and sets 0 there (so a resolved scene reads back); a scene built in
  // code keeps SolverSpec's default 40 whatever its transfer.
  const bool scheduled = s.solver.transfer == TransferKind::Flip && c_max > 0.0;
  c.xpic_period = scheduled ? s.solver.xpic_cells * h / c_max : 0.0;
  return c;
}

}  // namespace runout
