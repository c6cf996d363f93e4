#include "runout/history.hpp"

#include <stdexcept>

#include "runout/diagnostics.hpp"

namespace runout {

HistoryWriter::HistoryWriter(const std::string& path)
    : path_(path), file_(std::fopen(path.c_str(), "w")) {
  if (!file_) throw std::runtime_error("cannot write '" + path + "'");
  std::fputs("time,step,dt,kinetic_energy,momentum_x,momentum_y,max_speed\n", file_);
  std::fflush(file_);
}

HistoryWriter::~HistoryWriter() { std::fclose(file_); }

void HistoryWriter::append(const Simulation& sim) {
  const ParticleTotals t = particle_totals(sim.particles());
  const int ok = std::fprintf(file_, "%.17g,%ld,%.17g,%.17g,%.17g,%.17g,%.17g\n", sim.time(),
                              sim.steps(), sim.last_dt(), t.kinetic_energy, t.momentum_x,
                              t.momentum_y, t.max_speed);
  if (ok < 0 || std::fflush(file_) != 0) throw std::runtime_error("cannot write '" + path_ + "'");
}

}  // namespace runout
