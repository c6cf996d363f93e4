#include "runout/mpm/seeding.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "runout/run/memory_estimate.hpp"
#include "runout/scene/polygon.hpp"
#include "runout/scene/scene_parser.hpp"
#include "runout/scene/scene_quantities.hpp"

namespace runout {
namespace {

struct Seed {
  Eigen::Vector2d position;
  int body;
};

// Lattice indices i whose sub-cell centre origin + (i + 0.5) * spacing lies
// in [lo, hi].
struct IndexRange {
  long first, last;
};

IndexRange lattice_span(double origin, double spacing, double lo, double hi) {
  return {static_cast<long>(std::ceil((lo - origin) / spacing - 0.5)),
          static_cast<long>(std::floor((hi - origin) / spacing - 0.5))};
}

void seed_body(const Scene& scene, int body_index, std::vector<Seed>& seeds) {
  const Polygon& outline = scene.bodies[body_index].polygon;
  const Eigen::Vector2d& origin = scene.grid.min;
  const double spacing = particle_spacing(scene);

  Eigen::Vector2d lo = outline.front(), hi = outline.front();
  for (const Eigen::Vector2d& v : outline) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const IndexRange rows = lattice_span(origin.y(), spacing, lo.y(), hi.y());
  const IndexRange cols = lattice_span(origin.x(), spacing, lo.x(), hi.x());
  for (long j = rows.first; j <= rows.last; ++j) {
    for (long i = cols.first; i <= cols.last; ++i) {
      const Eigen::Vector2d centre =
          origin + spacing * Eigen::Vector2d(i + 0.5, j + 0.5);
      if (contains(outline, centre)) seeds.push_back({centre, body_index});
    }
  }
}

// Per body, the body's area over the area of its particles, A / (n v):
// the factor that gives the particles the body's whole mass. The lattice
// fills a body up to the last sub-cell centre inside it, so a layer of
// thickness H is seeded round(H / s) s thick: at 0.6 m cells (s = 0.3 m)
// the 5 m slide of the reference cases became 5.1 m and at 0.8 m 4.8 m,
// +-2 to 4 % of the basal shear stress rho g sin(theta) H of a slide whose
// driving stress exceeds its strength by 2.6 % (case 2), and its runout at
// 12 s jumped from 14.8 m (0.8 m) to 20.5 m (0.6 m). With the mass scaled,
// the seeded layer's weight, and so its basal stresses, are the body's:
// rho A / (n v) over round(H / s) s is rho H (docs/convergence.md,
// "Seeded mass"). The volume stays the particle's domain area, which the
// shape functions integrate over. 1 where the lattice fills the body to
// rounding, so that such scenes are unchanged bit for bit.
std::vector<double> mass_scale(const Scene& scene, const std::vector<Seed>& seeds,
                               double volume) {
  std::vector<double> count(scene.bodies.size(), 0.0), scale(scene.bodies.size(), 1.0);
  for (const Seed& seed : seeds) count[seed.body] += 1.0;
  for (std::size_t b = 0; b < scale.size(); ++b) {
    const double ratio = std::fabs(signed_area(scene.bodies[b].polygon)) / (count[b] * volume);
    if (std::fabs(ratio - 1.0) > 1e-9) scale[b] = ratio;
  }
  return scale;
}

std::string spacing_text(double spacing) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", spacing);
  return buf;
}

}  // namespace

Particles seed_particles(const Scene& scene, const std::optional<MemoryEstimate>& checked) {
  if (!checked) require_memory(scene, Method::Mpm);
  std::vector<Seed> seeds;
  for (int b = 0; b < static_cast<int>(scene.bodies.size()); ++b) {
    const std::size_t before = seeds.size();
    seed_body(scene, b, seeds);
    // A body thinner than the spacing everywhere would silently vanish.
    if (seeds.size() == before)
      throw SceneError("body[" + std::to_string(b) + "] \"" + scene.bodies[b].name +
                           "\": no particle: the body covers no sub-cell centre of the particle "
                           "lattice (spacing grid.cell_size / grid.ppc = " +
                           spacing_text(particle_spacing(scene)) +
                           " m); make it thicker or the spacing finer",
                       0);
  }

  const double spacing = particle_spacing(scene);
  const double volume = spacing * spacing;
  const std::vector<double> scale = mass_scale(scene, seeds, volume);
  Particles particles;
  particles.resize(static_cast<int>(seeds.size()));
  for (int p = 0; p < particles.size(); ++p) {
    const Seed& seed = seeds[p];
    const BodySpec& body = scene.bodies[seed.body];
    particles.x[p] = particles.x0[p] = seed.position.x();
    particles.y[p] = particles.y0[p] = seed.position.y();
    particles.vx[p] = body.velocity.x();
    particles.vy[p] = body.velocity.y();
    particles.vol0[p] = particles.vol[p] = volume;
    particles.mass[p] = scene.materials[body.material].density * volume * scale[seed.body];
    particles.body[p] = seed.body;
    particles.material[p] = body.material;
    particles.id[p] = p;
  }
  return particles;
}

}  // namespace runout
