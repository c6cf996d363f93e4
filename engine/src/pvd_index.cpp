#include <zlib.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <stdexcept>

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

std::string read_whole(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
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
// A file that cannot be read (an index given a frame that is not there)
// is recorded as such, for verify to report, rather than failing the run.
FrameSum frame_sum(const std::string& folder, const std::string& file) {
  std::ifstream in(in_folder(folder, file), std::ios::binary);
  if (!in) return {0, "unreadable"};
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  char crc[16];
  std::snprintf(crc, sizeof crc, "%08lx", crc_of(bytes));
  return {bytes.size(), crc};
}

// "file size crc32".
std::string manifest_line(const std::string& folder, const std::string& file) {
  const FrameSum sum = frame_sum(folder, file);
  return file + " " + std::to_string(sum.size) + " " + sum.crc;
}

// The .pvd's file="..." entries, in order.
std::vector<std::string> listed_files(const std::string& pvd_text) {
  std::vector<std::string> files;
  const std::string key = "file=\"";
  for (auto at = pvd_text.find(key); at != std::string::npos; at = pvd_text.find(key, at)) {
    at += key.size();
    files.push_back(pvd_text.substr(at, pvd_text.find('"', at) - at));
  }
  return files;
}

}  // namespace

PvdIndex::PvdIndex(std::string path, Entries entries)
    : path_(std::move(path)), frames_(std::move(entries)) {
  for (const auto& entry : frames_) manifest_.push_back(manifest_line(folder_of(path_), entry.second));
  if (!frames_.empty()) write();
}

void PvdIndex::add(double time, const std::string& relative_file) {
  frames_.emplace_back(time, relative_file);
  manifest_.push_back(manifest_line(folder_of(path_), relative_file));
  write();
}

std::vector<std::string> verify_frames(const std::string& pvd_path) {
  const std::string folder = folder_of(pvd_path);
  std::map<std::string, FrameSum> recorded;
  std::istringstream manifest(read_whole(manifest_path(pvd_path)));
  std::string file;
  FrameSum sum;
  while (manifest >> file >> sum.size >> sum.crc) recorded[file] = sum;
  std::vector<std::string> bad;
  for (const std::string& listed : listed_files(read_whole(pvd_path))) {
    const auto it = recorded.find(listed);
    std::error_code ignored;
    if (!std::filesystem::is_regular_file(in_folder(folder, listed), ignored)) {
      bad.push_back(listed + ": missing");
      continue;
    }
    if (it == recorded.end()) {
      bad.push_back(listed + ": not in the manifest");
      continue;
    }
    const FrameSum now = frame_sum(folder, listed);
    if (now.size != it->second.size)
      bad.push_back(listed + ": " + std::to_string(now.size) + " bytes, the manifest says " +
                    std::to_string(it->second.size));
    else if (now.crc != it->second.crc)
      bad.push_back(listed + ": CRC-32 " + now.crc + ", the manifest says " + it->second.crc);
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
