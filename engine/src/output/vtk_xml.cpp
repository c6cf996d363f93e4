// Array encoding checked against VTK 9.2's own writer (vtkXMLWriter with
// SetDataModeToBinary, header_type UInt64) and read back by
// vtkXMLUnstructuredGridReader in tests/test_vtu_readback.cpp; decoding
// round-trips it in tests/test_vtu_reader.cpp.
#include "runout/output/vtk_xml.hpp"

#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "runout/output/base64.hpp"

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

// The UInt64 values of decoded header bytes.
std::vector<std::uint64_t> header_values(const std::string& bytes) {
  std::vector<std::uint64_t> values(bytes.size() / sizeof(std::uint64_t));
  std::memcpy(values.data(), bytes.data(), values.size() * sizeof(std::uint64_t));
  return values;
}

std::string decode_raw(std::string_view text, std::size_t size) {
  if (size > text.size() / 4 * 3)
    throw std::runtime_error("the array claims " + std::to_string(size) + " bytes, more than its " +
                             std::to_string(text.size()) + " base64 characters hold");
  std::string bytes = base64_decode(text);
  if (bytes.size() < sizeof(std::uint64_t) ||
      header_values(bytes.substr(0, sizeof(std::uint64_t)))[0] != size ||
      bytes.size() != sizeof(std::uint64_t) + size)
    throw std::runtime_error("its header does not give its " + std::to_string(size) + " bytes");
  return bytes.substr(sizeof(std::uint64_t));
}

// The layout of encode_zlib.
std::string decode_zlib(std::string_view text, std::size_t size) {
  constexpr std::size_t kMaxInflation = 1032;  // deflate's largest ratio
  if (size / kMaxInflation > text.size())
    throw std::runtime_error("the array claims " + std::to_string(size) + " bytes, more than its " +
                             std::to_string(text.size()) + " base64 characters can inflate to");
  // 3 UInt64 (24 bytes, 32 characters) give the block count, hence the
  // length of the header's own base64 run.
  if (text.size() < 32) throw std::runtime_error("its zlib header is cut short");
  const std::vector<std::uint64_t> head = header_values(base64_decode(text.substr(0, 32)));
  if (head.size() < 3) throw std::runtime_error("its zlib header is cut short");
  const std::uint64_t blocks = head[0], block_size = head[1], last = head[2];
  const bool consistent = block_size > 0 && blocks == (size + block_size - 1) / block_size &&
                          last == size % block_size;
  if (!consistent)
    throw std::runtime_error("its zlib header (" + std::to_string(blocks) + " blocks of " +
                             std::to_string(block_size) + " bytes, the last " +
                             std::to_string(last) + ") does not give its " + std::to_string(size) +
                             " bytes");
  const std::size_t header_chars = (8 * (3 + blocks) + 2) / 3 * 4;
  if (header_chars > text.size()) throw std::runtime_error("its zlib header is cut short");
  const std::vector<std::uint64_t> header =
      header_values(base64_decode(text.substr(0, header_chars)));
  // (Padding where the header's run has none gives fewer bytes than it needs.)
  if (header.size() < 3 + blocks) throw std::runtime_error("its zlib header is cut short");
  const std::string compressed = base64_decode(text.substr(header_chars));
  std::string out(size, '\0');
  std::size_t at = 0;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const std::uint64_t length = header[3 + b];
    if (length > compressed.size() - at)
      throw std::runtime_error("its zlib block " + std::to_string(b) + " is cut short");
    const std::size_t raw = b + 1 == blocks && last > 0 ? last : block_size;
    uLongf written = raw;
    if (uncompress(reinterpret_cast<Bytef*>(&out[b * block_size]), &written,
                   reinterpret_cast<const Bytef*>(compressed.data() + at), length) != Z_OK ||
        written != raw)
      throw std::runtime_error("its zlib block " + std::to_string(b) + " does not inflate to " +
                               std::to_string(raw) + " bytes");
    at += length;
  }
  if (at != compressed.size())
    throw std::runtime_error("its zlib data run on past its blocks");
  return out;
}

}  // namespace

std::string decode(std::string_view text, std::size_t size, bool compressed) {
  try {
    return compressed ? decode_zlib(text, size) : decode_raw(text, size);
  } catch (const std::invalid_argument& e) {  // base64_decode's
    throw std::runtime_error(std::string("its text is not base64: ") + e.what());
  }
}

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
