#include "runout/history.hpp"

#include <unistd.h>

#include <fstream>
#include <stdexcept>

#include "runout/atomic_file.hpp"
#include "runout/diagnostics.hpp"

namespace runout {

HistoryWriter::HistoryWriter(const std::string& path, bool append)
    : path_(path), file_(std::fopen(path.c_str(), append ? "a" : "w")) {
  if (!file_) throw std::runtime_error("cannot write '" + path + "'");
  if (append) return;
  std::fputs(
      "time,step,dt,toe,toe_velocity,runout,rear,length,max_thickness,centroid_x,centroid_y,"
      "centroid_s,centroid_velocity,max_speed,kinetic_energy,basal_shear_force,outside_mass,"
      "momentum_x,momentum_y\n",
      file_);
  std::fflush(file_);
}

HistoryWriter::~HistoryWriter() { std::fclose(file_); }

void HistoryWriter::append(const HistoryRow& r) {
  const int ok = std::fprintf(
      file_,
      "%.17g,%ld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,"
      "%.17g,%.17g,%.17g,%.17g,%.17g\n",
      r.time, r.step, r.dt, r.toe, r.toe_velocity, r.runout, r.rear, r.length,
      r.max_thickness, r.centroid_x, r.centroid_y, r.centroid_s, r.centroid_velocity,
      r.max_speed, r.kinetic_energy, r.basal_shear_force, r.outside_mass, r.momentum_x,
      r.momentum_y);
  if (ok < 0 || std::fflush(file_) != 0) throw std::runtime_error("cannot write '" + path_ + "'");
}

void HistoryWriter::sync() {
  if (std::fflush(file_) != 0 || ::fsync(::fileno(file_)) != 0)
    throw std::runtime_error("cannot write '" + path_ + "'");
}

void keep_history_rows(const std::string& path, long rows) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read '" + path + "'");
  std::string kept, line;
  long lines = 0;
  // Only whole lines: a row's newline is written with it.
  while (lines <= rows && std::getline(in, line) && !in.eof()) {
    kept += line + '\n';
    ++lines;
  }
  if (lines <= rows)
    throw std::runtime_error("'" + path + "' holds " + std::to_string(lines - 1) +
                             " rows, fewer than the " + std::to_string(rows) +
                             " its checkpoint counts");
  write_file_atomically(path, kept);
}

HistoryRow mpm_history_row(const Particles& particles, const SlideMorphology& m, double runout,
                           double time, long step, double dt, double basal_shear_force) {
  const ParticleTotals t = particle_totals(particles);
  return HistoryRow{time,         step,           dt,           m.toe_s,
                    m.toe_velocity, runout,       m.rear_s,     m.length,
                    m.max_thickness, m.centroid_x, m.centroid_y, m.centroid_s,
                    m.centroid_velocity_s, m.max_speed, m.kinetic_energy, basal_shear_force,
                    m.outside_mass, t.momentum_x, t.momentum_y};
}

}  // namespace runout
