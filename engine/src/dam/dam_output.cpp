#include "runout/dam/dam_output.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "runout/output/atomic_file.hpp"
#include "runout/output/vtk_xml.hpp"

namespace runout {

HistoryRow dam_history_row(const DamSolver& dam, double initial_toe) {
  const BaseView base = dam.base();
  const int n = dam.elements();
  HistoryRow r;
  r.time = dam.time();
  r.step = dam.steps();
  r.dt = dam.last_dt();
  r.toe = dam.s().back();
  r.toe_velocity = dam.v().back();
  r.runout = r.toe - initial_toe;
  r.rear = dam.s().front();
  r.length = r.toe - r.rear;
  double mass = 0.0;
  for (int e = 0; e < n; ++e) {
    // The element's centroid: half its thickness above its mid-point.
    const double m = dam.density() * dam.volume()[e], h = dam.thickness(e);
    const BaseFrame f = base_frame_at(base, dam.mid(e));
    mass += m;
    r.max_thickness = std::max(r.max_thickness, h);
    r.centroid_x += m * (f.x + 0.5 * h * f.nx);
    r.centroid_y += m * (f.y + 0.5 * h * f.ny);
    r.centroid_s += m * dam.mid(e);
    r.centroid_velocity += m * dam.element_velocity(e);
  }
  // The mass front: each element's mass spread evenly over its length.
  const double front_mass = kMassFrontFraction * mass;
  double behind = 0.0;
  r.runout_95 = r.toe - initial_toe;
  for (int e = 0; e < n; ++e) {
    const double m = dam.density() * dam.volume()[e];
    if (behind + m >= front_mass) {
      const double s0 = dam.s()[e], s1 = dam.s()[e + 1];
      r.runout_95 = s0 + (s1 - s0) * (front_mass - behind) / m - initial_toe;
      break;
    }
    behind += m;
  }
  r.centroid_x /= mass;
  r.centroid_y /= mass;
  r.centroid_s /= mass;
  r.centroid_velocity /= mass;
  // Node-lumped, as the momentum equation is.
  for (std::size_t i = 0; i < dam.s().size(); ++i) {
    const double m = dam.node_mass()[i], v = dam.v()[i];
    const BaseFrame f = base_frame_at(base, dam.s()[i]);
    r.max_speed = std::max(r.max_speed, std::abs(v));
    r.kinetic_energy += 0.5 * m * v * v;
    r.momentum_x += m * v * f.tx;
    r.momentum_y += m * v * f.ty;
  }
  r.basal_shear_force = dam.basal_shear_force();
  return r;
}

void write_dam_vtp(const std::string& path, const DamSolver& dam,
                   const std::vector<double>& base_xy, bool compress) {
  using vtk_xml::append_array;
  using vtk_xml::tuples;
  const int n = dam.elements();
  const BaseView base = dam.base();
  std::vector<BaseFrame> frames;
  for (int e = 0; e < n; ++e) frames.push_back(base_frame_at(base, dam.mid(e)));

  std::string xml = vtk_xml::file_header("PolyData", compress);
  xml += "  <PolyData>\n    <FieldData>\n";
  append_array(xml, "      ", "TimeValue", 1, std::vector<double>{dam.time()}, compress);
  if (!base_xy.empty())
    append_array(xml, "      ", "base_points", 3, vtk_xml::base_points(base_xy), compress);
  xml += "    </FieldData>\n    <Piece NumberOfPoints=\"" + std::to_string(n) +
         "\" NumberOfVerts=\"0\" NumberOfLines=\"1\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n"
         "      <PointData>\n";
  auto array = [&](const char* name, int components, const std::vector<double>& values) {
    append_array(xml, "        ", name, components, values, compress);
  };
  auto per_element = [n](auto value_of) {
    return tuples<1>(n, [&](int e) { return std::array<double, 1>{value_of(e)}; });
  };
  array("thickness", 1, per_element([&](int e) { return dam.thickness(e); }));
  array("velocity", 3, tuples<3>(n, [&](int e) {
          const double v = dam.element_velocity(e);
          return std::array<double, 3>{v * frames[e].tx, v * frames[e].ty, 0.0};
        }));
  array("strength", 1, dam.tau());
  array("shear_strain_rate", 1, dam.gamma_dot());
  array("plastic_shear_strain", 1, dam.xi());
  array("longitudinal_deviator", 1, dam.deviator());
  array("layer_plastic_shear_strain", 1, dam.layer_xi());
  array("s", 1, per_element([&](int e) { return dam.mid(e); }));
  xml += "      </PointData>\n      <Points>\n";
  array("Points", 3, tuples<3>(n, [&](int e) {
          return std::array<double, 3>{frames[e].x, frames[e].y, 0.0};
        }));
  xml += "      </Points>\n      <Lines>\n";
  std::vector<std::int64_t> connectivity(n);
  for (int e = 0; e < n; ++e) connectivity[e] = e;
  append_array(xml, "        ", "connectivity", 1, connectivity, compress);
  append_array(xml, "        ", "offsets", 1, std::vector<std::int64_t>{n}, compress);
  xml += "      </Lines>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
  write_file_atomically(path, xml);
}

Profile dam_profile(const DamSolver& dam) {
  Profile p;
  const BaseView base = dam.base();
  p.bin_width = dam.s().size() > 1 ? (dam.s().back() - dam.s().front()) / dam.elements() : 0.0;
  for (int e = 0; e < dam.elements(); ++e) {
    const BaseFrame f = base_frame_at(base, dam.mid(e));
    const double h = dam.thickness(e);
    p.bins.push_back({dam.mid(e), 1, h, f.x + h * f.nx, f.y + h * f.ny, dam.element_velocity(e)});
  }
  return p;
}

}  // namespace runout
