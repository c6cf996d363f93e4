#include <zlib.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "runout/output/atomic_file.hpp"
#include "runout/output/file_text.hpp"
#include "runout/output/vtu_writer.hpp"

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

std::string folder_of(const std::string& pvd_path) {
  return std::filesystem::path(pvd_path).parent_path().string();
}

std::string in_folder(const std::string& folder, const std::string& file) {
  return (std::filesystem::path(folder) / file).string();
}

unsigned long crc_of(const std::string& bytes) {
  return crc32_z(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(bytes.data()),
                 bytes.size());
}

// A frame's size and CRC-32 as it is on disk now. Read back rather than
// taken from the writer: the manifest then vouches for what reached the
// file, whoever wrote it.
struct FrameSum {
  std::uint64_t size = 0;
  std::string crc;
};
FrameSum sum_of(const std::string& bytes) {
  char crc[16];
  std::snprintf(crc, sizeof crc, "%08lx", crc_of(bytes));
  return {bytes.size(), crc};
}
// A file that cannot be read (an index given a frame that is not there, or
// not a regular file) is recorded as such, for verify to report, rather
// than failing the run.
FrameSum frame_sum(const std::string& folder, const std::string& file) {
  // Only a regular file is a frame: a device behind the name would never end.
  const std::optional<std::string> bytes = regular_file_text(in_folder(folder, file));
  return bytes ? sum_of(*bytes) : FrameSum{0, "unreadable"};
}

// The value of attribute `key` in the element text `tag`, if it has one.
std::optional<std::string> attribute_of(const std::string& tag, const std::string& key) {
  const std::string start = " " + key + "=\"";
  const auto at = tag.find(start);
  if (at == std::string::npos) return std::nullopt;
  const auto begin = at + start.size(), end = tag.find('"', begin);
  if (end == std::string::npos) return std::nullopt;
  return tag.substr(begin, end - begin);
}

}  // namespace

std::string frame_record(const std::string& folder, const std::string& file) {
  const FrameSum sum = frame_sum(folder, file);
  return file + " " + std::to_string(sum.size) + " " + sum.crc;
}

PvdIndex::PvdIndex(std::string path, Entries entries, std::vector<std::string> records)
    : path_(std::move(path)), frames_(std::move(entries)), manifest_(std::move(records)) {
  if (manifest_.size() != frames_.size()) {
    manifest_.clear();
    for (const auto& entry : frames_)
      manifest_.push_back(frame_record(folder_of(path_), entry.second));
  }
  if (!frames_.empty()) write();
}

void PvdIndex::add(double time, const std::string& relative_file) {
  frames_.emplace_back(time, relative_file);
  manifest_.push_back(frame_record(folder_of(path_), relative_file));
  write();
}

PvdIndex::Entries read_pvd_entries(const std::string& pvd_path) {
  const std::string text = file_text_or_throw(pvd_path, "cannot read " + pvd_path);
  PvdIndex::Entries entries;
  for (auto at = text.find("<DataSet"); at != std::string::npos; at = text.find("<DataSet", at)) {
    const auto end = text.find('>', at);
    const std::string tag = text.substr(at, end == std::string::npos ? end : end - at);
    at += tag.size();
    const std::optional<std::string> file = attribute_of(tag, "file");
    if (!file) continue;
    const std::optional<std::string> time = attribute_of(tag, "timestep");
    char* parsed_to = nullptr;
    const double t = time ? std::strtod(time->c_str(), &parsed_to) : 0.0;
    const bool whole = time && !time->empty() && *parsed_to == '\0';
    entries.emplace_back(whole ? t : std::nan(""), *file);
  }
  return entries;
}

FrameManifest::FrameManifest(const std::string& pvd_path) : folder_(folder_of(pvd_path)) {
  const std::string path = manifest_path(pvd_path);
  std::istringstream manifest(file_text_or_throw(path, "cannot read " + path));
  std::string file;
  Sum sum;
  while (manifest >> file >> sum.size >> sum.crc) recorded_[file] = sum;
}

std::string FrameManifest::problem(const std::string& file, const std::string& bytes) const {
  const auto it = recorded_.find(file);
  if (it == recorded_.end()) return "not in the manifest";
  const FrameSum now = sum_of(bytes);
  if (now.size != it->second.size)
    return std::to_string(now.size) + " bytes, the manifest says " +
           std::to_string(it->second.size);
  if (now.crc != it->second.crc) return "CRC-32 " + now.crc + ", the manifest says " + it->second.crc;
  return "";
}

std::string FrameManifest::problem(const std::string& file) const {
  std::error_code ignored;
  if (!std::filesystem::is_regular_file(in_folder(folder_, file), ignored)) return "missing";
  if (!recorded_.count(file)) return "not in the manifest";
  const std::string path = in_folder(folder_, file);
  return problem(file, file_text_or_throw(path, "cannot read " + path));
}

std::string read_listed_frame(const std::string& folder, const std::string& file,
                              const FrameManifest* manifest, std::string& bytes) {
  const std::string path = in_folder(folder, file);
  std::optional<std::string> text = regular_file_text(path);
  std::error_code ignored;
  if (!text) return std::filesystem::exists(path, ignored) ? "cannot be read" : "missing";
  bytes = std::move(*text);
  if (!manifest) return "";
  const std::string mismatch = manifest->problem(file, bytes);
  return mismatch.empty() ? "" : "does not match the manifest: " + mismatch;
}

std::vector<std::string> verify_frames(const std::string& pvd_path) {
  const FrameManifest manifest(pvd_path);
  std::vector<std::string> bad;
  for (const auto& entry : read_pvd_entries(pvd_path)) {
    const std::string problem = manifest.problem(entry.second);
    if (!problem.empty()) bad.push_back(entry.second + ": " + problem);
  }
  return bad;
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
  std::string manifest;
  for (const std::string& line : manifest_) manifest += line + "\n";
  // The manifest first: every frame the index lists is in it.
  write_file_atomically(manifest_path(path_), manifest);
  write_file_atomically(path_, xml);
}

}  // namespace runout
