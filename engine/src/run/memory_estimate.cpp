#include "runout/run/memory_estimate.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <filesystem>
#include <sstream>

#include <sys/statvfs.h>

#include <toml++/toml.h>

#include "runout/scene/materials.hpp"
#include "runout/scene/polygon.hpp"
#include "runout/scene/scene_parser.hpp"
#include "runout/scene/scene_quantities.hpp"
#include "runout/mpm/stages.hpp"

namespace runout {
namespace {

// A frame is built in one string before it is written (vtu_writer.cpp,
// dam_output.cpp): base64 makes 4 bytes of 3, and while the string grows
// its old and new buffers coexist, so up to twice its final size. Counted
// uncompressed, the worst case of the zlib option.
constexpr double kFrameBytesPerRawByte = 2.0 * 4.0 / 3.0;

// Per particle (particles.hpp, simulation.hpp, vtu_writer.cpp):
//   state: kParticleDoubles doubles, body and material ints, a 64-bit id;
//   step scratch: dx, dy, the stencil and velocity gradient, and the
//   order, block, cell and next ints of the block sort;
//   a frame being written: 28 doubles (29 with band_shear_strain, under
//   the clay's basal band), 3 int64 (id, connectivity, offset), 2 int32
//   and a uint8 cell type.
constexpr double kParticleState = kParticleDoubles * sizeof(double) + 2 * sizeof(int) + sizeof(std::int64_t);
constexpr double kParticleScratch =
    2 * sizeof(double) + sizeof(Stencil2D) + sizeof(VelocityGradient) + 4 * sizeof(int);
constexpr double kParticleFrame = 28 * 8 + 3 * 8 + 2 * 4 + 1;
double particle_frame(const Scene& scene) { return kParticleFrame + (scene.base.clay_band ? 8 : 0); }

// Per grid node (grid.hpp): 23 nodal doubles, and the cell volume and
// mean of the volumetric smoothing (one cell per node, near enough).
constexpr double kNodeBytes = 25 * sizeof(double);

// Per depth-averaged element (dam.hpp, dam_output.cpp): s, v and the
// lumped mass of its node, volume, xi, gamma_dot, tau, two slope
// components and the driving force of a step; a frame carries 11 doubles
// and a 64-bit connectivity entry.
constexpr double kElementState = 10 * sizeof(double);
constexpr double kElementFrame = 11 * 8 + 8;

double perimeter(const Polygon& polygon) {
  double length = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i)
    length += (polygon[(i + 1) % polygon.size()] - polygon[i]).norm();
  return length;
}

double span(const GridSpec& grid, int axis) {
  return std::round((grid.max[axis] - grid.min[axis]) / grid.cell_size) + 1;
}

// Lattice points of spacing s inside a simple polygon: its area / s^2 on
// average; at most the area of the polygon grown by the circumradius
// r = s / sqrt(2) of a lattice cell, A + P r + pi r^2 (Steiner's formula
// bounds it for any simple polygon), over s^2.
void count_particles(const Scene& scene, MemoryEstimate& e) {
  const double s = particle_spacing(scene);
  for (const BodySpec& body : scene.bodies) {
    const double area = std::abs(signed_area(body.polygon));
    e.items += area / (s * s);
    e.items_bound += area / (s * s) + perimeter(body.polygon) / (s * std::sqrt(2.0)) + 2.0;
  }
  e.item_bytes = kParticleState + kParticleScratch + particle_frame(scene) * kFrameBytesPerRawByte;
  e.grid_nodes = span(scene.grid, 0) * span(scene.grid, 1);
  e.node_bytes = kNodeBytes;
}

// dam.elements, or (0) the first body's length along the base over the
// cell size, here its bounding-box diagonal, which that length cannot
// exceed on a planar base and hardly on a polyline one.
void count_elements(const Scene& scene, MemoryEstimate& e) {
  double elements = scene.dam.elements;
  if (elements == 0 && !scene.bodies.empty()) {
    const Polygon& p = scene.bodies.front().polygon;
    Eigen::Vector2d lo = p.front(), hi = p.front();
    for (const Eigen::Vector2d& v : p) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
    elements = std::max(2.0, std::ceil((hi - lo).norm() / scene.grid.cell_size));
  }
  e.items = e.items_bound = elements;
  e.item_bytes = kElementState + kElementFrame * kFrameBytesPerRawByte;
}

std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

// What the particle count comes from, for messages: the spacing and the
// largest body.
std::string particle_drivers(const Scene& scene) {
  const double s = particle_spacing(scene);
  std::size_t largest = 0;
  for (std::size_t b = 1; b < scene.bodies.size(); ++b)
    if (std::abs(signed_area(scene.bodies[b].polygon)) >
        std::abs(signed_area(scene.bodies[largest].polygon)))
      largest = b;
  std::string text = "particle spacing grid.cell_size / grid.ppc = " + number_text(s) + " m";
  if (!scene.bodies.empty())
    text += ", largest body body[" + std::to_string(largest) + "] \"" + scene.bodies[largest].name +
            "\" of " + number_text(std::abs(signed_area(scene.bodies[largest].polygon))) + " m2";
  return text;
}

[[noreturn]] void refuse(const std::string& what) { throw SceneError(what, 0); }

void require_int_counts(const Scene& scene, Method method, const MemoryEstimate& e) {
  if (method == Method::Dam) {
    if (e.items_bound > INT_MAX)
      refuse("dam.elements: about " + number_text(e.items_bound) +
             " elements (at most the body's length / grid.cell_size when dam.elements is 0), "
             "more than the " + std::to_string(INT_MAX) +
             " a run can index: raise grid.cell_size or set dam.elements");
    return;
  }
  if (e.items_bound > INT_MAX)
    refuse("grid.cell_size: up to " + number_text(e.items_bound) + " particles (" +
           particle_drivers(scene) + "), more than the " + std::to_string(INT_MAX) +
           " a run can index: raise grid.cell_size, lower grid.ppc or make the bodies smaller");
  if (e.grid_nodes > INT_MAX)
    refuse("grid.cell_size: " + number_text(e.grid_nodes) +
           " grid nodes over the domain grid.min to grid.max, more than the " +
           std::to_string(INT_MAX) + " a run can index: raise grid.cell_size or shrink the domain");
}

}  // namespace

MemoryEstimate estimate_memory(const Scene& scene, Method method) {
  MemoryEstimate e;
  if (method == Method::Dam)
    count_elements(scene, e);
  else
    count_particles(scene, e);
  return e;
}

std::optional<double> available_memory() {
  std::ifstream meminfo("/proc/meminfo");
  std::string line;
  while (std::getline(meminfo, line)) {
    std::istringstream fields(line);
    std::string key, unit;
    double kib = 0;
    if (fields >> key >> kib >> unit && key == "MemAvailable:" && unit == "kB") return kib * 1024;
  }
  return std::nullopt;
}

void require_memory(const Scene& scene, Method method, const MemoryEstimate& e,
                    std::optional<double> available_bytes) {
  require_int_counts(scene, method, e);
  if (!available_bytes || e.bytes() <= *available_bytes) return;
  const std::string need = "the run needs about " + byte_text(e.bytes()) +
                           " of memory, more than the " + byte_text(*available_bytes) +
                           " available (MemAvailable in /proc/meminfo): ";
  if (method == Method::Dam)
    refuse("dam.elements: " + need + number_text(e.items) + " elements of " +
           byte_text(e.item_bytes) +
           " (dam.elements, or at most the body's length / grid.cell_size); "
           "raise grid.cell_size or lower dam.elements");
  refuse("grid.cell_size: " + need + number_text(e.items) + " particles of " +
         byte_text(e.item_bytes) + " (" + particle_drivers(scene) + ") and " +
         number_text(e.grid_nodes) + " grid nodes of " + byte_text(e.node_bytes) +
         " (the domain grid.min to grid.max); raise grid.cell_size, lower grid.ppc or make the "
         "bodies smaller");
}

void require_memory(const Scene& scene, Method method, std::optional<double> available_bytes) {
  require_memory(scene, method, estimate_memory(scene, method), available_bytes);
}

void require_memory(const Scene& scene, Method method) {
  require_memory(scene, method, available_memory());
}

std::string byte_text(double bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  while (bytes >= 1024 && u < 6) {
    bytes /= 1024;
    ++u;
  }
  return number_text(bytes) + " " + units[u];
}

}  // namespace runout

namespace runout {
namespace {

// A profile row per cell of the domain's width.
constexpr double kProfileRowBytes = 6 * 24;

}  // namespace

RunCost estimate_cost(const Scene& scene, const MemoryEstimate& memory) {
  RunCost c;
  const FastestWave fastest = fastest_p_wave(make_materials(scene));
  const double c_max = fastest.speed;
  if (fastest.material >= 0) c.stiffest = scene.materials[fastest.material].name;
  c.initial_dt = c_max > 0 ? scene.time.courant * scene.grid.cell_size / c_max : 0;
  c.steps = c.initial_dt > 0 ? scene.time.end / c.initial_dt : 0;
  c.frames = std::floor(scene.time.end / scene.time.output_interval) + 1;
  const double items = memory.items;
  const double bins = (scene.grid.max.x() - scene.grid.min.x()) / scene.grid.cell_size;
  // A frame's bytes per particle as written uncompressed: raw, in base64.
  c.output_bytes = c.frames * (items * particle_frame(scene) * 4.0 / 3.0 + bins * kProfileRowBytes);
  return c;
}

namespace {

// "name:line: key" where the scene gives key (table.key) and no override
// replaced it, else "key".
std::string located(const std::string& key, const Scene& scene, const SceneSource& source,
                    int& line) {
  line = 0;
  for (const std::string& o : scene.overrides)
    if (o.rfind(key + " =", 0) == 0) return key;
  if (source.text.empty()) return key;
  try {
    const toml::table root = toml::parse(source.text, source.name);
    if (const toml::node* node = root.at_path(key).node())
      line = static_cast<int>(node->source().begin.line);
  } catch (const toml::parse_error&) {
  }
  return line > 0 ? source.name + ":" + std::to_string(line) + ": " + key : key;
}

}  // namespace

MemoryEstimate require_memory(const Scene& scene, Method method, const SceneSource& source) {
  const MemoryEstimate estimate = estimate_memory(scene, method);
  try {
    require_memory(scene, method, estimate, available_memory());
  } catch (const SceneError& e) {
    // The refusals name their key first: "grid.cell_size: ...".
    const std::string what = e.what();
    const std::size_t colon = what.find(": ");
    if (e.line() != 0 || colon == std::string::npos) throw;
    int line = 0;
    const std::string key = located(what.substr(0, colon), scene, source, line);
    throw SceneError(key + what.substr(colon), line);
  }
  return estimate;
}

void require_cost(const Scene& scene, Method method, const MemoryEstimate& memory,
                  const CostLimits& limits, const SceneSource& source) {
  const RunCost c = estimate_cost(scene, memory);
  int line = 0;
  // The depth-averaged model steps with its own, much longer, time step.
  if (method != Method::Dam && c.steps > limits.max_steps) {
    const std::string key = located("time.end", scene, source, line);
    throw SceneError(key + ": the run needs at least " + number_text(c.steps) +
                         " steps (time.end = " + number_text(scene.time.end) +
                         " s over the initial time step of " + number_text(c.initial_dt) +
                         " s, from time.courant, grid.cell_size and the P-wave speed of "
                         "material \"" + c.stiffest + "\"), more than the limit of " +
                         number_text(limits.max_steps) + "; shorten time.end, raise "
                         "grid.cell_size, or raise the limit with " + limits.steps_option,
                     line);
  }
  if (c.output_bytes > limits.max_output_bytes) {
    const std::string key = located("time.output_interval", scene, source, line);
    throw SceneError(key + ": the run writes about " + number_text(c.frames) +
                         " frames of " + number_text(memory.items) +
                         (method == Method::Dam ? " elements" : " particles") + ", about " +
                         byte_text(c.output_bytes) + " uncompressed, more than " +
                         limits.output_limit_is + " of " + byte_text(limits.max_output_bytes) +
                         "; raise time.output_interval or shorten time.end, or " +
                         limits.output_remedy,
                     line);
  }
}

std::optional<double> free_disk_bytes(const std::string& path) {
  std::error_code ignored;
  std::filesystem::path at = std::filesystem::absolute(path, ignored);
  while (!at.empty() && !std::filesystem::exists(at, ignored) && at != at.parent_path())
    at = at.parent_path();
  struct statvfs fs {};
  // No blocks at all: a pseudo file system (/proc), whose writes fail on
  // their own with a clearer reason than a size.
  if (::statvfs(at.c_str(), &fs) != 0 || fs.f_blocks == 0) return std::nullopt;
  return double(fs.f_bavail) * double(fs.f_frsize);
}

}  // namespace runout
