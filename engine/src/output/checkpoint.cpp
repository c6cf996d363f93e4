#include "runout/output/checkpoint.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <optional>
#include <type_traits>

#include "runout/output/atomic_file.hpp"
#include "runout/run/memory_estimate.hpp"
#include "runout/scene/scene_parser.hpp"

namespace runout {
namespace {

// Numbers are stored as the host holds them; every machine the engine
// builds for is little-endian, which the file format fixes.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "checkpoints are little-endian");

constexpr char kMagic[8] = {'R', 'U', 'N', 'O', 'U', 'T', 'C', 'K'};
constexpr std::uint32_t kVersion = 5;  // 5: the particles carry their basal band
// magic, version, payload size; the payload; then its checksum.
constexpr std::size_t kHeaderBytes = sizeof kMagic + 4 + 8;
constexpr std::size_t kChecksumBytes = 8;

// FNV-1a, 64 bit (Fowler, Noll, Vo): catches a flipped bit or a torn write,
// which is all a checksum here is for.
std::uint64_t fnv1a(std::string_view bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ull;
  }
  return h;
}

class Writer {
 public:
  template <class T>
  void put(T value) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&value), sizeof value);
  }
  void put_text(std::string_view text) {
    put<std::uint64_t>(text.size());
    out_.append(text);
  }
  template <class T, class A>
  void put_array(const std::vector<T, A>& a) {
    out_.append(reinterpret_cast<const char*>(a.data()), a.size() * sizeof(T));
  }
  std::string& bytes() { return out_; }

 private:
  std::string out_;
};

// Reads the payload; any read past its end is a truncated file.
class Reader {
 public:
  Reader(std::string_view bytes, const std::string& source) : in_(bytes), source_(source) {}
  template <class T>
  T get() {
    T value;
    std::memcpy(&value, take(sizeof value), sizeof value);
    return value;
  }
  std::string get_text() {
    const std::uint64_t n = get<std::uint64_t>();
    if (n > in_.size() - pos_) fail("a text longer than the file");
    return std::string(take(n), n);
  }
  template <class T, class A>
  void get_array(std::vector<T, A>& a, std::size_t n) {
    a.resize(n);
    std::memcpy(a.data(), take(n * sizeof(T)), n * sizeof(T));
  }
  std::size_t left() const { return in_.size() - pos_; }
  [[noreturn]] void fail(const std::string& what) const {
    throw CheckpointError(source_ + ": " + what + " at byte " +
                          std::to_string(kHeaderBytes + pos_));
  }

 private:
  const char* take(std::size_t n) {
    if (n > left()) fail("truncated: the data ends");
    const char* p = in_.data() + pos_;
    pos_ += n;
    return p;
  }
  std::string_view in_;
  std::size_t pos_ = 0;
  const std::string& source_;
};

// Bytes of one particle: the double arrays, body and material, id.
constexpr std::size_t kParticleBytes = kParticleDoubles * 8 + 2 * 4 + 8;

void put_particles(Writer& w, const Particles& P) {
  w.put<std::uint64_t>(P.size());
  for (const auto* a : P.double_arrays()) w.put_array(*a);
  w.put_array(P.body);
  w.put_array(P.material);
  w.put_array(P.id);
}

Particles get_particles(Reader& r) {
  const std::uint64_t n = r.get<std::uint64_t>();
  // A run without particles has nothing to continue ("at rest" at once).
  if (n == 0) r.fail("no particles");
  if (n > r.left() / kParticleBytes) r.fail("more particles than the file holds");
  Particles P;
  for (auto* a : P.double_arrays()) r.get_array(*a, n);
  r.get_array(P.body, n);
  r.get_array(P.material, n);
  r.get_array(P.id, n);
  return P;
}

void put_state(Writer& w, const CheckpointState& s) {
  w.put_text(s.scene_toml);
  const StepCounters& c = s.counters;
  w.put<double>(c.time);
  w.put<std::int64_t>(c.steps);
  w.put<double>(c.last_dt);
  w.put<double>(c.basal_shear_force);
  w.put<double>(c.max_signal_speed);
  w.put<double>(c.speed_limit);
  const ScheduleState& k = s.schedule;
  w.put<std::int64_t>(k.row);
  w.put<std::int64_t>(k.checkpoint_rows);
  w.put<std::int64_t>(k.frames);
  w.put<double>(k.rest_peak);
  w.put<double>(k.rest_since);
  w.put<double>(k.initial_toe);
  w.put<std::uint64_t>(k.pvd.size());
  for (std::size_t e = 0; e < k.pvd.size(); ++e) {
    w.put<double>(k.pvd[e].first);
    w.put_text(k.pvd[e].second);
    // No record: a frame a resume cannot vouch for, which it refuses.
    w.put_text(e < k.frame_records.size() ? k.frame_records[e] : std::string());
  }
}

// Whether a file name read back is frame_<index>.vtu, the name the run
// schedule gives that frame.
bool frame_name_at(const std::string& name, std::size_t index) {
  char expected[32];
  std::snprintf(expected, sizeof expected, "frame_%05zu.vtu", index);
  return name == expected;
}

// Index times as a run writes them: finite, in order, none after the
// checkpoint's own time (a NaN would reach the .pvd as timestep="nan").
void require_index_times(const std::vector<std::pair<double, std::string>>& pvd, double now,
                         const Reader& r) {
  double before = 0.0;
  for (std::size_t e = 0; e < pvd.size(); ++e) {
    const double t = pvd[e].first;
    if (!std::isfinite(t) || t < before || t > now)
      r.fail("index entry " + std::to_string(e) + " has time " + std::to_string(t) +
             "; index times are finite, in order and not after the checkpoint's");
    before = t;
  }
}

CheckpointState get_state(Reader& r) {
  CheckpointState s;
  s.scene_toml = r.get_text();
  StepCounters& c = s.counters;
  c.time = r.get<double>();
  c.steps = r.get<std::int64_t>();
  c.last_dt = r.get<double>();
  c.basal_shear_force = r.get<double>();
  c.max_signal_speed = r.get<double>();
  c.speed_limit = r.get<double>();
  ScheduleState& k = s.schedule;
  k.row = r.get<std::int64_t>();
  k.checkpoint_rows = r.get<std::int64_t>();
  const std::int64_t frames = r.get<std::int64_t>();
  k.rest_peak = r.get<double>();
  k.rest_since = r.get<double>();
  k.initial_toe = r.get<double>();
  const std::uint64_t entries = r.get<std::uint64_t>();
  // Each entry holds at least a time and two text lengths.
  if (entries > r.left() / 24) r.fail("more index entries than the file holds");
  for (std::uint64_t e = 0; e < entries; ++e) {
    const double time = r.get<double>();
    k.pvd.emplace_back(time, r.get_text());
    k.frame_records.push_back(r.get_text());
  }
  // checkpoint_rows 0: a run without --checkpoint-every, stopped by a signal.
  if (k.row < 0 || k.checkpoint_rows < 0 || frames < 0 ||
      frames != static_cast<std::int64_t>(k.pvd.size()) || c.steps < 0)
    r.fail("inconsistent counters");
  if (!std::isfinite(c.time) || c.time < 0 || !std::isfinite(c.last_dt) || c.last_dt < 0)
    r.fail("a time or time step that is negative or not finite");
  k.frames = static_cast<int>(frames);
  require_index_times(k.pvd, c.time, r);
  // The index names the frames the folder holds: nothing else (a path out
  // of the folder) may come back into it.
  for (std::size_t e = 0; e < k.pvd.size(); ++e)
    if (!frame_name_at(k.pvd[e].second, e)) r.fail("index entry " + std::to_string(e) +
                                                   " is not frame " + std::to_string(e));
  return s;
}

std::string hex(std::uint64_t value) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(value));
  return buf;
}

// The whole of a regular file whose first kHeaderBytes are checked by
// check_header before the rest is read.
std::string read_regular_file(const std::string& path,
                              void (*check_header)(std::string_view, std::uint64_t,
                                                   const std::string&)) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw CheckpointMissing("cannot open checkpoint '" + path + "'");
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw CheckpointError("cannot stat checkpoint '" + path + "'");
  if (!S_ISREG(st.st_mode))
    throw CheckpointError(path + ": not a regular file (a device, a pipe or a folder)");
  const auto size = static_cast<std::uint64_t>(st.st_size);
  std::string bytes(std::min<std::uint64_t>(size, kHeaderBytes), '\0');
  const auto read_into = [&](std::size_t from) {
    std::size_t at = from;
    while (at < bytes.size()) {
      const ssize_t n = ::pread(fd, bytes.data() + at, bytes.size() - at, at);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) throw CheckpointError("cannot read checkpoint '" + path + "'");
      at += static_cast<std::size_t>(n);
    }
  };
  read_into(0);
  check_header(bytes, size, path);
  // A size the header and the file agree on can still be absurd (a sparse
  // file): never try to hold more than the machine can.
  if (const std::optional<double> available = available_memory(); available && size > *available)
    throw CheckpointError(path + ": the checkpoint states " + byte_text(double(size)) +
                          ", more than the memory available (" + byte_text(*available) + ")");
  bytes.resize(size);  // the header vouches for this size: it is the file's
  read_into(kHeaderBytes);
  return bytes;
}

// Magic, version, and a stated payload size that is the file's real one.
void check_header(std::string_view bytes, std::uint64_t file_size, const std::string& source) {
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    throw CheckpointError(source + ": not a Runout checkpoint (no RUNOUTCK header)");
  if (file_size < kHeaderBytes + kChecksumBytes)
    throw CheckpointError(source + ": truncated: " + std::to_string(file_size) +
                          " bytes, shorter than the header");
  std::uint32_t version;
  std::uint64_t size;
  std::memcpy(&version, bytes.data() + sizeof kMagic, sizeof version);
  std::memcpy(&size, bytes.data() + sizeof kMagic + 4, sizeof size);
  if (version != kVersion)
    throw CheckpointError(source + ": checkpoint format version " + std::to_string(version) +
                          ", this runout reads version " + std::to_string(kVersion));
  const std::uint64_t body = file_size - kHeaderBytes - kChecksumBytes;
  if (size != body)
    throw CheckpointError(source + ": truncated or padded: the header gives " +
                          std::to_string(size) + " bytes of data, the file holds " +
                          std::to_string(body));
}

}  // namespace

std::string encode_checkpoint(const CheckpointState& state, const Particles& particles) {
  Writer payload;
  put_state(payload, state);
  put_particles(payload, particles);
  Writer file;
  file.bytes().append(kMagic, sizeof kMagic);
  file.put<std::uint32_t>(kVersion);
  file.put<std::uint64_t>(payload.bytes().size());
  file.bytes() += payload.bytes();
  file.put<std::uint64_t>(fnv1a(file.bytes()));
  return std::move(file.bytes());
}

Checkpoint decode_checkpoint(std::string_view bytes, const std::string& source) {
  check_header(bytes, bytes.size(), source);
  const std::size_t body = bytes.size() - kHeaderBytes - kChecksumBytes;
  std::uint64_t stored;
  std::memcpy(&stored, bytes.data() + bytes.size() - kChecksumBytes, sizeof stored);
  if (stored != fnv1a(bytes.substr(0, bytes.size() - kChecksumBytes)))
    throw CheckpointError(source + ": checksum mismatch: the file is corrupt");

  Reader r(bytes.substr(kHeaderBytes, body), source);
  Checkpoint cp;
  cp.state = get_state(r);
  cp.particles = get_particles(r);
  if (r.left() != 0) r.fail("unread data after the particles");
  return cp;
}

void write_checkpoint(const std::string& path, const CheckpointState& state,
                      const Particles& particles) {
  write_file_atomically(path, encode_checkpoint(state, particles));
}

Checkpoint read_checkpoint(const std::string& path) {
  return decode_checkpoint(read_regular_file(path, check_header), path);
}

std::uint64_t scene_hash(std::string_view scene_toml) { return fnv1a(scene_toml); }

void require_same_scene(const CheckpointState& state, const std::string& resolved_path,
                        const std::string& source) {
  std::string resolved;
  try {
    resolved = read_scene_text(resolved_path);
  } catch (const SceneFileError& e) {
    throw CheckpointError(source + ": the run folder has no readable " + resolved_path +
                          " to check the checkpoint against (" + e.what() + ")");
  }
  const std::uint64_t folder = scene_hash(resolved), own = scene_hash(state.scene_toml);
  if (folder != own)
    throw CheckpointError(source + ": the checkpoint belongs to another run: its scene (hash " +
                          hex(own) + ") is not the folder's " + resolved_path + " (hash " +
                          hex(folder) + ")");
}

void require_particles_fit(const Particles& P, const Scene& scene, const std::string& source) {
  const auto outside = [](int index, std::size_t count) {
    return index < 0 || static_cast<std::size_t>(index) >= count;
  };
  for (int p = 0; p < P.size(); ++p) {
    if (outside(P.material[p], scene.materials.size()))
      throw CheckpointError(source + ": particle " + std::to_string(p) + " has material_id " +
                            std::to_string(P.material[p]) + ", the scene has " +
                            std::to_string(scene.materials.size()) + " materials");
    if (outside(P.body[p], scene.bodies.size()))
      throw CheckpointError(source + ": particle " + std::to_string(p) + " has body_id " +
                            std::to_string(P.body[p]) + ", the scene has " +
                            std::to_string(scene.bodies.size()) + " bodies");
  }
}

}  // namespace runout
