#pragma once
// The one encoder of VTK XML data arrays shared by every frame writer (the
// particle .vtu, the depth-averaged .vtp): inline binary, base64 of a UInt64
// header and the bytes, optionally zlib in VTK's block layout. Never
// appended data, which Debian 12's expat breaks in VTK 9.2
// (../shared/BUILD.md). And its decoder, for the frame reader
// (vtu_reader.hpp).
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace runout::vtk_xml {

// The arrays are the host's memory as is, and the headers say LittleEndian.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "VTK XML writers assume a little-endian host");

template <class T> struct VtkType;
template <> struct VtkType<double> { static constexpr const char* name = "Float64"; };
template <> struct VtkType<std::int32_t> { static constexpr const char* name = "Int32"; };
template <> struct VtkType<std::int64_t> { static constexpr const char* name = "Int64"; };
template <> struct VtkType<std::uint8_t> { static constexpr const char* name = "UInt8"; };

// The text between <DataArray ...> and </DataArray> for `size` bytes.
std::string encode(const void* data, std::size_t size, bool compress);

// The `size` bytes of one array's text as encode() wrote it (whitespace
// trimmed), compressed or not. Throws std::runtime_error saying what does
// not add up: text that is not base64, a header whose byte count is not
// `size`, zlib blocks that do not inflate to the sizes the header gives.
// `size` comes from the array's attributes; one beyond what the text could
// hold (zlib inflates at most 1032-fold) is refused before anything is
// allocated, so a spoilt count cannot take more memory than the file does.
std::string decode(std::string_view text, std::size_t size, bool compressed);

// `<VTKFile type="..." ...>` with the attributes every frame uses.
std::string file_header(const char* type, bool compress);

// Appends one <DataArray> holding values as tuples of `components`; the only
// path by which any array reaches a file.
template <class T, class A>
void append_array(std::string& xml, const char* indent, const char* name,
                  int components, const std::vector<T, A>& values, bool compress) {
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
  xml += encode(values.data(), values.size() * sizeof(T), compress);
  xml += '\n';
  xml += indent;
  xml += "</DataArray>\n";
}

// Per-item tuples of K components, interleaved as VTK stores them.
template <std::size_t K, class TupleOf>
std::vector<double> tuples(int n, TupleOf tuple_of) {
  std::vector<double> out(static_cast<std::size_t>(n) * K);
  for (int i = 0; i < n; ++i) {
    const std::array<double, K> t = tuple_of(i);
    for (std::size_t k = 0; k < K; ++k) out[static_cast<std::size_t>(i) * K + k] = t[k];
  }
  return out;
}

// The base polyline x0, y0, x1, y1, ... as (x, y, 0) tuples: the field
// array base_points of every frame.
inline std::vector<double> base_points(const std::vector<double>& base_xy) {
  return tuples<3>(static_cast<int>(base_xy.size() / 2), [&](int i) {
    return std::array<double, 3>{base_xy[2 * i], base_xy[2 * i + 1], 0.0};
  });
}

}  // namespace runout::vtk_xml
