#pragma once
// VTK XML UnstructuredGrid (.vtu) frames of the particles and the .pvd
// index of a series. Arrays are inline binary (base64, optionally zlib):
// never appended data, which Debian 12's expat breaks in VTK 9.2
// (../shared/BUILD.md). Every file is written to a temporary name and
// renamed, so a killed run never leaves a half-written file.
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "runout/mpm/particles.hpp"
#include "runout/mpm/strength.hpp"

namespace runout {

// What a frame carries besides the particles, as field data, so that the
// ParaView filters can measure along the base without the scene file.
struct FrameInfo {
  double time = 0;              // TimeValue
  double particle_spacing = 0;  // h / ppc: particle_spacing (omitted when 0)
  std::vector<double> base_xy;  // the base as a polyline x0, y0, x1, y1, ...:
                                // base_points (omitted when empty)
  // The strength law of each material: with it the frame carries each
  // particle's rate factor R(gamma_dot) as rate_factor (omitted when empty).
  std::vector<StrengthParams> strengths;
  // Whether the particles carry the clay's basal band ([base] clay_band):
  // its shear as band_shear_strain (omitted otherwise).
  bool clay_band = false;
};

// One frame: every particle field, plus displacement, the stress tensor and
// its mean and deviatoric invariants (see docs/output.md).
void write_particles_vtu(const std::string& path, const Particles& particles,
                         const FrameInfo& info, bool compress);

// The .pvd index of a frame series. add() appends a frame and rewrites the
// index atomically, so the index on disk always lists whole frames only;
// beside it, <index>.manifest gives each listed frame's size and CRC-32
// (docs/output.md), written before the index that lists the frame.
class PvdIndex {
 public:
  using Entries = std::vector<std::pair<double, std::string>>;  // time, file
  // With entries (a resumed run's), the index is written at once, with
  // `records` as their manifest lines where there is one per entry (a
  // resume has just checked them against the files), else each frame's
  // read from disk.
  explicit PvdIndex(std::string path, Entries entries = {},
                    std::vector<std::string> records = {});
  void add(double time, const std::string& relative_file);
  const std::string& path() const { return path_; }
  const Entries& entries() const { return frames_; }
  // Each entry's manifest line, as entries().
  const std::vector<std::string>& records() const { return manifest_; }

 private:
  void write() const;
  std::string path_;
  Entries frames_;
  std::vector<std::string> manifest_;  // one line per frame, as frames_
};

inline std::string manifest_path(const std::string& pvd_path) { return pvd_path + ".manifest"; }

// The manifest line ("file size crc32") of frame `file` in `folder` as it
// is on disk now; "file 0 unreadable" when it cannot be read.
std::string frame_record(const std::string& folder, const std::string& file);

// The (time, file) entries of the .pvd at pvd_path, in order; a time that
// does not parse is NaN. Throws std::runtime_error when it cannot be read.
PvdIndex::Entries read_pvd_entries(const std::string& pvd_path);

// The manifest beside an index, to check the frames it lists one by one.
class FrameManifest {
 public:
  // Throws std::runtime_error when the manifest cannot be read.
  explicit FrameManifest(const std::string& pvd_path);
  // What is wrong with the listed frame `file` whose bytes on disk are
  // `bytes`: not listed in the manifest, its size, its checksum; "" when it
  // matches.
  std::string problem(const std::string& file, const std::string& bytes) const;
  // The same for the file as it is on disk now ("missing" when it is not).
  std::string problem(const std::string& file) const;

 private:
  struct Sum {
    std::uint64_t size = 0;
    std::string crc;
  };
  std::string folder_;
  std::map<std::string, Sum> recorded_;
};

// Reads frame `file`, as an index in `folder` lists it, into `bytes` and
// checks those bytes against `manifest` where there is one (nullptr: a run
// without one): what is wrong with the frame ("missing", "cannot be read",
// "does not match the manifest: ..."), "" when its bytes can be parsed.
// `runout analyse` and the ParaView series reader parse the very bytes
// checked.
std::string read_listed_frame(const std::string& folder, const std::string& file,
                              const FrameManifest* manifest, std::string& bytes);

// The frames of the .pvd at pvd_path that do not match its manifest, each
// "file: why" (missing, not listed in the manifest, size, checksum); empty
// when every listed frame is whole. Throws std::runtime_error when the
// index or its manifest cannot be read.
std::vector<std::string> verify_frames(const std::string& pvd_path);

}  // namespace runout
