// The resolved scene: every key written, defaults included, so the file
// beside a run's frames says exactly how it was run and parse_scene reads it
// back as the same Scene.
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "runout/output/quoted_text.hpp"
#include "runout/scene/scene_parser.hpp"
#include "scene_text.hpp"

namespace runout {
namespace {

using scene_text::name_of;

// Always with a decimal point or exponent, so the value reads as a TOML float.
std::string number(double value) {
  std::string text = scene_text::format_number(value);
  if (text.find_first_not_of("-0123456789") == std::string::npos) text += ".0";
  return text;
}

std::string vec2(const Eigen::Vector2d& v) {
  std::string text = "[";
  text += number(v.x());
  text += ", ";
  text += number(v.y());
  text += ']';
  return text;
}

std::string points(const std::vector<Eigen::Vector2d>& list) {
  std::string text = "[";
  for (std::size_t i = 0; i < list.size(); ++i) text += (i ? ", " : "") + vec2(list[i]);
  return text + "]";
}

// The parser turns a slope into magnitude * (sin, -cos); |vector| can differ
// from that magnitude in its last bits, so look next to it for the magnitude
// that gives back exactly this vector.
double slope_magnitude(const GravitySpec& gravity) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double norm = gravity.vector.norm();
  double up = norm, down = norm;
  for (int step = 0; step < 4; ++step) {
    for (const double m : {up, down})
      if (scene_text::slope_gravity(m, gravity.slope_angle_deg) == gravity.vector)
        return m;
    up = std::nextafter(up, kInf);
    down = std::nextafter(down, -kInf);
  }
  return norm;
}

void write_gravity(std::ostream& out, const GravitySpec& gravity) {
  out << "[gravity]\n";
  if (gravity.slope_angle_deg == 0.0) {
    out << "vector = " << vec2(gravity.vector) << "\n";
  } else {
    out << "magnitude = " << number(slope_magnitude(gravity)) << "\n"
        << "slope_angle = " << number(gravity.slope_angle_deg) << "\n";
  }
  out << "ramp = " << number(gravity.ramp) << "\n";
}

void write_material(std::ostream& out, const MaterialSpec& m) {
  out << "[[material]]\n"
      << "name = " << quoted_text(m.name) << "\n"
      << "model = " << quoted_text(name_of(scene_text::kModelNames, m.model)) << "\n"
      << "density = " << number(m.density) << "\n"
      << "youngs_modulus = " << number(m.youngs_modulus) << "\n"
      << "poisson_ratio = " << number(m.poisson_ratio) << "\n";
  if (m.model == MaterialModel::Tresca) {
    out << "su0 = " << number(m.su0) << "\n"
        << "sensitivity = " << number(m.sensitivity) << "\n"
        << "xi95 = " << number(m.xi95) << "\n"
        << "eta = " << number(m.eta) << "\n"
        << "rate_exponent = " << number(m.rate_exponent) << "\n"
        << "reference_rate = " << number(m.reference_rate) << "\n"
        << "strength_form = "
        << quoted_text(name_of(scene_text::kStrengthFormNames, m.strength_form)) << "\n";
    if (m.band_thickness > 0.0)  // 0 (local) is not a value the key takes
      out << "band_thickness = " << number(m.band_thickness) << "\n";
    if (m.nonlocal_length > 0.0)
      out << "nonlocal_length = " << number(m.nonlocal_length) << "\n";
  }
  out << "\n";
}

void write_body(std::ostream& out, const BodySpec& body,
                const std::vector<MaterialSpec>& materials) {
  out << "[[body]]\n"
      << "name = " << quoted_text(body.name) << "\n"
      << "material = " << quoted_text(materials.at(body.material).name) << "\n"
      << "type = \"polygon\"\n"
      << "vertices = " << points(body.polygon) << "\n"
      << "velocity = " << vec2(body.velocity) << "\n\n";
}

// Only a scene with a base has the table: BaseKind::None is its absence.
void write_base(std::ostream& out, const BaseSpec& base) {
  if (base.kind == BaseKind::None) return;
  out << "[base]\n"
      << "kind = " << quoted_text(name_of(scene_text::kBaseNames, base.kind)) << "\n";
  if (base.kind == BaseKind::Polyline) out << "points = " << points(base.points) << "\n";
  out << "interface = " << quoted_text(name_of(scene_text::kInterfaceNames, base.interface)) << "\n";
  if (base.interface == InterfaceKind::Frictional)
    out << "shear_strength = " << number(base.shear_strength) << "\n";
  if (base.interface == InterfaceKind::Coulomb)
    out << "friction = " << number(base.friction) << "\n";
  if (base.clay_band) out << "clay_band = true\n";
  out << "\n";
}

}  // namespace

std::string to_toml(const Scene& scene) {
  using scene_text::kBoundaryNames;
  std::ostringstream out;
  out << "# Resolved scene: every default filled in.\n"
      << "[scene]\n"
      << "name = " << quoted_text(scene.name) << "\n"
      << "description = " << quoted_text(scene.description) << "\n"
      << "method = " << quoted_text(name_of(scene_text::kMethodNames, scene.method)) << "\n\n";

  const GridSpec& grid = scene.grid;
  out << "[grid]\n"
      << "cell_size = " << number(grid.cell_size) << "\n"
      << "min = " << vec2(grid.min) << "\n"
      << "max = " << vec2(grid.max) << "\n"
      << "shape = " << quoted_text(name_of(scene_text::kShapeNames, grid.shape)) << "\n"
      << "domain = " << quoted_text(name_of(scene_text::kDomainNames, grid.domain)) << "\n"
      << "ppc = " << grid.ppc << "\n\n";

  const BoundarySpec& b = scene.boundary;
  out << "[boundary]\n"
      << "left = " << quoted_text(name_of(kBoundaryNames, b.left)) << "\n"
      << "right = " << quoted_text(name_of(kBoundaryNames, b.right)) << "\n"
      << "bottom = " << quoted_text(name_of(kBoundaryNames, b.bottom)) << "\n"
      << "top = " << quoted_text(name_of(kBoundaryNames, b.top)) << "\n\n";

  out << "[time]\n"
      << "end = " << number(scene.time.end) << "\n"
      << "output_interval = " << number(scene.time.output_interval) << "\n"
      << "courant = " << number(scene.time.courant) << "\n"
      << "rest_fraction = " << number(scene.time.rest_fraction) << "\n"
      << "rest_duration = " << number(scene.time.rest_duration) << "\n\n";

  write_gravity(out, scene.gravity);

  out << "\n[solver]\n"
      << "transfer = " << quoted_text(name_of(scene_text::kTransferNames, scene.solver.transfer))
      << "\n"
      << "flip = " << number(scene.solver.flip) << "\n"
      << "pic_cells = " << number(scene.solver.pic_cells) << "\n"
      << "xpic_order = " << scene.solver.xpic_order << "\n"
      << "xpic_cells = " << number(scene.solver.xpic_cells) << "\n"
      << "mass_threshold = " << number(scene.solver.mass_threshold) << "\n"
      << "damping = " << number(scene.solver.damping) << "\n"
      << "volumetric_smoothing = " << (scene.solver.volumetric_smoothing ? "true" : "false")
      << "\n\n";

  for (const MaterialSpec& m : scene.materials) write_material(out, m);
  for (const BodySpec& body : scene.bodies) write_body(out, body, scene.materials);
  write_base(out, scene.base);

  out << "[dam]\n"
      << "shear_rate = " << quoted_text(name_of(scene_text::kShearRateNames, scene.dam.shear_rate))
      << "\n"
      << "earth_pressure = "
      << quoted_text(name_of(scene_text::kEarthPressureNames, scene.dam.earth_pressure)) << "\n"
      << "elements = " << scene.dam.elements << "\n"
      << "water_density = " << number(scene.dam.water_density) << "\n"
      << "skin_friction = " << number(scene.dam.skin_friction) << "\n"
      << "pressure_drag = " << number(scene.dam.pressure_drag) << "\n"
      << "added_mass = " << number(scene.dam.added_mass) << "\n\n";

  out << "[output]\n"
      << "compress = " << (scene.output.compress ? "true" : "false") << "\n\n"
      << "[run]\n"
      << "overrides = [";
  for (std::size_t i = 0; i < scene.overrides.size(); ++i)
    out << (i ? ", " : "") << quoted_text(scene.overrides[i]);
  out << "]\n";
  return out.str();
}

}  // namespace runout
