#include <cstdio>

#include "runout/atomic_file.hpp"
#include "runout/vtu_writer.hpp"

namespace runout {

namespace {

// The caller names the files; escape what would break the attribute.
std::string xml_attribute(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace

PvdIndex::PvdIndex(std::string path, Entries entries)
    : path_(std::move(path)), frames_(std::move(entries)) {
  if (!frames_.empty()) write();
}

void PvdIndex::add(double time, const std::string& relative_file) {
  frames_.emplace_back(time, relative_file);
  write();
}

void PvdIndex::write() const {
  std::string xml =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const auto& [t, file] : frames_) {
    // 17 significant digits: the time reads back as the same double.
    char timestep[32];
    std::snprintf(timestep, sizeof timestep, "%.17g", t);
    xml += "    <DataSet timestep=\"";
    xml += timestep;
    xml += "\" group=\"\" part=\"0\" file=\"" + xml_attribute(file) + "\"/>\n";
  }
  xml += "  </Collection>\n</VTKFile>\n";
  write_file_atomically(path_, xml);
}

}  // namespace runout
