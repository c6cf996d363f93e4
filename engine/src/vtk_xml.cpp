// Array encoding checked against VTK 9.2's own writer (vtkXMLWriter with
// SetDataModeToBinary, header_type UInt64) and read back by
// vtkXMLUnstructuredGridReader in tests/test_vtu_readback.cpp.
#include "runout/vtk_xml.hpp"

#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "runout/base64.hpp"

namespace runout::vtk_xml {

namespace {

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
      throw std::runtime_error("zlib failed to compress a VTK array");
    }
    compressed.resize(at + written);
    header.push_back(written);
  }
  return base64_encode(header.data(), header.size() * sizeof(std::uint64_t)) +
         base64_encode(compressed.data(), compressed.size());
}

}  // namespace

std::string encode(const void* data, std::size_t size, bool compress) {
  return compress ? encode_zlib(data, size) : encode_raw(data, size);
}

std::string file_header(const char* type, bool compress) {
  std::string xml = std::string("<?xml version=\"1.0\"?>\n<VTKFile type=\"") + type +
                    "\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\"";
  if (compress) xml += " compressor=\"vtkZLibDataCompressor\"";
  return xml + ">\n";
}

}  // namespace runout::vtk_xml
