// The particle frame as a VTK XML UnstructuredGrid, every array inline
// binary (vtk_xml.hpp), read back by vtkXMLUnstructuredGridReader in
// tests/test_vtu_readback.cpp.
#include <array>
#include <cmath>
#include <cstdint>

#include "runout/output/atomic_file.hpp"
#include "runout/output/vtk_xml.hpp"
#include "runout/output/vtu_writer.hpp"

namespace runout {

namespace {

using vtk_xml::append_array;
using vtk_xml::tuples;

// Stress invariants, tension positive, plane strain (szz carried):
//   mean_stress       p     = (sxx + syy + szz) / 3
//   von_mises_stress  q     = sqrt(3 J2), J2 = (dxx^2 + dyy^2 + dzz^2) / 2 + sxy^2,
//                             d = s - p I the full 3D deviator
//   max_shear_stress  tau   = sqrt(((sxx - syy) / 2)^2 + sxy^2), in-plane
double mean_stress(const Particles& p, int i) {
  return (p.sxx[i] + p.syy[i] + p.szz[i]) / 3.0;
}

double von_mises_stress(const Particles& p, int i) {
  const double m = mean_stress(p, i);
  const double dxx = p.sxx[i] - m, dyy = p.syy[i] - m, dzz = p.szz[i] - m;
  const double j2 = 0.5 * (dxx * dxx + dyy * dyy + dzz * dzz) + p.sxy[i] * p.sxy[i];
  return std::sqrt(3.0 * j2);
}

double max_shear_stress(const Particles& p, int i) {
  return std::hypot(0.5 * (p.sxx[i] - p.syy[i]), p.sxy[i]);
}

}  // namespace

void write_particles_vtu(const std::string& path, const Particles& p,
                         const FrameInfo& info, bool compress) {
  static_assert(sizeof(int) == sizeof(std::int32_t), "body and material ids are written as Int32");
  const int n = p.size();

  std::string xml = vtk_xml::file_header("UnstructuredGrid", compress);
  xml += "  <UnstructuredGrid>\n    <FieldData>\n";
  append_array(xml, "      ", "TimeValue", 1, std::vector<double>{info.time}, compress);
  if (info.particle_spacing > 0)
    append_array(xml, "      ", "particle_spacing", 1,
                 std::vector<double>{info.particle_spacing}, compress);
  if (!info.base_xy.empty())
    append_array(xml, "      ", "base_points", 3, vtk_xml::base_points(info.base_xy), compress);
  xml += "    </FieldData>\n    <Piece NumberOfPoints=\"" + std::to_string(n) +
         "\" NumberOfCells=\"" + std::to_string(n) + "\">\n      <PointData>\n";

  // An array inside the Piece; (a, b, 0) vectors; a stress invariant.
  auto array = [&](const char* name, int components, const auto& values) {
    append_array(xml, "        ", name, components, values, compress);
  };
  auto in_plane = [n](const StaggeredArray& a, const StaggeredArray& b) {
    return tuples<3>(n, [&](int i) { return std::array<double, 3>{a[i], b[i], 0.0}; });
  };
  auto invariant = [n, &p](double (*value_of)(const Particles&, int)) {
    return tuples<1>(n, [&](int i) { return std::array<double, 1>{value_of(p, i)}; });
  };

  array("velocity", 3, in_plane(p.vx, p.vy));
  array("displacement", 3, tuples<3>(n, [&](int i) {
          return std::array<double, 3>{p.x[i] - p.x0[i], p.y[i] - p.y0[i], 0.0};
        }));
  // VTK's symmetric tensor order: XX, YY, ZZ, XY, YZ, XZ.
  array("stress", 6, tuples<6>(n, [&](int i) {
          return std::array<double, 6>{p.sxx[i], p.syy[i], p.szz[i], p.sxy[i], 0.0, 0.0};
        }));
  array("mean_stress", 1, invariant(mean_stress));
  array("von_mises_stress", 1, invariant(von_mises_stress));
  array("max_shear_stress", 1, invariant(max_shear_stress));
  array("plastic_shear_strain", 1, p.xi);
  array("shear_strain_rate", 1, p.gamma_dot);
  array("strength", 1, p.su);
  if (info.clay_band) array("band_shear_strain", 1, p.band_xi);
  if (!info.strengths.empty())
    array("rate_factor", 1, tuples<1>(n, [&](int i) {
            return std::array<double, 1>{rate_factor(info.strengths[p.material[i]], p.gamma_dot[i])};
          }));
  array("mass", 1, p.mass);
  array("volume", 1, p.vol);
  array("initial_volume", 1, p.vol0);
  array("initial_position", 3, in_plane(p.x0, p.y0));
  array("body_id", 1, p.body);
  array("material_id", 1, p.material);
  array("particle_id", 1, p.id);
  xml += "      </PointData>\n      <Points>\n";

  array("Points", 3, in_plane(p.x, p.y));
  xml += "      </Points>\n      <Cells>\n";

  // One VTK_VERTEX (type 1) per particle; types are UInt8 as VTK writes them.
  std::vector<std::int64_t> connectivity(n), offsets(n);
  for (int i = 0; i < n; ++i) {
    connectivity[i] = i;
    offsets[i] = i + 1;
  }
  array("connectivity", 1, connectivity);
  array("offsets", 1, offsets);
  array("types", 1, std::vector<std::uint8_t>(n, 1));
  xml += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";

  write_file_atomically(path, xml);
}

}  // namespace runout
