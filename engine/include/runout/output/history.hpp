#pragma once
// history.csv: one row per history time, appended and flushed as the run
// goes, so a killed run keeps every row it computed. Columns in
// docs/output.md; the morphology ones are defined in docs/morphology.md.
// Every method (MPM, the depth-averaged model) writes the same columns.
#include <cmath>
#include <string>
#include <string_view>

#include "runout/measure/morphology.hpp"
#include "runout/mpm/particles.hpp"

namespace runout {

// One row, in column order.
struct HistoryRow {
  double time = 0;
  long step = 0;
  double dt = 0;
  double toe = 0, toe_velocity = 0, runout = 0, rear = 0, length = 0, max_thickness = 0;
  double centroid_x = 0, centroid_y = 0, centroid_s = 0, centroid_velocity = 0;
  double max_speed = 0, kinetic_energy = 0, basal_shear_force = 0, outside_mass = 0;
  double momentum_x = 0, momentum_y = 0;
  double basal_fill = NAN;  // basal_fill.hpp; NaN for the depth-averaged model
  double runout_95 = 0;     // the mass front (morphology.hpp) past the toe at t = 0
  double remoulded_mass = NAN;  // remoulded_mass.hpp; NaN for the depth-averaged model
};

// The row of an MPM run (CPU or CUDA) from its particles on the host and
// their morphology; initial_toe: the main body's toe at t = 0, from which
// runout (the toe's) and runout_95 (the mass front's) are measured;
// basal_fill: basal_fill.hpp; remoulded_mass: remoulded_mass.hpp.
HistoryRow mpm_history_row(const Particles& particles, const SlideMorphology& shape,
                           double initial_toe, double time, long step, double dt,
                           double basal_shear_force, double basal_fill,
                           double remoulded_mass);

// history.csv's header and first `rows` rows (a resumed run's rows up to
// its checkpoint), without whatever a killed run wrote after them, a torn
// last line included; the caller writes them back. Throws
// std::runtime_error when the file is missing, holds fewer rows, or has
// another header than this build writes.
std::string first_history_rows(const std::string& path, long rows);

class HistoryWriter {
 public:
  // Writes the header, or with append (a resumed run) goes on after the
  // rows the file holds.
  explicit HistoryWriter(const std::string& path, bool append = false);
  ~HistoryWriter();
  HistoryWriter(const HistoryWriter&) = delete;
  HistoryWriter& operator=(const HistoryWriter&) = delete;

  // Appends a whole row or, when the write fails (a full disk), none:
  // throws std::runtime_error with the reason, the file cut back to its
  // last whole row.
  void append(const HistoryRow& row);
  // The rows so far on the disk (fsync), before a checkpoint counts them.
  void sync();

 private:
  void write_whole(std::string_view line);
  std::string path_;
  int fd_;
};

}  // namespace runout
