// The frame and index files as text, without VTK: base64, atomic writes,
// the VTU's arrays decoded by hand, the PVD list. test_vtu_readback checks
// the same files through VTK's own reader.
#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "runout/output/atomic_file.hpp"
#include "runout/output/base64.hpp"
#include "runout/output/vtu_writer.hpp"
#include "vtu_text.hpp"

namespace fs = std::filesystem;
using namespace runout;
using namespace runout::vtu_text;

namespace {

std::string encode(const std::string& s) { return base64_encode(s.data(), s.size()); }

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> folder_names(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

// zlib: base64(UInt64 [blocks, block size, last size, compressed sizes...])
// followed by base64(compressed blocks).
std::string decode_zlib(const std::string& text) {
  const auto first = as_values<std::uint64_t>(decode_base64(text.substr(0, 32)));
  const std::size_t blocks = first.at(0), block_size = first.at(1), last = first.at(2);
  const std::size_t header_chars = (8 * (3 + blocks) + 2) / 3 * 4;
  const auto header = as_values<std::uint64_t>(decode_base64(text.substr(0, header_chars)));
  const std::string compressed = decode_base64(text.substr(header_chars));
  std::string out;
  std::size_t at = 0;
  for (std::size_t b = 0; b < blocks; ++b) {
    std::string block(b + 1 == blocks && last != 0 ? last : block_size, '\0');
    uLongf size = block.size();
    EXPECT_EQ(uncompress(reinterpret_cast<Bytef*>(&block[0]), &size,
                         reinterpret_cast<const Bytef*>(&compressed[at]), header.at(3 + b)),
              Z_OK);
    EXPECT_EQ(size, block.size());
    at += header.at(3 + b);
    out += block;
  }
  EXPECT_EQ(at, compressed.size());
  return out;
}

Particles sample_particles(int n) {
  Particles p;
  p.resize(n);
  for (int i = 0; i < n; ++i) {
    const double s = i + 0.125;
    p.x[i] = 1.5 * s;  p.y[i] = -0.25 * s;
    p.x0[i] = s;       p.y0[i] = 0.5 * s;
    p.vx[i] = 0.1 * s; p.vy[i] = -0.2 * s;
    p.sxx[i] = -100 * s; p.syy[i] = -50 * s; p.szz[i] = -70 * s; p.sxy[i] = 20 * s;
    p.mass[i] = 3 + s; p.vol[i] = 0.01 * s; p.vol0[i] = 0.02 * s;
    p.xi[i] = 0.001 * s; p.gamma_dot[i] = 0.3 * s; p.su[i] = 2500 - s;
    p.body[i] = i % 3; p.material[i] = i % 2; p.id[i] = 1000000000000LL + i;
  }
  return p;
}

const std::vector<std::string> kPointArrays = {
    "velocity", "displacement", "stress", "mean_stress", "von_mises_stress",
    "max_shear_stress", "plastic_shear_strain", "shear_strain_rate", "strength",
    "mass", "volume", "initial_volume", "initial_position", "body_id",
    "material_id", "particle_id"};

class OutputFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("runout_test_vtu_writer_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

}  // namespace

TEST(Base64, Rfc4648TestVectors) {
  EXPECT_EQ(encode(""), "");
  EXPECT_EQ(encode("f"), "Zg==");
  EXPECT_EQ(encode("fo"), "Zm8=");
  EXPECT_EQ(encode("foo"), "Zm9v");
  EXPECT_EQ(encode("foob"), "Zm9vYg==");
  EXPECT_EQ(encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(encode("foobar"), "Zm9vYmFy");
}

TEST(Base64, EveryByteValueRoundTrips) {
  std::string bytes;
  for (int i = 0; i < 256; ++i) bytes += static_cast<char>(i);
  const std::string text = encode(bytes);
  EXPECT_EQ(text.find_first_not_of(
                "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/="),
            std::string::npos);
  EXPECT_EQ(decode_base64(text), bytes);
}

TEST_F(OutputFiles, AtomicWriteReplacesContentAndLeavesNoTemporary) {
  const fs::path file = dir_ / "a.txt";
  write_file_atomically(file, "first version, longer");
  write_file_atomically(file, "second");
  EXPECT_EQ(read_text(file), "second");
  EXPECT_EQ(folder_names(dir_), std::vector<std::string>{"a.txt"});
}

TEST_F(OutputFiles, AtomicWriteFailureNamesThePathAndCleansUp) {
  const fs::path missing = dir_ / "no_such_folder" / "a.txt";
  try {
    write_file_atomically(missing, "x");
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
  }
  // rename onto a non-empty folder fails after the temporary was written.
  const fs::path folder = dir_ / "occupied";
  fs::create_directories(folder / "inside");
  try {
    write_file_atomically(folder, "x");
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(folder.string()), std::string::npos) << e.what();
  }
  EXPECT_EQ(folder_names(dir_), std::vector<std::string>{"occupied"});
}

TEST_F(OutputFiles, VtuHasEveryArrayInlineBinary) {
  for (const bool compress : {false, true}) {
    const fs::path file = dir_ / "frame.vtu";
    write_particles_vtu(file, sample_particles(7), FrameInfo{1.25, 0.0, {}, {}}, compress);
    const std::string xml = read_text(file);
    EXPECT_EQ(xml.find("<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" "
                       "version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\""),
              0u);
    EXPECT_EQ(xml.find("compressor=\"vtkZLibDataCompressor\"") != std::string::npos, compress);
    EXPECT_NE(xml.find("<Piece NumberOfPoints=\"7\" NumberOfCells=\"7\">"), std::string::npos);
    for (const auto& name : kPointArrays) {
      EXPECT_NE(xml.find("Name=\"" + name + "\""), std::string::npos) << name;
    }
    for (const char* name : {"TimeValue", "Points", "connectivity", "offsets", "types"}) {
      EXPECT_NE(xml.find("Name=\"" + std::string(name) + "\""), std::string::npos) << name;
    }
    std::size_t arrays = 0, binary = 0;
    for (auto at = xml.find("<DataArray"); at != std::string::npos; at = xml.find("<DataArray", at + 1)) ++arrays;
    for (auto at = xml.find("format=\"binary\""); at != std::string::npos; at = xml.find("format=\"binary\"", at + 1)) ++binary;
    EXPECT_EQ(arrays, kPointArrays.size() + 5);
    EXPECT_EQ(binary, arrays);
    std::string lower = xml;
    std::transform(lower.begin(), lower.end(), lower.begin(), ::tolower);
    EXPECT_EQ(lower.find("appended"), std::string::npos);
    EXPECT_EQ(folder_names(dir_), std::vector<std::string>{"frame.vtu"});
  }
}

TEST_F(OutputFiles, UncompressedArraysDecodeToTheWrittenValues) {
  const int n = 7;
  const Particles p = sample_particles(n);
  const fs::path file = dir_ / "frame.vtu";
  write_particles_vtu(file, p, FrameInfo{1.25, 0.0, {}, {}}, false);
  const std::string xml = read_text(file);

  EXPECT_EQ(as_values<double>(decode_raw(array_text(xml, "TimeValue"))), std::vector<double>{1.25});

  const auto stress = as_values<double>(decode_raw(array_text(xml, "stress")));
  ASSERT_EQ(stress.size(), 6u * n);
  for (int i = 0; i < n; ++i) {
    const std::vector<double> tuple(stress.begin() + 6 * i, stress.begin() + 6 * i + 6);
    EXPECT_EQ(tuple, (std::vector<double>{p.sxx[i], p.syy[i], p.szz[i], p.sxy[i], 0.0, 0.0}));
  }
  EXPECT_EQ(as_values<std::int64_t>(decode_raw(array_text(xml, "particle_id"))), p.id);
  EXPECT_EQ(as_values<std::int32_t>(decode_raw(array_text(xml, "body_id"))), p.body);
  EXPECT_EQ(as_values<std::int64_t>(decode_raw(array_text(xml, "offsets"))),
            (std::vector<std::int64_t>{1, 2, 3, 4, 5, 6, 7}));
}

TEST_F(OutputFiles, CompressedArraysDecodeBlockByBlock) {
  // 5000 doubles: two zlib blocks, the last one partial.
  const Particles p = sample_particles(5000);
  const fs::path file = dir_ / "frame.vtu";
  write_particles_vtu(file, p, FrameInfo{0.5, 0.0, {}, {}}, true);
  const std::string xml = read_text(file);
  EXPECT_EQ(as_values<double>(decode_zlib(array_text(xml, "mass"))),
            std::vector<double>(p.mass.begin(), p.mass.end()));
  EXPECT_EQ(as_values<std::int64_t>(decode_zlib(array_text(xml, "particle_id"))), p.id);
  EXPECT_EQ(as_values<double>(decode_zlib(array_text(xml, "TimeValue"))), std::vector<double>{0.5});
}

TEST_F(OutputFiles, EmptyFrameIsValid) {
  for (const bool compress : {false, true}) {
    const fs::path file = dir_ / "empty.vtu";
    write_particles_vtu(file, Particles{}, FrameInfo{0.0, 0.0, {}, {}}, compress);
    const std::string xml = read_text(file);
    EXPECT_NE(xml.find("<Piece NumberOfPoints=\"0\" NumberOfCells=\"0\">"), std::string::npos);
    const std::string mass = array_text(xml, "mass");
    EXPECT_TRUE((compress ? decode_zlib(mass) : decode_raw(mass)).empty());
  }
}

TEST_F(OutputFiles, PvdListsFramesInOrderWithExactTimes) {
  PvdIndex index((dir_ / "run.pvd").string());
  const std::vector<double> times = {0.0, 0.1, 1.0 / 3.0};
  for (std::size_t k = 0; k < times.size(); ++k) {
    index.add(times[k], "frame_0000" + std::to_string(k) + ".vtu");
  }
  const std::string pvd = read_text(index.path());
  EXPECT_EQ(pvd.find("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" "
                     "byte_order=\"LittleEndian\">\n  <Collection>\n"),
            0u);
  std::size_t at = 0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const std::string file = "file=\"frame_0000" + std::to_string(k) + ".vtu\"";
    const auto next = pvd.find(file, at);
    ASSERT_NE(next, std::string::npos) << file;
    const auto stamp = pvd.rfind("timestep=\"", next) + 10;
    EXPECT_EQ(std::stod(pvd.substr(stamp)), times[k]);
    EXPECT_NE(pvd.find("group=\"\" part=\"0\"", stamp), std::string::npos);
    at = next;
  }
  EXPECT_NE(pvd.find("timestep=\"0.33333333333333331\""), std::string::npos);
  // The index and its manifest (docs/output.md), no temporary.
  EXPECT_EQ(folder_names(dir_), (std::vector<std::string>{"run.pvd", "run.pvd.manifest"}));
}
