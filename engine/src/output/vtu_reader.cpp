// The frames of vtu_writer.cpp read back, element by element as it writes
// them: a small XML scanner for that one layout (no entities, comments or
// mixed content, which the writer never produces), then the arrays through
// vtk_xml::decode. Round-tripped in tests/test_vtu_reader.cpp.
#include "runout/output/vtu_reader.hpp"

#include <charconv>
#include <cstdint>
#include <cstring>
#include <limits>
#include <utility>

#include "runout/output/file_text.hpp"
#include "runout/output/vtk_xml.hpp"

namespace runout {

namespace {

// Deeper than any frame (VTKFile, UnstructuredGrid, Piece, PointData,
// DataArray): a bound on the recursion for text that is not one.
constexpr int kMaxDepth = 8;

struct Element {
  std::string_view name;
  std::vector<std::pair<std::string_view, std::string_view>> attributes;
  std::vector<Element> children;
  std::string_view text;  // the character data of an element without children

  const std::string_view* attribute(std::string_view key) const {
    for (const auto& [k, v] : attributes)
      if (k == key) return &v;
    return nullptr;
  }
};

bool is_space(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; }
bool is_name_char(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
}

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
  return text;
}

class XmlScanner {
 public:
  explicit XmlScanner(std::string_view xml) : xml_(xml) {}

  // The root element, after an optional <?xml ...?> declaration.
  Element document() {
    skip_space();
    if (xml_.compare(at_, 5, "<?xml") == 0) {
      const std::size_t end = xml_.find("?>", at_);
      if (end == std::string_view::npos) fail("an unterminated <?xml declaration");
      at_ = end + 2;
    }
    skip_space();
    Element root = element(0);
    skip_space();
    if (at_ != xml_.size()) fail("text after the root element");
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw VtuReadError("not well-formed XML at byte " + std::to_string(at_) + ": " + what);
  }
  void skip_space() {
    while (at_ < xml_.size() && is_space(xml_[at_])) ++at_;
  }
  void expect(char c) {
    if (at_ >= xml_.size() || xml_[at_] != c) fail(std::string("expected '") + c + "'");
    ++at_;
  }
  std::string_view name() {
    const std::size_t start = at_;
    while (at_ < xml_.size() && is_name_char(xml_[at_])) ++at_;
    if (at_ == start) fail("expected a name");
    return xml_.substr(start, at_ - start);
  }

  Element element(int depth) {
    if (depth > kMaxDepth) fail("elements nested deeper than a frame's");
    Element e;
    expect('<');
    e.name = name();
    for (;;) {
      skip_space();
      if (xml_.compare(at_, 2, "/>") == 0) {
        at_ += 2;
        return e;
      }
      if (at_ < xml_.size() && xml_[at_] == '>') break;
      const std::string_view key = name();
      skip_space();
      expect('=');
      skip_space();
      expect('"');
      const std::size_t end = xml_.find('"', at_);
      if (end == std::string_view::npos) fail("an unterminated attribute value");
      e.attributes.emplace_back(key, xml_.substr(at_, end - at_));
      at_ = end + 1;
    }
    ++at_;  // '>'
    for (;;) {
      const std::size_t end = xml_.find('<', at_);
      if (end == std::string_view::npos) fail("<" + std::string(e.name) + "> is not closed");
      const std::string_view text = xml_.substr(at_, end - at_);
      at_ = end;
      if (xml_.compare(at_, 2, "</") == 0) {
        if (e.children.empty()) e.text = text;
        else if (!trimmed(text).empty()) fail("text between elements");
        at_ += 2;
        if (name() != e.name) fail("</...> does not close <" + std::string(e.name) + ">");
        skip_space();
        expect('>');
        return e;
      }
      if (!trimmed(text).empty()) fail("text between elements");
      if (xml_.compare(at_, 2, "<!") == 0 || xml_.compare(at_, 2, "<?") == 0)
        fail("a comment, CDATA or processing instruction, which the engine never writes");
      e.children.push_back(element(depth + 1));
    }
  }

  std::string_view xml_;
  std::size_t at_ = 0;
};

// Reading one frame: its compression, and the errors it raises.
struct FrameParser {
  bool compressed = false;

  [[noreturn]] static void refuse(const std::string& what) { throw VtuReadError(what); }

  static std::string_view required(const Element& e, std::string_view key) {
    const std::string_view* value = e.attribute(key);
    if (!value) refuse("<" + std::string(e.name) + "> has no " + std::string(key) + " attribute");
    return *value;
  }

  static std::size_t count(const Element& e, std::string_view key) {
    const std::string_view text = required(e, key);
    std::uint64_t value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size() ||
        value > std::numeric_limits<std::uint32_t>::max() * std::uint64_t{64})
      refuse("<" + std::string(e.name) + "> " + std::string(key) + "=\"" + std::string(text) +
             "\" is not a count");
    return static_cast<std::size_t>(value);
  }

  // Each child of `e` that is one of `names`, at most once each.
  static std::map<std::string_view, const Element*> sections(
      const Element& e, std::initializer_list<std::string_view> names) {
    std::map<std::string_view, const Element*> found;
    for (const Element& child : e.children) {
      if (child.name == "AppendedData")
        refuse("appended data (<AppendedData>): only the inline binary arrays the engine "
               "writes are read (docs/output.md, \"Frame format\")");
      bool known = false;
      for (const std::string_view n : names) known |= child.name == n;
      if (!known)
        refuse("<" + std::string(child.name) + "> in <" + std::string(e.name) +
               ">, which the engine never writes there");
      if (!found.emplace(child.name, &child).second)
        refuse("more than one <" + std::string(child.name) + "> in <" + std::string(e.name) + ">");
    }
    return found;
  }

  template <class T>
  static void append_values(const std::string& bytes, std::vector<double>& out) {
    std::vector<T> typed(bytes.size() / sizeof(T));
    std::memcpy(typed.data(), bytes.data(), typed.size() * sizeof(T));
    out.assign(typed.begin(), typed.end());
  }

  VtuArray array(const Element& e, std::string& name) const {
    if (e.name != "DataArray") {
      std::string what = "<";
      what += e.name;
      what += "> where the engine writes a <DataArray>";
      refuse(what);
    }
    name = std::string(required(e, "Name"));
    const std::string quoted = "the array \"" + name + "\"";
    const std::string_view format = required(e, "format");
    if (format != "binary")
      refuse(quoted + " is format=\"" + std::string(format) +
             "\": only the inline binary arrays the engine writes are read");
    VtuArray a;
    a.type = std::string(required(e, "type"));
    const std::size_t size = a.type == "Float64" || a.type == "Int64" ? 8
                             : a.type == "Int32"                      ? 4
                             : a.type == "UInt8"                      ? 1
                                                                      : 0;
    if (size == 0)
      refuse(quoted + " is of type " + a.type +
             ", not one the engine writes (Float64, Int32, Int64, UInt8)");
    const std::size_t components = e.attribute("NumberOfComponents") ? count(e, "NumberOfComponents") : 1;
    if (components < 1 || components > 64)
      refuse(quoted + " has " + std::to_string(components) + " components");
    a.components = static_cast<int>(components);
    const std::size_t tuples = count(e, "NumberOfTuples");
    std::string bytes;
    try {
      bytes = vtk_xml::decode(trimmed(e.text), tuples * components * size, compressed);
    } catch (const std::runtime_error& error) {
      refuse(quoted + " cannot be decoded: " + error.what());
    }
    if (a.type == "Float64") append_values<double>(bytes, a.values);
    if (a.type == "Int64") append_values<std::int64_t>(bytes, a.values);
    if (a.type == "Int32") append_values<std::int32_t>(bytes, a.values);
    if (a.type == "UInt8") append_values<std::uint8_t>(bytes, a.values);
    return a;
  }

  // The arrays of a <FieldData>, <PointData> or <Cells>, each with
  // `tuples` tuples unless that is 0.
  std::map<std::string, VtuArray> arrays(const Element* section, std::size_t tuples) const {
    std::map<std::string, VtuArray> out;
    if (!section) return out;
    for (const Element& child : section->children) {
      std::string name;
      VtuArray a = array(child, name);
      if (tuples > 0 && a.tuples() != tuples)
        refuse("the array \"" + name + "\" has " + std::to_string(a.tuples()) + " tuples for " +
               std::to_string(tuples) + " in <" + std::string(section->name) + ">");
      if (!out.emplace(name, std::move(a)).second)
        refuse("two arrays named \"" + name + "\" in <" + std::string(section->name) + ">");
    }
    return out;
  }

  VtuFrame frame(const Element& root) {
    if (root.name != "VTKFile")
      refuse("not a VTK XML file: its root element is <" + std::string(root.name) + ">");
    const std::string_view type = required(root, "type");
    if (type != "UnstructuredGrid")
      refuse("a VTK " + std::string(type) +
             " file, not a particle frame (an UnstructuredGrid, as `runout run` writes for "
             "the MPM)");
    const std::string_view* order = root.attribute("byte_order");
    if (!order || *order != "LittleEndian")
      refuse("byte_order " + std::string(order ? *order : "(none)") +
             ": the engine writes LittleEndian");
    const std::string_view* header = root.attribute("header_type");
    if (!header || *header != "UInt64")
      refuse("header_type " + std::string(header ? *header : "(none, so UInt32)") +
             ": the engine writes UInt64 headers");
    const std::string_view* compressor = root.attribute("compressor");
    if (compressor && *compressor != "vtkZLibDataCompressor")
      refuse("compressor " + std::string(*compressor) +
             ": the engine writes zlib (vtkZLibDataCompressor) or none");
    compressed = compressor != nullptr;

    const auto top = sections(root, {"UnstructuredGrid"});
    if (top.empty()) refuse("no <UnstructuredGrid>");
    const Element& grid = *top.at("UnstructuredGrid");
    const auto parts = sections(grid, {"FieldData", "Piece"});
    if (!parts.count("Piece")) refuse("no <Piece>");
    const Element& piece = *parts.at("Piece");
    const auto data = sections(piece, {"PointData", "Points", "Cells"});
    if (!data.count("Points")) refuse("no <Points>");
    if (!data.count("Cells")) refuse("no <Cells>");

    VtuFrame f;
    f.points = count(piece, "NumberOfPoints");
    f.cells = count(piece, "NumberOfCells");
    const auto field = parts.find("FieldData");
    f.field_data = arrays(field == parts.end() ? nullptr : field->second, 0);
    const auto point_data = data.find("PointData");
    f.point_data = arrays(point_data == data.end() ? nullptr : point_data->second, f.points);
    f.cell_arrays = arrays(data.at("Cells"), 0);
    for (const char* name : {"connectivity", "offsets", "types"})
      if (!f.cell_arrays.count(name)) refuse(std::string("<Cells> has no \"") + name + "\" array");
    if (f.cell_arrays.at("types").tuples() != f.cells || f.cell_arrays.at("offsets").tuples() != f.cells)
      refuse("<Cells> does not hold NumberOfCells=\"" + std::to_string(f.cells) + "\" cells");

    const Element& points = *data.at("Points");
    if (points.children.size() != 1) refuse("<Points> does not hold exactly one <DataArray>");
    std::string name;
    f.positions = array(points.children[0], name);
    if (f.positions.components != 3 || f.positions.tuples() != f.points)
      refuse("the Points array is not " + std::to_string(f.points) + " (x, y, z) tuples");
    return f;
  }
};

}  // namespace

const VtuArray* VtuFrame::point_array(const std::string& name) const {
  const auto it = point_data.find(name);
  return it == point_data.end() ? nullptr : &it->second;
}

const VtuArray* VtuFrame::field_array(const std::string& name) const {
  const auto it = field_data.find(name);
  return it == field_data.end() ? nullptr : &it->second;
}

VtuFrame parse_vtu_frame(std::string_view xml) {
  return FrameParser().frame(XmlScanner(xml).document());
}

VtuFrame read_vtu_frame(const std::string& path) {
  const std::optional<std::string> xml = file_text(path);
  if (!xml) throw VtuReadError(path + ": cannot be read");
  try {
    return parse_vtu_frame(*xml);
  } catch (const VtuReadError& e) {
    throw VtuReadError(path + ": " + e.what());
  }
}

}  // namespace runout
