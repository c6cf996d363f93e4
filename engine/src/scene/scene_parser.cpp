#include "runout/scene/scene_parser.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include <toml++/toml.h>

#include "runout/scene/polygon.hpp"
#include "runout/mpm/step_config.hpp"
#include "scene_text.hpp"

namespace runout {
namespace {

using scene_text::format_number;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kDegree = 3.14159265358979323846 / 180.0;

// The values a number may take; an open end excludes its bound.
struct Range {
  double lo = -kInf, hi = kInf;
  bool lo_open = false, hi_open = false;

  bool contains(double v) const {
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }

  std::string describe() const {
    if (hi == kInf)
      return std::string(lo_open ? "> " : ">= ") + format_number(lo);
    return std::string("in ") + (lo_open ? "(" : "[") + format_number(lo) +
           ", " + format_number(hi) + (hi_open ? ")" : "]");
  }
};

Range above(double lo) { return {lo, kInf, true, false}; }
Range at_least(double lo) { return {lo, kInf, false, false}; }
// brackets is interval notation: "()", "(]", "[)" or "[]".
Range between(double lo, double hi, const char* brackets) {
  return {lo, hi, brackets[0] == '(', brackets[1] == ')'};
}

const Range kPpcRange = between(1, 16, "[]");

// Denser than any rock or metal (osmium: 22 590 kg/m3): a density beyond it
// is a typo, and 1e300 overflows the masses and energies within steps.
const Range kDensityRange = between(0.0, 1e5, "(]");

// Frames a run may write (time.end / time.output_interval): far beyond any
// useful series, and well short of a file count that fills a disk.
constexpr double kMaxFrames = 1e6;

// Why end / interval gives too many frames, or "".
// A Courant number beyond what the step's shape functions and transfer
// hold answers differently from a smaller one, so it is refused.
std::string courant_refusal(double courant, ShapeKind shape, TransferKind transfer) {
  const double limit = max_courant(shape, transfer);
  if (courant <= limit) return "";
  return "must be <= " + format_number(limit) + " with shape " +
         std::string(scene_text::name_of(scene_text::kShapeNames, shape)) + " and transfer " +
         std::string(scene_text::name_of(scene_text::kTransferNames, transfer)) + " (got " +
         format_number(courant) + "): beyond it the runout changes with the time step " +
         "(docs/convergence.md)";
}

std::string too_many_frames(double end, double interval) {
  const double frames = end / interval;
  if (frames <= kMaxFrames) return "";
  return "time.end / time.output_interval gives " + format_number(frames) +
         " frames, more than the " + format_number(kMaxFrames) + " a run may write";
}

// line 0 means "no line": command-line values, missing files.
[[noreturn]] void throw_error(const std::string& source, int line,
                              const std::string& key, const std::string& what) {
  const std::string where =
      line > 0 ? source + ":" + std::to_string(line) + ": " : std::string();
  throw SceneError(where + key + ": " + what, line);
}

std::string type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table: return "table";
    case toml::node_type::array: return "array";
    case toml::node_type::string: return "string";
    case toml::node_type::integer: return "integer";
    case toml::node_type::floating_point: return "float";
    case toml::node_type::boolean: return "boolean";
    case toml::node_type::date: return "date";
    case toml::node_type::time: return "time";
    case toml::node_type::date_time: return "date-time";
    default: return "nothing";
  }
}

std::string in_quotes(std::string_view text) {
  return "\"" + std::string(text) + "\"";
}

class TableReader;

// A TOML node together with the dotted key it was found under, so every
// conversion can name the key and the line when it rejects the value.
class Value {
 public:
  Value(const toml::node& node, std::string key, const std::string& source,
        int fallback_line)
      : node_(&node), key_(std::move(key)), source_(&source) {
    const int own = static_cast<int>(node.source().begin.line);
    line_ = own > 0 ? own : fallback_line;
  }

  int line() const { return line_; }

  [[noreturn]] void fail(const std::string& what) const {
    throw_error(*source_, line_, key_, what);
  }

  std::string string() const {
    if (const auto* s = node_->as_string()) return s->get();
    fail_type("a string");
  }

  bool boolean() const {
    if (const auto* b = node_->as_boolean()) return b->get();
    fail_type("a boolean");
  }

  double number(const Range& range = {}) const {
    double v = 0.0;
    if (const auto* i = node_->as_integer())
      v = static_cast<double>(i->get());
    else if (const auto* f = node_->as_floating_point())
      v = f->get();
    else
      fail_type("a number");
    check(v, range);
    return v;
  }

  int integer(const Range& range) const {
    const auto* i = node_->as_integer();
    if (!i) fail_type("an integer");
    check(static_cast<double>(i->get()), range);
    if (i->get() < std::numeric_limits<int>::min() || i->get() > std::numeric_limits<int>::max())
      fail("must fit a 32-bit int (got " + std::to_string(i->get()) + ")");
    return static_cast<int>(i->get());
  }

  Eigen::Vector2d vec2() const {
    const toml::array& a = array("an array of 2 numbers [x, y]");
    if (a.size() != 2)
      fail("expected an array of 2 numbers [x, y], got " +
           std::to_string(a.size()) + " values");
    return {element(a, 0).number(), element(a, 1).number()};
  }

  std::vector<Eigen::Vector2d> points() const {
    const toml::array& a = array("an array of [x, y] points");
    std::vector<Eigen::Vector2d> result;
    for (std::size_t i = 0; i < a.size(); ++i)
      result.push_back(element(a, i).vec2());
    return result;
  }

  std::vector<std::string> strings() const {
    const toml::array& a = array("an array of strings");
    std::vector<std::string> result;
    for (std::size_t i = 0; i < a.size(); ++i)
      result.push_back(element(a, i).string());
    return result;
  }

  // entries: anything with a `name`, e.g. Named<Enum>.
  template <class Entry, std::size_t N>
  const Entry& choice(const Entry (&entries)[N]) const {
    const std::string text = string();
    std::string allowed;
    for (const Entry& entry : entries) {
      if (entry.name == text) return entry;
      allowed += (allowed.empty() ? "" : ", ") + in_quotes(entry.name);
    }
    fail("must be one of " + allowed + " (got " + in_quotes(text) + ")");
  }

  TableReader table() const;
  std::vector<TableReader> tables() const;

 private:
  [[noreturn]] void fail_type(const std::string& expected) const {
    fail("expected " + expected + ", got " + type_name(*node_));
  }

  void check(double v, const Range& range) const {
    if (!std::isfinite(v)) fail("must be a finite number (got " + format_number(v) + ")");
    if (!range.contains(v))
      fail("must be " + range.describe() + " (got " + format_number(v) + ")");
  }

  const toml::array& array(const std::string& expected) const {
    if (const auto* a = node_->as_array()) return *a;
    fail_type(expected);
  }

  Value element(const toml::array& a, std::size_t i) const {
    return Value(*a.get(i), key_ + "[" + std::to_string(i) + "]", *source_,
                 line_);
  }

  const toml::node* node_;
  std::string key_;
  const std::string* source_;
  int line_ = 0;
};

// One TOML table of the scene, with its dotted path for messages. Each
// section first lists the keys it knows (check_keys), so a misspelt key is
// reported as unknown rather than as the required key it was meant to be.
class TableReader {
 public:
  TableReader(const toml::table& table, std::string path,
              const std::string& source, int line)
      : table_(&table), path_(std::move(path)), source_(&source), line_(line) {}

  void check_keys(const std::vector<std::string_view>& known) const {
    const toml::node* first_unknown = nullptr;
    std::string unknown_key;
    for (const auto& [key, node] : *table_) {
      if (std::find(known.begin(), known.end(), key.str()) != known.end())
        continue;
      // Report the first one in the file, not in the table's key order.
      if (!first_unknown || line_of(node) < line_of(*first_unknown)) {
        first_unknown = &node;
        unknown_key = std::string(key.str());
      }
    }
    if (first_unknown) value(unknown_key, *first_unknown).fail("unknown key");
  }

  std::optional<Value> find(std::string_view key) const {
    if (const toml::node* node = table_->get(key)) return value(key, *node);
    return std::nullopt;
  }

  Value need(std::string_view key) const {
    if (auto found = find(key)) return *found;
    fail(key, line_, "missing required key");
  }

  // An absent optional table reads as empty, so its section takes defaults.
  TableReader optional_table(std::string_view key) const {
    if (auto found = find(key)) return found->table();
    static const toml::table empty;
    return TableReader(empty, path(key), *source_, line_);
  }

  // For a property derived from several keys (e.g. a body's outline).
  [[noreturn]] void fail(std::string_view key, int line,
                         const std::string& what) const {
    throw_error(*source_, line, path(key), what);
  }

 private:
  std::string path(std::string_view key) const {
    return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
  }

  int line_of(const toml::node& node) const {
    return value("", node).line();
  }

  Value value(std::string_view key, const toml::node& node) const {
    return Value(node, path(key), *source_, line_);
  }

  const toml::table* table_;
  std::string path_;
  const std::string* source_;
  int line_;
};

TableReader Value::table() const {
  const auto* t = node_->as_table();
  if (!t) fail_type("a table");
  return TableReader(*t, key_, *source_, line_);
}

std::vector<TableReader> Value::tables() const {
  const std::string expected = "an array of tables ([[" + key_ + "]])";
  const auto* a = node_->as_array();
  if (!a) fail_type(expected);
  if (a->empty()) fail("must have at least one entry");
  if (!a->is_array_of_tables()) fail_type(expected);
  std::vector<TableReader> result;
  for (std::size_t i = 0; i < a->size(); ++i)
    result.push_back(element(*a, i).table());
  return result;
}

// The grid has a node on its min corner; max is pushed out to the next node
// so the domain is a whole number of cells. The tolerance keeps a max that
// is already on a node (up to rounding) where it is, which also makes the
// snap idempotent when a resolved scene is read back.
void snap_max_to_node(GridSpec& grid) {
  for (int axis = 0; axis < 2; ++axis) {
    const double cells =
        std::ceil((grid.max[axis] - grid.min[axis]) / grid.cell_size - 1e-9);
    grid.max[axis] = grid.min[axis] + cells * grid.cell_size;
  }
}

// The longest file name a run makes of the scene name is
// "." + name + ".pvd.manifest.tmp.<pid>.<n>", about 40 bytes more than the
// name, within the 255 bytes a file name may have on Linux.
constexpr std::size_t kMaxSceneNameBytes = 200;

// Whether a code point prints as itself: not a control (C0, DEL, C1) and
// not one of the format characters that make a name show other than it is
// or break a line (bidirectional marks, embeddings, overrides and
// isolates, zero-width characters, line and paragraph separators, the
// byte-order mark).
bool printable(char32_t c) {
  if (c < 0x20 || (c >= 0x7F && c <= 0x9F)) return false;
  if ((c >= 0x200B && c <= 0x200F) || (c >= 0x2028 && c <= 0x202E)) return false;
  if ((c >= 0x2066 && c <= 0x2069) || c == 0xFEFF) return false;
  return true;
}

// The code points of a UTF-8 string (TOML strings are valid UTF-8: the
// parser refuses a document that is not).
std::vector<char32_t> code_points(const std::string& text) {
  std::vector<char32_t> out;
  for (std::size_t i = 0; i < text.size();) {
    const auto lead = static_cast<unsigned char>(text[i]);
    const int extra = lead < 0x80 ? 0 : lead < 0xE0 ? 1 : lead < 0xF0 ? 2 : 3;
    char32_t c = extra == 0 ? lead : lead & (0x3F >> extra);
    for (int k = 1; k <= extra && i + k < text.size(); ++k)
      c = (c << 6) | (static_cast<unsigned char>(text[i + k]) & 0x3F);
    out.push_back(c);
    i += extra + 1;
  }
  return out;
}

// The name becomes file names (<name>.pvd, the default folder out/<name>),
// so it must be one: a path separator would write outside the folder.
void check_scene_name(const Value& value, const std::string& name) {
  if (name.empty() || name == "." || name == "..")
    value.fail("must be a file name (got " + in_quotes(name) + ")");
  if (name.size() > kMaxSceneNameBytes)
    value.fail("must be at most " + std::to_string(kMaxSceneNameBytes) +
               " bytes, as it names the output's files (got " + std::to_string(name.size()) +
               ")");
  for (const char c : name)
    if (c == '/' || c == '\\')
      value.fail("must be a file name, without '/' or '\\'");
  for (const char32_t c : code_points(name))
    if (!printable(c)) {
      char code[16];
      std::snprintf(code, sizeof code, "U+%04X", static_cast<unsigned>(c));
      value.fail(std::string("must be printable: it holds ") + code +
                 " (a control or formatting character)");
    }
}

void read_scene_info(TableReader r, Scene& scene) {
  r.check_keys({"name", "description", "method"});
  const Value name = r.need("name");
  scene.name = name.string();
  check_scene_name(name, scene.name);
  if (auto v = r.find("description")) scene.description = v->string();
  if (auto v = r.find("method")) scene.method = v->choice(scene_text::kMethodNames).value;
}

GridSpec read_grid(TableReader r) {
  r.check_keys({"cell_size", "min", "max", "shape", "domain", "ppc"});
  GridSpec grid;
  const Value cell_size = r.need("cell_size");
  grid.cell_size = cell_size.number(above(0.0));
  grid.min = r.need("min").vec2();
  const Value max = r.need("max");
  grid.max = max.vec2();
  if (auto v = r.find("shape")) grid.shape = v->choice(scene_text::kShapeNames).value;
  if (auto v = r.find("domain")) grid.domain = v->choice(scene_text::kDomainNames).value;
  if (auto v = r.find("ppc")) grid.ppc = v->integer(kPpcRange);
  if ((grid.max.array() <= grid.min.array()).any())
    max.fail("must be greater than grid.min in both x and y");
  // A cell wider than the domain would snap grid.max back onto grid.min.
  const Eigen::Array2d extent = (grid.max - grid.min).array();
  if ((extent < grid.cell_size).any())
    cell_size.fail("is larger than the domain grid.min to grid.max (" +
                   format_number(extent.x()) + " m x " + format_number(extent.y()) +
                   " m): at least one cell must fit across it");
  // Node indices along an axis are ints (and beyond that the extent itself
  // may overflow a double).
  const Eigen::Array2d cells = (grid.max - grid.min).array() / grid.cell_size;
  if (!(cells <= std::numeric_limits<int>::max()).all())
    max.fail("the domain is " + format_number(cells.maxCoeff()) +
             " cells of grid.cell_size across, more than the " +
             std::to_string(std::numeric_limits<int>::max()) + " a grid can index");
  snap_max_to_node(grid);
  return grid;
}

BoundarySpec read_boundary(TableReader r) {
  r.check_keys({"left", "right", "bottom", "top"});
  BoundarySpec boundary;
  const std::pair<const char*, BoundaryKind*> sides[] = {
      {"left", &boundary.left},
      {"right", &boundary.right},
      {"bottom", &boundary.bottom},
      {"top", &boundary.top}};
  for (const auto& [key, side] : sides)
    if (auto v = r.find(key)) *side = v->choice(scene_text::kBoundaryNames).value;
  // A periodic domain repeats along x: material leaving on one side
  // enters on the other, so both sides are periodic or neither is.
  for (const auto& [key, side] : {sides[2], sides[3]})  // bottom, top
    if (*side == BoundaryKind::Periodic)
      r.need(key).fail("\"periodic\" is for left and right only (the domain repeats along x)");
  const bool left = boundary.left == BoundaryKind::Periodic;
  if (left != (boundary.right == BoundaryKind::Periodic))
    r.need(left ? "left" : "right")
        .fail("\"periodic\" needs the other side periodic too (boundary.left and boundary.right)");
  return boundary;
}

// A periodic domain must repeat whole: a planar base (the grid's bottom
// line, the same at every x) or none.
void check_periodic(const TableReader& boundary_table, const Scene& scene) {
  if (scene.boundary.left != BoundaryKind::Periodic) return;
  const Value left = boundary_table.need("left");
  if (scene.base.kind == BaseKind::Polyline)
    left.fail("\"periodic\" needs a planar base or none: a polyline base does not repeat");
}

TimeSpec read_time(TableReader r, const GridSpec& grid, const SolverSpec& solver) {
  r.check_keys({"end", "output_interval", "courant", "rest_fraction", "rest_duration"});
  TimeSpec time;
  time.end = r.need("end").number(above(0.0));
  const Value interval = r.need("output_interval");
  time.output_interval = interval.number(above(0.0));
  if (auto v = r.find("courant")) {
    time.courant = v->number(between(0, 1, "(]"));
    const std::string refusal = courant_refusal(time.courant, grid.shape, solver.transfer);
    if (!refusal.empty()) v->fail(refusal);
  }
  if (auto v = r.find("rest_fraction"))
    time.rest_fraction = v->number(between(0, 1, "[)"));
  if (auto v = r.find("rest_duration")) time.rest_duration = v->number(above(0.0));
  if (time.output_interval > time.end)
    interval.fail("must be <= time.end (got " + format_number(time.output_interval) +
                  " > " + format_number(time.end) + ")");
  const std::string frames = too_many_frames(time.end, time.output_interval);
  if (!frames.empty()) interval.fail(frames);
  return time;
}

// Either a slope (magnitude and angle) or an explicit vector: giving both
// would leave it unclear which one the run uses.
GravitySpec read_gravity(TableReader r) {
  r.check_keys({"magnitude", "slope_angle", "vector", "ramp"});
  GravitySpec gravity;
  if (auto v = r.find("ramp")) gravity.ramp = v->number(at_least(0.0));
  const auto magnitude = r.find("magnitude");
  const auto angle = r.find("slope_angle");
  if (const auto vector = r.find("vector")) {
    for (const auto& conflict : {magnitude, angle})
      if (conflict) conflict->fail("cannot be combined with gravity.vector");
    gravity.vector = vector->vec2();
    return gravity;
  }
  // The default vector is plain downward gravity, so its length is the
  // default magnitude.
  const double g = magnitude ? magnitude->number(at_least(0.0)) : gravity.vector.norm();
  if (angle) gravity.slope_angle_deg = angle->number(between(-90, 90, "()"));
  gravity.vector = scene_text::slope_gravity(g, gravity.slope_angle_deg);
  return gravity;
}

SolverSpec read_solver(TableReader r) {
  r.check_keys({"transfer", "flip", "pic_cells", "xpic_order", "xpic_cells", "mass_threshold",
                "damping", "volumetric_smoothing"});
  SolverSpec solver;
  if (auto v = r.find("transfer")) solver.transfer = v->choice(scene_text::kTransferNames).value;
  if (auto v = r.find("flip")) solver.flip = v->number(between(0, 1, "[]"));
  if (auto v = r.find("pic_cells")) solver.pic_cells = v->number(at_least(0.0));
  if (auto v = r.find("xpic_order")) solver.xpic_order = v->integer(between(1, 8, "[]"));
  if (auto v = r.find("xpic_cells")) {
    solver.xpic_cells = v->number(at_least(0.0));
    if (solver.xpic_cells > 0.0 && solver.transfer != TransferKind::Flip)
      v->fail("is a schedule for transfer \"flip\" (transfer \"xpic\" filters every step)");
  } else if (solver.transfer != TransferKind::Flip) {
    solver.xpic_cells = 0.0;  // the default schedule is FLIP's
  }
  if (auto v = r.find("mass_threshold"))
    solver.mass_threshold = v->number(between(0, 1, "[)"));
  if (auto v = r.find("damping")) solver.damping = v->number(between(0, 1, "[)"));
  if (auto v = r.find("volumetric_smoothing")) solver.volumetric_smoothing = v->boolean();
  return solver;
}

// The strength of SCENES.md, "Strength of the slide". The defaults leave
// out softening (sensitivity 1) and the rate effect (eta 0); xi95 has no
// sensible default once there is softening, so it is then required.
void read_tresca(const TableReader& r, MaterialSpec& m) {
  m.su0 = r.need("su0").number(above(0.0));
  if (auto v = r.find("sensitivity")) m.sensitivity = v->number(at_least(1.0));
  const auto xi95 = m.sensitivity > 1.0 ? r.need("xi95") : r.find("xi95");
  if (xi95) m.xi95 = xi95->number(above(0.0));
  if (auto v = r.find("eta")) m.eta = v->number(at_least(0.0));
  if (auto v = r.find("rate_exponent")) m.rate_exponent = v->number(between(0, 1, "(]"));
  if (auto v = r.find("reference_rate")) m.reference_rate = v->number(above(0.0));
  if (auto v = r.find("strength_form"))
    m.strength_form = v->choice(scene_text::kStrengthFormNames).value;
  if (auto v = r.find("band_thickness")) m.band_thickness = v->number(above(0.0));
  if (auto v = r.find("nonlocal_length")) {
    m.nonlocal_length = v->number(above(0.0));
    if (m.band_thickness == 0.0)
      v->fail("nonlocal_length averages the regularised softening, which band_thickness sets");
  }
}

std::vector<MaterialSpec> read_materials(const TableReader& root) {
  std::vector<MaterialSpec> materials;
  for (const TableReader& r : root.need("material").tables()) {
    // The keys a material may have depend on its model, so the model comes first.
    MaterialSpec m;
    if (auto v = r.find("model")) m.model = v->choice(scene_text::kModelNames).value;
    std::vector<std::string_view> keys = {"name", "model", "density", "youngs_modulus",
                                          "poisson_ratio"};
    if (m.model == MaterialModel::Tresca)
      keys.insert(keys.end(), {"su0", "sensitivity", "xi95", "eta", "rate_exponent",
                               "reference_rate", "strength_form", "band_thickness",
                               "nonlocal_length"});
    r.check_keys(keys);
    const Value name = r.need("name");
    m.name = name.string();
    for (const MaterialSpec& earlier : materials)
      if (earlier.name == m.name) name.fail("duplicate material name " + in_quotes(m.name));
    m.density = r.need("density").number(kDensityRange);
    m.youngs_modulus = r.need("youngs_modulus").number(above(0.0));
    m.poisson_ratio = r.need("poisson_ratio").number(between(-1, 0.5, "()"));
    if (m.model == MaterialModel::Tresca) read_tresca(r, m);
    materials.push_back(std::move(m));
  }
  return materials;
}

Polygon read_rectangle(const TableReader& r) {
  const Eigen::Vector2d lo = r.need("min").vec2();
  const Value max = r.need("max");
  const Eigen::Vector2d hi = max.vec2();
  if ((hi.array() <= lo.array()).any())
    max.fail("must be greater than min in both x and y");
  return {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
}

// The base runs along +x from base_start; each side face makes its angle
// with the base, the rear one leaning forward from base_start and the front
// one leaning back from the far end of the base.
Polygon read_trapezoid(const TableReader& r) {
  const Eigen::Vector2d start = r.need("base_start").vec2();
  const Value length_value = r.need("base_length");
  const double length = length_value.number(above(0.0));
  const double height = r.need("height").number(above(0.0));
  const Range angle = between(0, 180, "()");
  const double rear = r.need("rear_angle").number(angle) * kDegree;
  const double front = r.need("front_angle").number(angle) * kDegree;
  const double rear_run = height / std::tan(rear);
  const double front_run = height / std::tan(front);
  const double top = length - rear_run - front_run;
  if (!(top > 0.0))
    length_value.fail(
        "the top of the trapezoid (base_length - height/tan(rear_angle) - "
        "height/tan(front_angle)) must be > 0 (got " + format_number(top) + ")");
  return {start,
          start + Eigen::Vector2d(length, 0.0),
          start + Eigen::Vector2d(length - front_run, height),
          start + Eigen::Vector2d(rear_run, height)};
}

Polygon read_vertices(const TableReader& r) {
  const Value vertices = r.need("vertices");
  Polygon polygon = vertices.points();
  if (polygon.size() < 3)
    vertices.fail("expected at least 3 vertices (got " +
                  std::to_string(polygon.size()) + ")");
  // The outline check is near-linear for short edges, but stays bounded
  // for any outline only with a bounded count.
  constexpr std::size_t kMaxVertices = 1000000;
  if (polygon.size() > kMaxVertices)
    vertices.fail("more than " + std::to_string(kMaxVertices) + " vertices (got " +
                  std::to_string(polygon.size()) + ")");
  return polygon;
}

struct BodyType {
  std::string_view name;
  std::vector<std::string_view> keys;
  Polygon (*read)(const TableReader&);
};

const BodyType kBodyTypes[] = {
    {"rectangle", {"min", "max"}, read_rectangle},
    {"trapezoid",
     {"base_start", "base_length", "height", "rear_angle", "front_angle"},
     read_trapezoid},
    {"polygon", {"vertices"}, read_vertices},
};

std::string point_text(const Eigen::Vector2d& v) {
  return "(" + format_number(v.x()) + ", " + format_number(v.y()) + ")";
}

// The solver wants a counter-clockwise simple outline inside the grid.
Polygon checked_outline(Polygon outline, const GridSpec& grid,
                        const TableReader& r, int line) {
  const std::string defect = outline_defect(outline);
  if (!defect.empty()) r.fail("polygon", line, defect);
  const double area = signed_area(outline);  // 0 still possible by rounding
  if (area == 0.0) r.fail("polygon", line, "zero area");
  if (area < 0.0) std::reverse(outline.begin(), outline.end());
  for (const Eigen::Vector2d& v : outline) {
    if ((v.array() >= grid.min.array()).all() && (v.array() <= grid.max.array()).all())
      continue;
    r.fail("polygon", line,
           "vertex " + point_text(v) + " lies outside the grid [" +
               format_number(grid.min.x()) + ", " +
               format_number(grid.max.x()) + "] x [" + format_number(grid.min.y()) +
               ", " + format_number(grid.max.y()) + "]");
  }
  return outline;
}

int material_index(const Value& name, const std::vector<MaterialSpec>& materials) {
  const std::string wanted = name.string();
  for (std::size_t i = 0; i < materials.size(); ++i)
    if (materials[i].name == wanted) return static_cast<int>(i);
  name.fail("unknown material " + in_quotes(wanted));
}

std::vector<BodySpec> read_bodies(const TableReader& root,
                                  const std::vector<MaterialSpec>& materials,
                                  const GridSpec& grid) {
  std::vector<BodySpec> bodies;
  for (const TableReader& r : root.need("body").tables()) {
    // The keys a body may have depend on its type, so the type comes first.
    const Value type_value = r.need("type");
    const BodyType& type = type_value.choice(kBodyTypes);
    std::vector<std::string_view> keys = {"name", "material", "type", "velocity"};
    keys.insert(keys.end(), type.keys.begin(), type.keys.end());
    r.check_keys(keys);

    BodySpec body;
    body.name = r.need("name").string();
    body.material = material_index(r.need("material"), materials);
    body.polygon = checked_outline(type.read(r), grid, r, type_value.line());
    if (auto v = r.find("velocity")) body.velocity = v->vec2();
    bodies.push_back(std::move(body));
  }
  return bodies;
}

// A bathymetry y(x): one height for every x of the grid it covers.
std::vector<Eigen::Vector2d> read_base_line(const Value& value, const GridSpec& grid) {
  std::vector<Eigen::Vector2d> points = value.points();
  if (points.size() < 2)
    value.fail("expected at least 2 points (got " + std::to_string(points.size()) + ")");
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d& p = points[i];
    const std::string which = "point " + std::to_string(i) + " " + point_text(p);
    if (p.x() < grid.min.x() || p.x() > grid.max.x())
      value.fail(which + " lies outside the grid's x range [" + format_number(grid.min.x()) +
                 ", " + format_number(grid.max.x()) + "]");
    if (i > 0 && !(p.x() > points[i - 1].x()))
      value.fail("x must increase strictly along the line: " + which + " follows x = " +
                 format_number(points[i - 1].x()));
    // The base divides by each segment's length (Base): one whose square
    // underflows to 0 has none.
    if (i > 0 && !((p - points[i - 1]).norm() > 0.0))
      value.fail(which + " is too close to point " + std::to_string(i - 1) +
                 " for the segment between them to have a length");
  }
  return points;
}

// The keys of [base] depend on its kind and its interface, so those two
// come first.
BaseSpec read_base(const TableReader& r, const GridSpec& grid) {
  BaseSpec base;
  base.kind = r.need("kind").choice(scene_text::kBaseNames).value;
  if (auto v = r.find("interface")) base.interface = v->choice(scene_text::kInterfaceNames).value;
  std::vector<std::string_view> keys = {"kind", "interface"};
  if (base.kind == BaseKind::Polyline) keys.push_back("points");
  if (base.interface == InterfaceKind::Frictional) keys.push_back("shear_strength");
  if (base.interface == InterfaceKind::Coulomb) keys.push_back("friction");
  if (base.interface != InterfaceKind::Coulomb) keys.push_back("clay_band");
  r.check_keys(keys);
  if (auto v = r.find("clay_band")) base.clay_band = v->boolean();
  if (base.kind == BaseKind::Polyline) base.points = read_base_line(r.need("points"), grid);
  if (base.interface == InterfaceKind::Frictional)
    base.shear_strength = r.need("shear_strength").number(above(0.0));
  if (base.interface == InterfaceKind::Coulomb)
    base.friction = r.need("friction").number(above(0.0));
  return base;
}

// The basal band softens over the slip across it divided by its
// thickness, so every softening clay needs one.
void check_clay_band(const TableReader& base_table, const Scene& scene) {
  if (!scene.base.clay_band) return;
  for (const MaterialSpec& m : scene.materials)
    if (m.model == MaterialModel::Tresca && m.sensitivity > 1.0 && !(m.band_thickness > 0.0))
      base_table.need("clay_band")
          .fail("softens the basal band over the slip across it divided by band_thickness, "
                "which material \"" + m.name + "\" (sensitivity " +
                format_number(m.sensitivity) + ") does not set");
}

// The base is the bottom of the slide: a bottom boundary condition as
// well would act on the same nodes as the contact, so only "free" may be
// given, and it is what an absent one becomes.
void free_bottom_for_base(const TableReader& boundary_table, BoundarySpec& boundary) {
  const auto bottom = boundary_table.find("bottom");
  if (bottom && boundary.bottom != BoundaryKind::Free)
    bottom->fail("must be \"free\" when [base] is given: the base is the bottom");
  boundary.bottom = BoundaryKind::Free;
}

// The slide of the depth-averaged model is the first body (docs/dam.md):
// the thickness t_s of its clay's shear band, 0 where it has none.
double slide_band_thickness(const Scene& scene) {
  const MaterialSpec& m = scene.materials[scene.bodies.front().material];
  return m.model == MaterialModel::Tresca ? m.band_thickness : 0.0;
}

// The shear rate estimate defaults to the band where the slide's clay has a
// band thickness, so that t_s means in the DAM what it means in the MPM
// (docs/dam.md, "Shear strain rate"); without one there is no length for it.
DamSpec read_dam(TableReader r, const Scene& scene) {
  r.check_keys({"shear_rate", "earth_pressure", "elements", "water_density", "skin_friction",
                "pressure_drag", "added_mass"});
  DamSpec dam;
  const double band = slide_band_thickness(scene);
  if (band > 0.0) dam.shear_rate = ShearRateEstimate::Band;
  if (auto v = r.find("shear_rate")) {
    dam.shear_rate = v->choice(scene_text::kShearRateNames).value;
    if (dam.shear_rate == ShearRateEstimate::Band && !(band > 0.0))
      v->fail("\"band\" needs band_thickness in the material of the first body (the slide)");
  }
  if (auto v = r.find("earth_pressure"))
    dam.earth_pressure = v->choice(scene_text::kEarthPressureNames).value;
  if (auto v = r.find("elements")) dam.elements = v->integer(at_least(0));
  if (auto v = r.find("water_density")) dam.water_density = v->number(above(0.0));
  if (auto v = r.find("skin_friction")) dam.skin_friction = v->number(at_least(0.0));
  if (auto v = r.find("pressure_drag")) dam.pressure_drag = v->number(at_least(0.0));
  if (auto v = r.find("added_mass")) dam.added_mass = v->number(at_least(0.0));
  return dam;
}

OutputSpec read_output(TableReader r) {
  r.check_keys({"compress"});
  OutputSpec output;
  if (auto v = r.find("compress")) output.compress = v->boolean();
  return output;
}

std::vector<std::string> read_run(TableReader r) {
  r.check_keys({"overrides"});
  if (auto v = r.find("overrides")) return v->strings();
  return {};
}

[[noreturn]] void throw_syntax_error(const std::string& source_name,
                                     const toml::parse_error& e) {
  throw_error(source_name, static_cast<int>(e.source().begin.line), "syntax error",
              std::string(e.description()));
}

toml::table parse_toml(std::string_view text, const std::string& source_name) {
#if TOML_EXCEPTIONS
  try {
    return toml::parse(text, source_name);
  } catch (const toml::parse_error& e) {
    throw_syntax_error(source_name, e);
  }
#else
  toml::parse_result result = toml::parse(text, source_name);
  if (!result) throw_syntax_error(source_name, result.error());
  return std::move(result).table();
#endif
}

// Command-line values have no line: the flag names them instead.
template <class Number>
void check_override(const char* flag, Number value, const Range& range) {
  const double v = static_cast<double>(value);
  if (!std::isfinite(v) || !range.contains(v))
    throw_error("", 0, flag, "must be " + range.describe() + " (got " + format_number(v) + ")");
}

}  // namespace

Scene parse_scene(std::string_view text, const std::string& source_name) {
  const toml::table root_table = parse_toml(text, source_name);
  const TableReader root(root_table, "", source_name, 1);
  root.check_keys({"scene", "grid", "boundary", "time", "gravity", "solver",
                   "material", "body", "base", "dam", "output", "run"});
  Scene scene;
  read_scene_info(root.need("scene").table(), scene);
  scene.grid = read_grid(root.need("grid").table());
  const TableReader boundary = root.optional_table("boundary");
  scene.boundary = read_boundary(boundary);
  if (auto base = root.find("base")) {
    scene.base = read_base(base->table(), scene.grid);
    free_bottom_for_base(boundary, scene.boundary);
  }
  scene.solver = read_solver(root.optional_table("solver"));
  scene.time = read_time(root.need("time").table(), scene.grid, scene.solver);
  scene.gravity = read_gravity(root.optional_table("gravity"));
  scene.materials = read_materials(root);
  scene.bodies = read_bodies(root, scene.materials, scene.grid);
  check_periodic(boundary, scene);
  if (auto base = root.find("base")) check_clay_band(base->table(), scene);
  scene.dam = read_dam(root.optional_table("dam"), scene);
  scene.output = read_output(root.optional_table("output"));
  scene.overrides = read_run(root.optional_table("run"));
  return scene;
}

namespace {

// Closes a descriptor when it goes out of scope.
struct FdCloser {
  int fd;
  ~FdCloser() { ::close(fd); }
};

// The whole of an open regular file of `size` bytes.
std::string read_all(int fd, std::size_t size, const std::string& path) {
  std::string text(size, '\0');
  std::size_t at = 0;
  while (at < size) {
    const ssize_t n = ::read(fd, text.data() + at, size - at);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0)
      throw SceneFileError("cannot read scene file '" + path + "': " + std::strerror(errno));
    if (n == 0) break;  // shrunk while read: what is there
    at += static_cast<std::size_t>(n);
  }
  text.resize(at);
  return text;
}

}  // namespace

std::string read_scene_text(const std::string& path) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer before fstat
  // refuses it.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0)
    throw SceneFileError("cannot open scene file '" + path + "': " + std::strerror(errno));
  const FdCloser closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode))
    throw SceneFileError("scene file '" + path +
                         "' is not a regular file (a folder, a device or a pipe)");
  if (static_cast<std::uint64_t>(st.st_size) > kMaxSceneBytes)
    throw SceneFileError("scene file '" + path + "' is " + std::to_string(st.st_size) +
                         " bytes, more than a scene may be (" + std::to_string(kMaxSceneBytes) +
                         " bytes, 16 MiB)");
  return read_all(fd, static_cast<std::size_t>(st.st_size), path);
}

Scene load_scene_file(const std::string& path) { return parse_scene(read_scene_text(path), path); }

void apply_overrides(Scene& scene, std::optional<double> cell_size, std::optional<int> ppc,
                     std::optional<double> end_time) {
  if (cell_size) {
    check_override("--cell", *cell_size, above(0.0));
    const Eigen::Array2d extent = (scene.grid.max - scene.grid.min).array();
    if ((extent < *cell_size).any())
      throw_error("", 0, "--cell", "is larger than the domain grid.min to grid.max (" +
                                       format_number(extent.x()) + " m x " +
                                       format_number(extent.y()) + " m)");
    scene.grid.cell_size = *cell_size;
    snap_max_to_node(scene.grid);
    scene.overrides.push_back("grid.cell_size = " + format_number(*cell_size));
  }
  if (ppc) {
    check_override("--ppc", *ppc, kPpcRange);
    scene.grid.ppc = *ppc;
    scene.overrides.push_back("grid.ppc = " + std::to_string(*ppc));
  }
  if (end_time) {
    check_override("--end", *end_time, at_least(scene.time.output_interval));
    const std::string frames = too_many_frames(*end_time, scene.time.output_interval);
    if (!frames.empty()) throw_error("", 0, "--end", frames);
    scene.time.end = *end_time;
    scene.overrides.push_back("time.end = " + format_number(*end_time));
  }
}

namespace {

// A named value given on the command line, checked as the parser checks
// it, against the same table.
template <class Names>
auto lookup(const char* flag, const Names& names, const std::string& text) {
  std::string allowed;
  for (const auto& entry : names) {
    if (entry.name == text) return entry.value;
    allowed += (allowed.empty() ? "" : ", ") + in_quotes(entry.name);
  }
  throw_error("", 0, flag, "must be one of " + allowed + " (got " + in_quotes(text) + ")");
}

}  // namespace

void apply_shape_override(Scene& scene, const std::optional<std::string>& shape) {
  if (!shape) return;
  scene.grid.shape = lookup("--shape", scene_text::kShapeNames, *shape);
  scene.overrides.push_back("grid.shape = " + in_quotes(*shape));
}

void apply_method_overrides(Scene& scene, const std::optional<std::string>& method,
                            const std::optional<std::string>& shear_rate,
                            std::optional<int> elements) {
  if (method) {
    scene.method = lookup("--method", scene_text::kMethodNames, *method);
    scene.overrides.push_back("scene.method = " + in_quotes(*method));
  }
  if (shear_rate) {
    scene.dam.shear_rate = lookup("--shear-rate", scene_text::kShearRateNames, *shear_rate);
    scene.overrides.push_back("dam.shear_rate = " + in_quotes(*shear_rate));
  }
  if (elements) {
    check_override("--elements", *elements, at_least(0));
    scene.dam.elements = *elements;
    scene.overrides.push_back("dam.elements = " + std::to_string(*elements));
  }
}

}  // namespace runout
