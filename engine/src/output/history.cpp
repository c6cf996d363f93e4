#include "runout/output/history.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "runout/output/atomic_file.hpp"
#include "runout/measure/diagnostics.hpp"

namespace runout {

namespace {

constexpr const char* kHeader =
    "time,step,dt,toe,toe_velocity,runout,rear,length,max_thickness,centroid_x,centroid_y,"
    "centroid_s,centroid_velocity,max_speed,kinetic_energy,basal_shear_force,outside_mass,"
    "momentum_x,momentum_y,basal_fill,runout_95,remoulded_mass\n";

std::string row_text(const HistoryRow& r) {
  char line[1024];
  std::snprintf(
      line, sizeof line,
      "%.17g,%ld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,"
      "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
      r.time, r.step, r.dt, r.toe, r.toe_velocity, r.runout, r.rear, r.length,
      r.max_thickness, r.centroid_x, r.centroid_y, r.centroid_s, r.centroid_velocity,
      r.max_speed, r.kinetic_energy, r.basal_shear_force, r.outside_mass, r.momentum_x,
      r.momentum_y, r.basal_fill, r.runout_95, r.remoulded_mass);
  return line;
}

}  // namespace

HistoryWriter::HistoryWriter(const std::string& path, bool append)
    : path_(path),
      fd_(::open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC | (append ? O_APPEND : O_TRUNC),
                 0666)) {
  if (fd_ < 0) throw std::runtime_error("cannot write '" + path + "': " + std::strerror(errno));
  if (append) return;
  try {
    write_whole(kHeader);
  } catch (...) {
    ::close(fd_);
    throw;
  }
}

HistoryWriter::~HistoryWriter() { ::close(fd_); }

void HistoryWriter::write_whole(std::string_view line) {
  const off_t before = ::lseek(fd_, 0, SEEK_END);
  if (before >= 0 && write_all(fd_, line)) return;
  const int error = errno;
  // The part of the line that reached the file goes again, so that the file
  // ends with a whole row whatever the disk let through.
  if (before >= 0 && ::ftruncate(fd_, before) != 0) {
    throw std::runtime_error("cannot write '" + path_ + "': " + std::strerror(error) +
                             ", and its torn last row could not be cut off: " +
                             std::strerror(errno));
  }
  throw std::runtime_error("cannot write '" + path_ + "': " + std::strerror(error));
}

void HistoryWriter::append(const HistoryRow& r) { write_whole(row_text(r)); }

void HistoryWriter::sync() {
  if (::fsync(fd_) != 0)
    throw std::runtime_error("cannot write '" + path_ + "': " + std::strerror(errno));
}

std::string first_history_rows(const std::string& path, long rows) {
  // A device behind the name (/dev/zero) would be one endless line.
  std::error_code ignored;
  if (!std::filesystem::is_regular_file(path, ignored))
    throw std::runtime_error("'" + path + "' is missing or not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read '" + path + "'");
  std::string kept, line;
  long lines = 0;
  // Only whole lines: a row's newline is written with it.
  while (lines <= rows && std::getline(in, line) && !in.eof()) {
    // Rows of this version's columns under another version's header would
    // be read by the header's names.
    if (lines == 0 && line + '\n' != kHeader)
      throw std::runtime_error("'" + path + "' has another version's columns (" +
                               line.substr(0, 200) + "); this build writes " +
                               std::string(kHeader, std::strlen(kHeader) - 1));
    kept += line + '\n';
    ++lines;
  }
  if (lines <= rows)
    throw std::runtime_error("'" + path + "' holds " + std::to_string(lines - 1) +
                             " rows, fewer than the " + std::to_string(rows) +
                             " its checkpoint counts");
  return kept;
}

HistoryRow mpm_history_row(const Particles& particles, const SlideMorphology& m,
                           double initial_toe, double time, long step, double dt,
                           double basal_shear_force, double basal_fill,
                           double remoulded_mass) {
  const ParticleTotals t = particle_totals(particles);
  return HistoryRow{time,
                    step,
                    dt,
                    m.toe_s,
                    m.toe_velocity,
                    runout_distance(m, initial_toe),
                    m.rear_s,
                    m.length,
                    m.max_thickness,
                    m.centroid_x,
                    m.centroid_y,
                    m.centroid_s,
                    m.centroid_velocity_s,
                    m.max_speed,
                    m.kinetic_energy,
                    basal_shear_force,
                    m.outside_mass,
                    t.momentum_x,
                    t.momentum_y,
                    basal_fill,
                    m.mass_front_s - initial_toe,
                    remoulded_mass};
}

}  // namespace runout
