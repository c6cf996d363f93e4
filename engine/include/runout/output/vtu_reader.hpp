#pragma once
// Reads back the particle frames the engine writes (vtu_writer.hpp), without
// VTK: a VTK XML UnstructuredGrid whose arrays are inline binary, base64 of
// a UInt64 header and the bytes, zlib-compressed in VTK's block layout or
// not (docs/output.md, "Frame format"). Strict: the other layouts VTK can
// write (appended data, ascii arrays, UInt32 headers, big-endian, other
// compressors, other data set types) are refused with a message that says
// which, rather than guessed at; so is anything that does not add up.
#include <cstddef>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace runout {

// One <DataArray>: its type as the file names it (Float64, Int32, Int64 or
// UInt8, the types the engine writes) and its values as doubles, tuples of
// `components` interleaved. (Int64 particle ids are exact up to 2^53, as
// VTK's GetComponent gives them to the filters.)
struct VtuArray {
  std::string type;
  int components = 1;
  std::vector<double> values;
  std::size_t tuples() const { return values.size() / components; }
};

struct VtuFrame {
  std::size_t points = 0;  // NumberOfPoints of the Piece
  std::size_t cells = 0;   // NumberOfCells
  VtuArray positions;      // the Points array: x, y, z per point
  std::map<std::string, VtuArray> field_data, point_data, cell_arrays;  // by Name

  // The point or field array `name`, or nullptr.
  const VtuArray* point_array(const std::string& name) const;
  const VtuArray* field_array(const std::string& name) const;
};

class VtuReadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The frame in `xml`, the whole text of a .vtu; throws VtuReadError saying
// what is wrong with it.
VtuFrame parse_vtu_frame(std::string_view xml);

// The frame in the file at `path`; throws VtuReadError, naming the path.
VtuFrame read_vtu_frame(const std::string& path);

}  // namespace runout
