#pragma once
// The background grid: a box of nodes that follows the particles inside the
// scene's domain. Node (i, j) of the box is global node (i0 + i, j0 + j),
// global node (0, 0) being the domain's min corner. Nodal fields are reset
// every step, so moving the box costs nothing but a resize when it grows.
#include <cmath>
#include <vector>

#include "runout/mpm/host_device.hpp"
#include "runout/scene/kinds.hpp"
#include "runout/mpm/staggered_allocator.hpp"

namespace runout {

struct GridView {
  int nx = 0, ny = 0;       // nodes in the box
  int i0 = 0, j0 = 0;       // global index of the box's node (0, 0)
  double ox = 0, oy = 0;    // position of the box's node (0, 0)
  double h = 0;
  double *m;                // mass
  double *vol;              // volume, sum N V: gives a base node its interface area
  double *px, *py;          // momentum (then, in MUSL, the remapped momentum)
  double *fx, *fy;          // internal + external force
  double *v0x, *v0y;        // velocity at the start of the step, p/m
  double *vx, *vy;          // velocity at the end of the step, constrained
  double *dvx, *dvy;        // its change in the grid update, v - v0, which FLIP carries
  double *vmx, *vmy;        // mid-step velocity (v0 + v)/2, constrained
  double *fbase;            // base's tangential force on the slide at the node, along +s
  double *gap;              // min over the node's particles of their gap to the base
  double *stuck;            // 1 where Geo-contact held the node's material still, else 0
  double *qx, *qy;          // XPIC: the current term (B S+ S)^(k-1) v0
  double *xvx, *xvy;        // XPIC: the filtered start velocity V*
  // The clay's band along the base (StepConfig::clay_band): sum N V su of
  // the particles near the base, and a base node's slip in the step.
  double *band_su, *band_slip;

  RUNOUT_HD int index(int i, int j) const { return j * nx + i; }
  RUNOUT_HD int size() const { return nx * ny; }
};

// Places g's box over the nodes that particles spanning [xmin, xmax] x
// [ymin, ymax] touch, on the lattice of spacing h through the domain corner
// (domain_x, domain_y): a particle in cell c touches nodes c-1..c+2 (GIMP),
// so one ghost node below the span and two above; along x, the rows of the
// stencil (kStencilNodes) reach c+3 with a zero weight, so one more column.
// Sets the sizes and the origin only; the CPU and the CUDA drivers both fit
// their grids with it.
inline void place_box(GridView& g, double xmin, double xmax, double ymin, double ymax,
                      double domain_x, double domain_y, double h) {
  const auto cell = [h](double v, double origin) {
    return static_cast<int>(std::floor((v - origin) / h));
  };
  g.i0 = cell(xmin, domain_x) - 1;
  g.j0 = cell(ymin, domain_y) - 1;
  g.nx = cell(xmax, domain_x) + 3 - g.i0 + 1;
  g.ny = cell(ymax, domain_y) + 2 - g.j0 + 1;
  g.h = h;
  g.ox = domain_x + g.i0 * h;
  g.oy = domain_y + g.j0 * h;
}

// Empties node n for the next p2g: what p2g adds into (mass, volume,
// momentum, force, the band's strength) and the base's force zero, the
// gap +infinity (no particle).
RUNOUT_HD inline void clear_node(const GridView& g, int n) {
  g.m[n] = g.vol[n] = g.px[n] = g.py[n] = g.fx[n] = g.fy[n] = g.fbase[n] = g.band_su[n] = 0.0;
  g.gap[n] = INFINITY;
}

class Grid {
 public:
  // Takes the box of `placed` (place_box); the caller clears what p2g
  // adds into (clear_node). Storage only ever grows.
  const GridView& fit(const GridView& placed);
  GridView view() { return view_; }
  const GridView& view() const { return view_; }
  std::size_t capacity() const { return m_.size(); }

 private:
  GridView view_;
  // Staggered in their pages (staggered_allocator.hpp): p2g adds rows of
  // m, px, py, fx and fy at the same nodes, one after another.
  StaggeredArray m_, vol_, px_, py_, fx_, fy_, v0x_, v0y_, vx_, vy_, dvx_, dvy_, vmx_, vmy_,
      fbase_, gap_, stuck_, qx_, qy_, xvx_, xvy_, band_su_, band_slip_;
};

}  // namespace runout
