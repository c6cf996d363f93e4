// The engine's frames read back without VTK (runout/output/vtu_reader.hpp): every
// array write_particles_vtu writes comes back as written, compressed or
// not, over several zlib blocks and for no particles; base64 and the array
// decoder against known values; and each layout the reader refuses (VTK's
// others, spoilt frames) refused with a message that says which.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "run_folder.hpp"
#include "runout/output/base64.hpp"
#include "runout/output/vtk_xml.hpp"
#include "runout/output/vtu_reader.hpp"
#include "runout/output/vtu_writer.hpp"

using runout::VtuArray;
using runout::VtuFrame;
using runout::VtuReadError;
using runout::run_folder::read_file;
using runout::run_folder::ScratchFolder;

namespace {

// n particles whose every field differs from particle to particle.
runout::Particles particles(int n) {
  runout::Particles p;
  p.resize(n);
  for (int i = 0; i < n; ++i) {
    const double a = 0.37 * i + 1.0 / 3.0;
    p.x[i] = a;
    p.y[i] = -a / 7;
    p.vx[i] = std::sin(a);
    p.vy[i] = std::cos(a);
    p.x0[i] = a - 0.5;
    p.y0[i] = a / 9;
    p.mass[i] = 1 + a;
    p.vol[i] = 2 + a;
    p.vol0[i] = 3 + a;
    p.sxx[i] = -1e3 * a;
    p.syy[i] = -2e3 * a;
    p.szz[i] = -3e3 * a;
    p.sxy[i] = 5 * a;
    p.xi[i] = a * a;
    p.gamma_dot[i] = 1e-3 * a;
    p.su[i] = 1e3 + a;
    p.body[i] = i % 3;
    p.material[i] = i % 2;
    p.id[i] = 1000000007LL * i;
  }
  return p;
}

const runout::FrameInfo kInfo{2.5, 0.125, {-10.0, 0.5, 50.0, -3.0, 90.0, -3.5}, {}};

// The frame of `p` as the engine writes it, as text.
std::string frame_text(const ScratchFolder& dir, const runout::Particles& p, bool compress) {
  const std::string path = (dir.path() / "frame.vtu").string();
  runout::write_particles_vtu(path, p, kInfo, compress);
  return read_file(path);
}

template <class Values>
void expect_array(const VtuFrame& f, const char* name, const std::string& type, int components,
                  const Values& expected) {
  const std::vector<double> values(expected.begin(), expected.end());
  SCOPED_TRACE(name);
  const VtuArray* a = f.point_array(name);
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(a->type, type);
  EXPECT_EQ(a->components, components);
  EXPECT_EQ(a->values, values);  // bit for bit
}

// The message VtuReadError gives for `xml`, "" when it reads.
std::string refusal(const std::string& xml) {
  try {
    runout::parse_vtu_frame(xml);
  } catch (const VtuReadError& e) {
    return e.what();
  }
  return "";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

}  // namespace

TEST(Base64Decode, DecodesWhatItEncodes) {
  for (const std::string bytes : {"", "f", "fo", "foo", "foob", "fooba", "foobar"})
    EXPECT_EQ(runout::base64_decode(runout::base64_encode(bytes.data(), bytes.size())), bytes);
  EXPECT_EQ(runout::base64_decode("Zm9vYg=="), "foob");  // RFC 4648 s. 10
  std::string all;
  for (int c = 0; c < 256; ++c) all += static_cast<char>(c);
  EXPECT_EQ(runout::base64_decode(runout::base64_encode(all.data(), all.size())), all);
}

TEST(Base64Decode, RefusesWhatItDoesNotWrite) {
  EXPECT_THROW(runout::base64_decode("Zm9"), std::invalid_argument);         // not 4n characters
  EXPECT_THROW(runout::base64_decode("Zm9v!A=="), std::invalid_argument);    // not the alphabet
  EXPECT_THROW(runout::base64_decode("Zg==Zm9v"), std::invalid_argument);    // padding inside
  EXPECT_THROW(runout::base64_decode("Z==="), std::invalid_argument);
  EXPECT_THROW(runout::base64_decode("Zm9v\nZm9v"), std::invalid_argument);  // whitespace
}

TEST(VtkXmlDecode, RoundTripsEveryBlockLayout) {
  // None, one partial, one full, a full and a partial, several blocks.
  for (const std::size_t size : {0, 1, 1000, 32768, 32769, 100000}) {
    std::vector<std::uint8_t> bytes(size);
    for (std::size_t k = 0; k < size; ++k) bytes[k] = static_cast<std::uint8_t>(k * 7919 >> 3);
    const std::string want(bytes.begin(), bytes.end());
    for (const bool compressed : {false, true}) {
      SCOPED_TRACE(std::to_string(size) + (compressed ? " zlib" : " raw"));
      const std::string text = runout::vtk_xml::encode(bytes.data(), size, compressed);
      EXPECT_EQ(runout::vtk_xml::decode(text, size, compressed), want);
      // The attributes' size must be the one the header gives.
      EXPECT_THROW(runout::vtk_xml::decode(text, size + 1, compressed), std::runtime_error);
    }
  }
}

TEST(VtkXmlDecode, SpoiltDataIsRefusedNotAllocated) {
  std::vector<double> values(20000);
  for (std::size_t k = 0; k < values.size(); ++k) values[k] = std::sqrt(double(k));
  const std::size_t size = values.size() * sizeof(double);
  const std::string zlib = runout::vtk_xml::encode(values.data(), size, true);
  // A size far beyond what the text could inflate to: refused up front.
  try {
    runout::vtk_xml::decode(zlib, std::size_t{1} << 50, true);
    ADD_FAILURE() << "decoded 2^50 bytes";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("more than"), std::string::npos) << e.what();
  }
  // A changed character in the compressed data, and one that is not base64.
  std::string spoilt = zlib;
  spoilt[zlib.size() / 2] = spoilt[zlib.size() / 2] == 'A' ? 'B' : 'A';
  EXPECT_THROW(runout::vtk_xml::decode(spoilt, size, true), std::runtime_error);
  spoilt[zlib.size() / 2] = '!';
  try {
    runout::vtk_xml::decode(spoilt, size, true);
    ADD_FAILURE() << "decoded a '!'";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("not base64"), std::string::npos) << e.what();
  }
  EXPECT_THROW(runout::vtk_xml::decode(zlib.substr(0, zlib.size() - 8), size, true),
               std::runtime_error);
  // Padding inside the header's run (fuzz_frame_reader's first find: the
  // header was read past its end): within its first 24 bytes, and at the
  // end of a one-block header that needs only one '='.
  const double one = 1.0;
  std::string padded = runout::vtk_xml::encode(&one, sizeof one, true);
  ASSERT_EQ(padded[43], '=');
  padded.replace(30, 2, "==");
  EXPECT_THROW(runout::vtk_xml::decode(padded, sizeof one, true), std::runtime_error);
  padded = runout::vtk_xml::encode(&one, sizeof one, true);
  padded[42] = '=';
  EXPECT_THROW(runout::vtk_xml::decode(padded, sizeof one, true), std::runtime_error);
  EXPECT_THROW(runout::vtk_xml::decode(zlib.substr(0, 20), size, true), std::runtime_error);
}

TEST(VtuReader, RoundTripsTheEnginesFrameCompressedAndNot) {
  ScratchFolder dir;
  // 5000 particles: the vector arrays span four zlib blocks of 32 KiB.
  const runout::Particles p = particles(5000);
  const int n = p.size();
  auto xyz = [&](const auto& a, const auto& b) {
    std::vector<double> out;
    for (int i = 0; i < n; ++i) out.insert(out.end(), {a[i], b[i], 0.0});
    return out;
  };
  for (const bool compress : {false, true}) {
    SCOPED_TRACE(compress ? "compressed" : "raw");
    const VtuFrame f = runout::parse_vtu_frame(frame_text(dir, p, compress));
    EXPECT_EQ(f.points, 5000u);
    EXPECT_EQ(f.cells, 5000u);
    EXPECT_EQ(f.positions.values, xyz(p.x, p.y));
    EXPECT_EQ(f.positions.type, "Float64");
    expect_array(f, "velocity", "Float64", 3, xyz(p.vx, p.vy));
    std::vector<double> dx(n), dy(n), stress;
    for (int i = 0; i < n; ++i) {
      dx[i] = p.x[i] - p.x0[i];
      dy[i] = p.y[i] - p.y0[i];
      stress.insert(stress.end(), {p.sxx[i], p.syy[i], p.szz[i], p.sxy[i], 0.0, 0.0});
    }
    expect_array(f, "displacement", "Float64", 3, xyz(dx, dy));
    expect_array(f, "stress", "Float64", 6, stress);
    expect_array(f, "plastic_shear_strain", "Float64", 1, p.xi);
    expect_array(f, "shear_strain_rate", "Float64", 1, p.gamma_dot);
    expect_array(f, "strength", "Float64", 1, p.su);
    expect_array(f, "mass", "Float64", 1, p.mass);
    expect_array(f, "volume", "Float64", 1, p.vol);
    expect_array(f, "initial_volume", "Float64", 1, p.vol0);
    expect_array(f, "initial_position", "Float64", 3, xyz(p.x0, p.y0));
    expect_array(f, "body_id", "Int32", 1, std::vector<double>(p.body.begin(), p.body.end()));
    expect_array(f, "material_id", "Int32", 1,
                 std::vector<double>(p.material.begin(), p.material.end()));
    expect_array(f, "particle_id", "Int64", 1, std::vector<double>(p.id.begin(), p.id.end()));
    for (const char* name : {"mean_stress", "von_mises_stress", "max_shear_stress"})
      EXPECT_NE(f.point_array(name), nullptr) << name;
    EXPECT_EQ(f.point_array("rate_factor"), nullptr);  // no strengths in kInfo

    ASSERT_NE(f.field_array("TimeValue"), nullptr);
    EXPECT_EQ(f.field_array("TimeValue")->values, std::vector<double>{2.5});
    EXPECT_EQ(f.field_array("particle_spacing")->values, std::vector<double>{0.125});
    EXPECT_EQ(f.field_array("base_points")->components, 3);
    EXPECT_EQ(f.field_array("base_points")->values,
              (std::vector<double>{-10.0, 0.5, 0.0, 50.0, -3.0, 0.0, 90.0, -3.5, 0.0}));
    EXPECT_EQ(f.cell_arrays.at("types").type, "UInt8");
    EXPECT_EQ(f.cell_arrays.at("types").values, std::vector<double>(n, 1.0));
    EXPECT_EQ(f.cell_arrays.at("offsets").values.back(), n);
  }
}

TEST(VtuReader, FrameWithoutParticles) {
  ScratchFolder dir;
  for (const bool compress : {false, true}) {
    const VtuFrame f = runout::parse_vtu_frame(frame_text(dir, runout::Particles(), compress));
    EXPECT_EQ(f.points, 0u);
    EXPECT_TRUE(f.positions.values.empty());
    ASSERT_NE(f.point_array("mass"), nullptr);
    EXPECT_TRUE(f.point_array("mass")->values.empty());
  }
}

TEST(VtuReader, ReadsFilesNamingThePathOfOneItCannot) {
  ScratchFolder dir;
  const std::string path = (dir.path() / "frame.vtu").string();
  runout::write_particles_vtu(path, particles(3), kInfo, true);
  EXPECT_EQ(runout::read_vtu_frame(path).points, 3u);
  const std::string missing = (dir.path() / "none.vtu").string();
  try {
    runout::read_vtu_frame(missing);
    ADD_FAILURE() << "read a missing file";
  } catch (const VtuReadError& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
  dir.write("cut.vtu", read_file(path).substr(0, 700));
  try {
    runout::read_vtu_frame((dir.path() / "cut.vtu").string());
    ADD_FAILURE() << "read a cut frame";
  } catch (const VtuReadError& e) {
    EXPECT_NE(std::string(e.what()).find("cut.vtu: "), std::string::npos) << e.what();
  }
}

// The layouts VTK writes that the engine does not, each refused saying so.
TEST(VtuReader, RefusesOtherLayoutsSayingWhich) {
  ScratchFolder dir;
  const std::string raw = frame_text(dir, particles(10), false);
  const std::string zlib = frame_text(dir, particles(10), true);
  ASSERT_EQ(refusal(raw), "");
  ASSERT_EQ(refusal(zlib), "");
  const struct {
    std::string xml, says;
  } cases[] = {
      {replaced(raw, "format=\"binary\"", "format=\"ascii\""), "format=\"ascii\""},
      {replaced(raw, "format=\"binary\"", "format=\"appended\" offset=\"0\""),
       "format=\"appended\""},
      {replaced(raw, "</VTKFile>", "<AppendedData encoding=\"raw\">_</AppendedData></VTKFile>"),
       "appended data"},
      {replaced(raw, "header_type=\"UInt64\"", "header_type=\"UInt32\""), "header_type UInt32"},
      {replaced(raw, " header_type=\"UInt64\"", ""), "header_type (none, so UInt32)"},
      {replaced(raw, "LittleEndian", "BigEndian"), "byte_order BigEndian"},
      {replaced(zlib, "vtkZLibDataCompressor", "vtkLZ4DataCompressor"),
       "compressor vtkLZ4DataCompressor"},
      {replaced(raw, "type=\"UnstructuredGrid\"", "type=\"PolyData\""), "a VTK PolyData file"},
      {replaced(raw, "type=\"Float64\"", "type=\"Float32\""), "type Float32"},
      {replaced(replaced(raw, "<VTKFile", "<Other"), "</VTKFile>", "</Other>"),
       "root element is <Other>"},
      {replaced(raw, "<PointData>", "<CellData/><PointData>"), "<CellData> in <Piece>"},
      {replaced(raw, "<DataArray type=\"Float64\" Name=\"velocity\"", "<Array type=\"Float64\" Name=\"velocity\""),
       "not well-formed"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.says);
    const std::string message = refusal(c.xml);
    EXPECT_NE(message.find(c.says), std::string::npos) << message;
  }
}

// Frames spoilt on disk or by hand: refused, never read as something else.
TEST(VtuReader, RefusesWhatDoesNotAddUp) {
  ScratchFolder dir;
  const runout::Particles p = particles(10);
  for (const bool compress : {false, true}) {
    SCOPED_TRACE(compress ? "compressed" : "raw");
    const std::string xml = frame_text(dir, p, compress);
    const struct {
      std::string xml, says;
    } cases[] = {
        // A velocity of 9 tuples in a frame of 10 points.
        {replaced(xml, "Name=\"velocity\" NumberOfComponents=\"3\" NumberOfTuples=\"10\"",
                  "Name=\"velocity\" NumberOfComponents=\"3\" NumberOfTuples=\"9\""),
         "\"velocity\" cannot be decoded"},
        // A count far beyond the data: refused, not allocated.
        {replaced(xml, "Name=\"mass\" NumberOfComponents=\"1\" NumberOfTuples=\"10\"",
                  "Name=\"mass\" NumberOfComponents=\"1\" NumberOfTuples=\"99999999999\""),
         "\"mass\" cannot be decoded"},
        {replaced(xml, "NumberOfTuples=\"10\"", "NumberOfTuples=\"ten\""), "is not a count"},
        {replaced(xml, "NumberOfPoints=\"10\"", "NumberOfPoints=\"11\""), "tuples for 11"},
        {replaced(xml, "Name=\"volume\"", "Name=\"mass\""), "two arrays named \"mass\""},
        {replaced(xml, "Name=\"connectivity\"", "Name=\"links\""), "no \"connectivity\""},
        {xml.substr(0, xml.size() / 2), "not well-formed"},
        {replaced(xml, "</Piece>", "</Peace>"), "not well-formed"},
        {xml + "<VTKFile/>", "text after the root element"},
        {replaced(xml, "<Points>", "<!-- a comment --><Points>"), "comment"},
    };
    for (const auto& c : cases) {
      SCOPED_TRACE(c.says);
      const std::string message = refusal(c.xml);
      EXPECT_NE(message.find(c.says), std::string::npos) << message;
    }
    // One base64 character of the positions changed: not base64, or data
    // that no longer adds up (a raw array decodes to other numbers of the
    // same size, which only the manifest's CRC-32 can catch).
    std::string spoilt = xml;
    const auto points = spoilt.find("Name=\"Points\"");
    const auto text = spoilt.find('>', points) + 20;
    spoilt[text] = '*';
    EXPECT_NE(refusal(spoilt).find("not base64"), std::string::npos) << refusal(spoilt);
  }
}
