#pragma once
// The nonlocal average (nonlocal.hpp) the way a device backend takes it:
// element by element with the stages of nonlocal_lattice.hpp, one launch
// each, the particles spread in any order. The CUDA backend runs it on the
// GPU and the serial device backend on the CPU, so the GPU's path is
// tested on every machine (tests/test_device_backends.cpp).
//
// The backend B provides for_each(count, stage) and
//   NonlocalLatticeArrays lattice_arrays(int nodes): three arrays of at
//     least `nodes` doubles, increments and volumes zeroed;
//   NonlocalTaps lattice_taps(const NonlocalAverage&, int m): material m's
//     taps (NonlocalAverage::taps) where its stages can read them.
// out must hold in already: only the regularised materials' particles are
// overwritten.
#include <vector>

#include "runout/mpm/nonlocal.hpp"
#include "runout/mpm/particles.hpp"
#include "runout/mpm/step_views.hpp"

namespace runout {

struct NonlocalLatticeArrays {
  double *increments, *volumes, *pass;
};

struct NonlocalTaps {
  const double *x, *y;
};

// The lattice's arrays and taps for a backend that averages by elements on
// the CPU.
class HostNonlocalLattice {
 public:
  NonlocalLatticeArrays lattice_arrays(int nodes) {
    increments_.assign(nodes, 0.0);
    volumes_.assign(nodes, 0.0);
    pass_.resize(nodes);
    return {increments_.data(), volumes_.data(), pass_.data()};
  }
  NonlocalTaps lattice_taps(const NonlocalAverage& nonlocal, int m) const {
    return {nonlocal.taps(m).x.data(), nonlocal.taps(m).y.data()};
  }

 private:
  std::vector<double> increments_, volumes_, pass_;
};

// box: of every particle (a superset of each material's); mirror: the
// no-slip base where the stages can read it; add: the backend's scatter add.
template <class B, class Add>
void average_by_elements(B& b, const NonlocalAverage& avg, const ParticleView& P,
                         const ParticleBox& box, const BaseView& mirror, const double* in,
                         double* out, Add add) {
  for (int m = 0; m < avg.materials(); ++m) {
    const Regularisation& reg = avg.regularisation(m);
    if (reg.length <= 0.0) continue;
    // An image lies at most twice its reach from its particle.
    const double reach = avg.image_reach(m);
    const double pad = mirror.kind != BaseKind::None ? 2.0 * reach : 0.0;
    NonlocalLattice g =
        avg.lattice(m, box.xmin - pad, box.xmax + pad, box.ymin - pad, box.ymax + pad);
    const NonlocalTaps taps = b.lattice_taps(avg, m);
    g.ax.taps = taps.x;
    g.ay.taps = taps.y;
    const int nodes = g.size();
    const NonlocalLatticeArrays a = b.lattice_arrays(nodes);
    b.for_each(P.n, SpreadToLattice<Add>{g, a.increments, a.volumes, P.x, P.y, P.vol, P.material,
                                         in, m, mirror, reach, add});
    for (double* field : {a.increments, a.volumes}) {
      b.for_each(nodes, ConvolveAlongX{field, a.pass, g.ax});
      b.for_each(nodes, ConvolveAlongY{a.pass, field, g.ay, g.ax.count});
    }
    b.for_each(P.n, GatherBand{g, a.increments, a.volumes, P.x, P.y, P.material, in, out, m,
                               avg.band_scale(m), reg.band_thickness, reg.length});
  }
}

}  // namespace runout
