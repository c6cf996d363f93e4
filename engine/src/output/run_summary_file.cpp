#include "runout/output/run_summary_file.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <stdexcept>

#include "runout/output/atomic_file.hpp"
#include "runout/output/checkpoint.hpp"
#include "runout/output/file_text.hpp"
#include "runout/study/study.hpp"

namespace runout {
namespace {

namespace fs = std::filesystem;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// 17 significant digits: a number read back is the number written.
std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// A JSON value of the flat object: a string, or a number (null: NaN).
struct JsonValue {
  bool is_string = false;
  std::string text;
  double number = kNaN;
};

// The one flat object summary.json holds: "key": string | number | null.
class FlatObjectReader {
 public:
  FlatObjectReader(std::string_view json, const std::string& source)
      : s_(json), source_(source) {}

  std::map<std::string, JsonValue> read() {
    std::map<std::string, JsonValue> out;
    expect('{');
    if (peek() == '}') return ++pos_, out;
    for (;;) {
      const std::string key = string();
      expect(':');
      out[key] = value(key);
      if (peek() == ',') {
        ++pos_;
        continue;
      }
      expect('}');
      return out;
    }
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(source_ + ": " + what + " at byte " + std::to_string(pos_));
  }
  char peek() {
    while (pos_ < s_.size() && std::strchr(" \t\r\n", s_[pos_])) ++pos_;
    return pos_ < s_.size() ? s_[pos_] : '\0';
  }
  void expect(char c) {
    if (peek() != c) fail(std::string("expected '") + c + "'");
    ++pos_;
  }
  std::string string() {
    expect('"');
    std::string out;
    while (pos_ < s_.size() && s_[pos_] != '"') {
      char c = s_[pos_++];
      if (c == '\\') {
        if (pos_ >= s_.size()) break;
        c = s_[pos_++];
        if (c == 'u') {
          if (pos_ + 4 > s_.size()) fail("a cut \\u escape");
          c = static_cast<char>(std::stoi(std::string(s_.substr(pos_, 4)), nullptr, 16));
          pos_ += 4;
        } else if (c == 'n') {
          c = '\n';
        } else if (c == 't') {
          c = '\t';
        }
      }
      out += c;
    }
    expect('"');
    return out;
  }
  JsonValue value(const std::string& key) {
    JsonValue v;
    const char c = peek();
    if (c == '"') {
      v.is_string = true;
      v.text = string();
    } else if (s_.compare(pos_, 4, "null") == 0) {
      pos_ += 4;
    } else {
      const std::string rest(s_.substr(pos_, 40));
      char* end = nullptr;
      v.number = std::strtod(rest.c_str(), &end);
      if (end == rest.c_str()) fail("\"" + key + "\": not a string, number or null");
      pos_ += end - rest.c_str();
    }
    return v;
  }

  std::string_view s_;
  std::string source_;
  std::size_t pos_ = 0;
};

}  // namespace

std::string scene_hash_text(std::string_view resolved_toml) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%016llx",
                static_cast<unsigned long long>(scene_hash(resolved_toml)));
  return buf;
}

RunRecord make_run_record(const RunSummary& summary, const std::string& out_dir, Method method,
                          int stop_signal, double peak_memory_mib, const std::string& mechanism) {
  const fs::path dir(out_dir);
  RunRecord r;
  const fs::path resolved = dir / kResolvedSceneFile;
  r.scene_hash =
      scene_hash_text(file_text_or_throw(resolved, "cannot read '" + resolved.string() + "'"));
  if (summary.failed) {
    r.status = "blown_up";
    r.note = summary.failure;
  } else if (stop_signal != 0) {
    r.status = "stopped";
    r.note = "signal " + std::to_string(stop_signal);
  } else {
    r.status = summary.at_rest ? "at_rest" : "completed";
  }
  r.method = method == Method::Dam ? "dam" : "mpm";
  r.particles = summary.particles;
  r.steps = summary.steps;
  r.end_time = summary.end_time;
  r.wall_seconds = summary.wall_seconds;
  r.peak_memory_mib = peak_memory_mib;
  const study::History history = study::read_history((dir / "history.csv").string());
  const study::Metrics m = study::run_metrics(history, {}, summary.at_rest);
  r.runout = m.runout_end;
  r.runout_95 = history.runout_95.empty() ? kNaN : history.runout_95.back();
  r.peak_toe_velocity = m.peak_toe_velocity;
  r.final_length = m.final_length;
  r.stop_time = summary.at_rest ? summary.end_time : kNaN;
  r.mechanism = mechanism;
  return r;
}

std::string to_json(const RunRecord& r) {
  std::string j = "{\n";
  const auto add = [&](const char* key, const std::string& value, bool last = false) {
    j += std::string("  \"") + key + "\": " + value + (last ? "\n" : ",\n");
  };
  add("scene_hash", json_string(r.scene_hash));
  add("status", json_string(r.status));
  add("note", json_string(r.note));
  add("method", json_string(r.method));
  add("particles", std::to_string(r.particles));
  add("steps", std::to_string(r.steps));
  add("end_time", json_number(r.end_time));
  add("wall_seconds", json_number(r.wall_seconds));
  add("peak_memory_mib", json_number(r.peak_memory_mib));
  add("runout", json_number(r.runout));
  add("runout_95", json_number(r.runout_95));
  add("stop_time", json_number(r.stop_time));
  add("peak_toe_velocity", json_number(r.peak_toe_velocity));
  add("final_length", json_number(r.final_length));
  add("mechanism", r.mechanism.empty() ? "null" : json_string(r.mechanism), true);
  return j + "}\n";
}

RunRecord parse_run_record(std::string_view json, const std::string& source) {
  const std::map<std::string, JsonValue> obj = FlatObjectReader(json, source).read();
  const auto get = [&](const char* key, bool want_string) -> const JsonValue& {
    const auto it = obj.find(key);
    if (it == obj.end()) throw std::runtime_error(source + ": no \"" + key + "\"");
    const bool null = !it->second.is_string && std::isnan(it->second.number);
    if (it->second.is_string != want_string && !(null && std::strcmp(key, "mechanism") == 0))
      throw std::runtime_error(source + ": \"" + key + "\" is not a " +
                               (want_string ? "string" : "number"));
    return it->second;
  };
  RunRecord r;
  r.scene_hash = get("scene_hash", true).text;
  r.status = get("status", true).text;
  r.note = get("note", true).text;
  r.method = get("method", true).text;
  r.particles = static_cast<long>(get("particles", false).number);
  r.steps = static_cast<long>(get("steps", false).number);
  r.end_time = get("end_time", false).number;
  r.wall_seconds = get("wall_seconds", false).number;
  r.peak_memory_mib = get("peak_memory_mib", false).number;
  r.runout = get("runout", false).number;
  // Summaries written before the mass front was recorded have none.
  r.runout_95 = obj.count("runout_95") ? get("runout_95", false).number : kNaN;
  r.stop_time = get("stop_time", false).number;
  r.peak_toe_velocity = get("peak_toe_velocity", false).number;
  r.final_length = get("final_length", false).number;
  r.mechanism = get("mechanism", true).text;
  return r;
}

void write_run_record(const std::string& out_dir, const RunRecord& record) {
  write_file_atomically((fs::path(out_dir) / kSummaryFile).string(), to_json(record));
}

RunRecord read_run_record(const std::string& out_dir) {
  const fs::path path = fs::path(out_dir) / kSummaryFile;
  return parse_run_record(file_text_or_throw(path, "cannot read '" + path.string() + "'"),
                          path.string());
}

}  // namespace runout
