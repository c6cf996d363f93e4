// The particle frame as a VTK XML UnstructuredGrid, every array inline
// binary. Layout checked against VTK 9.2's own writer (vtkXMLWriter with
// SetDataModeToBinary, header_type UInt64) and read back by
// vtkXMLUnstructuredGridReader in tests/test_vtu_readback.cpp.
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include "runout/atomic_file.hpp"
#include "runout/base64.hpp"
#include "runout/vtu_writer.hpp"

namespace runout {

namespace {

// The arrays are the host's memory as is, and the header says LittleEndian.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "VTU writer assumes a little-endian host");

template <class T> struct VtkType;
template <> struct VtkType<double> { static constexpr const char* name = "Float64"; };
template <> struct VtkType<std::int32_t> { static constexpr const char* name = "Int32"; };
template <> struct VtkType<std::int64_t> { static constexpr const char* name = "Int64"; };
template <> struct VtkType<std::uint8_t> { static constexpr const char* name = "UInt8"; };

// VTK's own block size. Level 1: simulation doubles barely compress at any
// level; the gain (ids, zero components, uniform arrays) comes at level 1
// already, at a fraction of the default level's time.
constexpr std::size_t kBlockSize = 32768;
constexpr int kZlibLevel = Z_BEST_SPEED;

std::string encode_raw(const void* data, std::size_t size) {
  // base64 of (UInt64 byte count, bytes) as one run.
  const std::uint64_t header = size;
  std::string raw(sizeof header + size, '\0');
  std::memcpy(&raw[0], &header, sizeof header);
  if (size > 0) std::memcpy(&raw[sizeof header], data, size);
  return base64_encode(raw.data(), raw.size());
}

std::string encode_zlib(const void* data, std::size_t size) {
  // UInt64 header [blocks, block size, size of the last block (0 when it is
  // full), compressed size of each block], then the compressed blocks back
  // to back: two separate base64 runs, as vtkXMLDataParser reads them.
  const auto* in = static_cast<const Bytef*>(data);
  const std::size_t blocks = (size + kBlockSize - 1) / kBlockSize;
  std::vector<std::uint64_t> header{blocks, kBlockSize, size % kBlockSize};
  std::string compressed;
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t block = std::min(kBlockSize, size - b * kBlockSize);
    const std::size_t at = compressed.size();
    uLongf written = compressBound(block);
    compressed.resize(at + written);
    if (compress2(reinterpret_cast<Bytef*>(&compressed[at]), &written,
                  in + b * kBlockSize, block, kZlibLevel) != Z_OK) {
      throw std::runtime_error("zlib failed to compress a VTU array");
    }
    compressed.resize(at + written);
    header.push_back(written);
  }
  return base64_encode(header.data(), header.size() * sizeof(std::uint64_t)) +
         base64_encode(compressed.data(), compressed.size());
}

// Appends one <DataArray> holding values as tuples of `components`; the only
// path by which any array reaches the file.
template <class T>
void append_array(std::string& xml, const char* indent, const char* name,
                  int components, const std::vector<T>& values, bool compress) {
  const std::size_t bytes = values.size() * sizeof(T);
  xml += indent;
  xml += "<DataArray type=\"";
  xml += VtkType<T>::name;
  xml += "\" Name=\"";
  xml += name;
  xml += "\" NumberOfComponents=\"" + std::to_string(components) +
         "\" NumberOfTuples=\"" + std::to_string(values.size() / components) +
         "\" format=\"binary\">\n";
  xml += indent;
  xml += "  ";
  xml += compress ? encode_zlib(values.data(), bytes) : encode_raw(values.data(), bytes);
  xml += '\n';
  xml += indent;
  xml += "</DataArray>\n";
}

// Per-particle tuples of K components, interleaved as VTK stores them.
template <std::size_t K, class TupleOf>
std::vector<double> tuples(int n, TupleOf tuple_of) {
  std::vector<double> out(static_cast<std::size_t>(n) * K);
  for (int i = 0; i < n; ++i) {
    const std::array<double, K> t = tuple_of(i);
    std::copy(t.begin(), t.end(), out.begin() + static_cast<std::ptrdiff_t>(i) * K);
  }
  return out;
}

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

  std::string xml =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
      "byte_order=\"LittleEndian\" header_type=\"UInt64\"";
  if (compress) xml += " compressor=\"vtkZLibDataCompressor\"";
  xml += ">\n  <UnstructuredGrid>\n    <FieldData>\n";
  append_array(xml, "      ", "TimeValue", 1, std::vector<double>{info.time}, compress);
  if (info.particle_spacing > 0)
    append_array(xml, "      ", "particle_spacing", 1,
                 std::vector<double>{info.particle_spacing}, compress);
  if (!info.base_xy.empty()) {
    const int points = static_cast<int>(info.base_xy.size() / 2);
    append_array(xml, "      ", "base_points", 3, tuples<3>(points, [&](int i) {
                   return std::array<double, 3>{info.base_xy[2 * i], info.base_xy[2 * i + 1], 0.0};
                 }), compress);
  }
  xml += "    </FieldData>\n    <Piece NumberOfPoints=\"" + std::to_string(n) +
         "\" NumberOfCells=\"" + std::to_string(n) + "\">\n      <PointData>\n";

  // An array inside the Piece; (a, b, 0) vectors; a stress invariant.
  auto array = [&](const char* name, int components, const auto& values) {
    append_array(xml, "        ", name, components, values, compress);
  };
  auto in_plane = [n](const std::vector<double>& a, const std::vector<double>& b) {
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
