// The memory estimate of a scene (memory_estimate.hpp): its particle count
// against the seeded count (a lattice-point bound), its refusal above the
// available memory and beyond int, and seed_particles and DamSolver
// refusing before they allocate.
#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <string>
#include <vector>

#include "runout/dam/dam.hpp"
#include "runout/run/memory_estimate.hpp"
#include "runout/scene/polygon.hpp"
#include "runout/scene/scene_parser.hpp"
#include "runout/mpm/seeding.hpp"
#include "scene_builders.hpp"

using namespace runout;

namespace {

Scene rectangle(double h, int ppc) {
  return fixtures::block_scene({1.0, 0.0}, {5.0, 2.0}, {0.0, 0.0}, {20.0, 5.0}, h, ppc, 600,
                               1e5, 0.3);
}

// A triangle and a hexagon with slanted edges, off the lattice, so the
// count is not an exact area / spacing^2.
Scene slanted(double h, int ppc) {
  Scene s = rectangle(h, ppc);
  s.bodies[0].polygon = {{1.03, 0.11}, {6.71, 0.4}, {3.3, 3.9}};
  BodySpec hexagon = s.bodies[0];
  hexagon.name = "hexagon";
  hexagon.polygon = {{10.1, 1.0}, {12.2, 0.3}, {14.4, 1.1}, {14.6, 3.3}, {12.3, 4.2}, {10.4, 3.1}};
  s.bodies.push_back(hexagon);
  return s;
}

double perimeter(const Polygon& p) {
  double length = 0;
  for (std::size_t i = 0; i < p.size(); ++i) length += (p[(i + 1) % p.size()] - p[i]).norm();
  return length;
}

std::string refusal(const Scene& s, Method method, std::optional<double> available) {
  try {
    require_memory(s, method, available);
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 0);
    return e.what();
  }
  return "";
}

}  // namespace

// Each lattice point inside a polygon owns a lattice cell of area s^2 that
// lies within s / sqrt(2) of the polygon, so |N - A / s^2| <= P / (sqrt(2) s) + pi / 2
// (A, P: area and perimeter); the estimate's bound must hold the count.
TEST(MemoryEstimate, ParticleCountWithinTheLatticeBoundOfTheSeededCount) {
  for (const double h : {0.5, 0.23, 0.1}) {
    for (const int ppc : {1, 2, 3}) {
      const Scene s = slanted(h, ppc);
      const double spacing = h / ppc;
      double margin = 0;
      for (const BodySpec& b : s.bodies) margin += perimeter(b.polygon) / (std::sqrt(2.0) * spacing) + M_PI / 2;
      const MemoryEstimate e = estimate_memory(s, Method::Mpm);
      const int seeded = seed_particles(s).size();
      EXPECT_NEAR(e.items, seeded, margin) << "h " << h << " ppc " << ppc;
      EXPECT_LE(seeded, e.items_bound) << "h " << h << " ppc " << ppc;
      EXPECT_GE(e.items_bound, e.items);
    }
  }
}

// A lattice-aligned rectangle holds exactly area / s^2 particles.
TEST(MemoryEstimate, AlignedRectangleIsExact) {
  const Scene s = rectangle(0.5, 2);
  const MemoryEstimate e = estimate_memory(s, Method::Mpm);
  EXPECT_DOUBLE_EQ(e.items, seed_particles(s).size());
  EXPECT_DOUBLE_EQ(e.items, 8.0 / (0.25 * 0.25));
  // The domain's nodes: (20 / 0.5 + 1) x (5 / 0.5 + 1).
  EXPECT_DOUBLE_EQ(e.grid_nodes, 41.0 * 11.0);
  EXPECT_DOUBLE_EQ(e.bytes(), e.items * e.item_bytes + e.grid_nodes * e.node_bytes);
}

TEST(MemoryEstimate, RefusedJustAboveTheAvailableMemoryNamingItsKeys) {
  const Scene s = rectangle(0.5, 2);
  const double bytes = estimate_memory(s, Method::Mpm).bytes();
  EXPECT_EQ(refusal(s, Method::Mpm, bytes * 1.01), "");
  EXPECT_EQ(refusal(s, Method::Mpm, std::nullopt), "");
  const std::string message = refusal(s, Method::Mpm, bytes * 0.99);
  const std::vector<std::string> parts = {
      "grid.cell_size", "grid.ppc", "body[0] \"block\"", "MemAvailable",
      "the run needs about " + byte_text(bytes), byte_text(bytes * 0.99) + " available"};
  for (const std::string& part : parts)
    EXPECT_NE(message.find(part), std::string::npos) << part << " in: " << message;
}

TEST(MemoryEstimate, CountsBeyondIntRefusedWhateverTheMemory) {
  Scene particles = rectangle(1e-5, 2);  // 8 m2 at 5 um: 3.2e11 particles
  EXPECT_NE(refusal(particles, Method::Mpm, std::nullopt).find("a run can index"),
            std::string::npos);
  Scene nodes = rectangle(0.5, 2);
  nodes.grid.max = {2e5, 2e5};  // 1.6e11 nodes
  EXPECT_NE(refusal(nodes, Method::Mpm, std::nullopt).find("grid nodes"), std::string::npos);
  Scene elements = rectangle(1e-9, 2);  // 4.5 m of body over 1 nm
  EXPECT_NE(refusal(elements, Method::Dam, std::nullopt).find("dam.elements"), std::string::npos);
}

// Without the refusal these would allocate 3.2e11 seeds and fail with
// bad_alloc (or be killed), not throw a SceneError.
TEST(MemoryEstimate, SeedingAndTheDepthAveragedModelRefuseBeforeAllocating) {
  EXPECT_THROW(seed_particles(rectangle(1e-5, 2)), SceneError);
  Scene dam = rectangle(1e-9, 2);
  dam.base.kind = BaseKind::Planar;
  dam.method = Method::Dam;
  EXPECT_THROW(DamSolver{dam}, SceneError);
}

TEST(MemoryEstimate, DepthAveragedElementsAreTheGivenCount) {
  Scene s = rectangle(0.5, 2);
  s.dam.elements = 40;
  EXPECT_DOUBLE_EQ(estimate_memory(s, Method::Dam).items, 40);
  s.dam.elements = 0;  // the body's diagonal over the cell size: sqrt(4^2 + 2^2) / 0.5
  EXPECT_DOUBLE_EQ(estimate_memory(s, Method::Dam).items, std::ceil(std::sqrt(20.0) / 0.5));
}

TEST(MemoryEstimate, AvailableMemoryIsReadOnLinux) {
  const std::optional<double> available = available_memory();
  ASSERT_TRUE(available.has_value());
  EXPECT_GT(*available, 0);
}

TEST(MemoryEstimate, ByteText) {
  EXPECT_EQ(byte_text(512), "512 B");
  EXPECT_EQ(byte_text(1536), "1.5 KiB");
  EXPECT_EQ(byte_text(3.0 * 1024 * 1024 * 1024), "3 GiB");
}
