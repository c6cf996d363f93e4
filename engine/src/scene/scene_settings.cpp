#include "runout/scene/scene_settings.hpp"

#include <sstream>

#include <toml++/toml.h>

#include "runout/scene/scene_parser.hpp"

namespace runout {
namespace {

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, sep);) parts.push_back(part);
  if (!text.empty() && text.back() == sep) parts.emplace_back();
  return parts;
}

[[noreturn]] void refuse(const SceneSetting& s, const std::string& why) {
  throw SceneError("--set " + s.key + "=" + s.value + ": " + why, 0);
}

// The value as TOML reads it, or the text as a string when TOML reads no
// single value from it (a bare word: --set base.interface=coulomb).
toml::table value_node(const SceneSetting& s) {
  try {
    toml::table t = toml::parse("v = " + s.value);
    if (t.size() == 1) return t;
  } catch (const toml::parse_error&) {
  }
  toml::table t;
  t.insert("v", s.value);
  return t;
}

// The element of an array of tables named by `part`: its "name" or its index.
toml::table* element(toml::array& array, const std::string& part) {
  for (toml::node& n : array)
    if (toml::table* t = n.as_table())
      if (const auto name = (*t)["name"].value<std::string>(); name && *name == part) return t;
  char* end = nullptr;
  const long index = std::strtol(part.c_str(), &end, 10);
  if (!part.empty() && *end == '\0' && index >= 0 && index < static_cast<long>(array.size()))
    return array[static_cast<std::size_t>(index)].as_table();
  return nullptr;
}

void apply(toml::table& root, const SceneSetting& s) {
  const std::vector<std::string> parts = split(s.key, '.');
  for (const std::string& p : parts)
    if (p.empty()) refuse(s, "an empty key in the path");
  toml::table* table = &root;
  std::string path;
  for (std::size_t k = 0; k + 1 < parts.size(); ++k) {
    const std::string& part = parts[k];
    path += (path.empty() ? "" : ".") + part;
    toml::node* node = table->get(part);
    if (!node) {  // a table the file leaves out, with all its defaults
      table = table->insert(part, toml::table{}).first->second.as_table();
      continue;
    }
    if (toml::table* t = node->as_table()) {
      table = t;
      continue;
    }
    toml::array* array = node->as_array();
    if (!array || !array->is_array_of_tables()) refuse(s, path + " is a value, not a table");
    if (k + 2 == parts.size()) refuse(s, path + " is an array of tables: name an element of it");
    table = element(*array, parts[++k]);
    if (!table) refuse(s, "no [[" + part + "]] named or numbered " + parts[k]);
    path += "." + parts[k];
  }
  const std::string& last = parts.back();
  if (const toml::node* old = table->get(last); old && (old->is_table() || old->is_array_of_tables()))
    refuse(s, s.key + " is a table, not a value");
  table->insert_or_assign(last, *value_node(s).get("v"));
}

}  // namespace

std::pair<std::string, std::vector<std::string>> parse_setting_list(const std::string& text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw SceneError("--set " + text + ": expected KEY=VALUE[,VALUE...]", 0);
  std::vector<std::string> values = split(text.substr(eq + 1), ',');
  for (const std::string& v : values)
    if (v.empty()) throw SceneError("--set " + text + ": an empty value", 0);
  return {text.substr(0, eq), values};
}

Scene scene_with_settings(std::string_view toml_text, const std::string& source,
                          const std::vector<SceneSetting>& settings) {
  if (settings.empty()) return parse_scene(toml_text, source);
  toml::table root;
  try {
    root = toml::parse(toml_text, source);
  } catch (const toml::parse_error&) {
    return parse_scene(toml_text, source);  // the parser's own message, with its line
  }
  // The paths first: one that leads nowhere is refused on its own.
  for (const SceneSetting& s : settings) {
    toml::table probe = root;
    apply(probe, s);
  }
  const auto parse_with = [&](const std::vector<SceneSetting>& set) {
    toml::table changed = root;
    for (const SceneSetting& s : set) apply(changed, s);
    std::ostringstream text;
    text << toml::toml_formatter(changed);
    return parse_scene(text.str(), source);
  };
  // The parser's message without its "source:line: ": the line is of the
  // scene as re-written, not of the file.
  const auto why = [&](const SceneError& e) {
    const std::string where = source + ":" + std::to_string(e.line()) + ": ", what = e.what();
    return what.rfind(where, 0) == 0 ? what.substr(where.size()) : what;
  };
  try {
    return parse_with(settings);
  } catch (const SceneError& e) {
    // The setting the scene refuses on its own, or else all of them: two
    // values may be refused only together.
    for (const SceneSetting& s : settings) try {
        parse_with({s});
      } catch (const SceneError& alone) {
        refuse(s, why(alone));
      }
    std::string set;
    for (const SceneSetting& s : settings) set += (set.empty() ? "" : ", ") + s.key + "=" + s.value;
    throw SceneError("--set " + set + " together: " + why(e), 0);
  }
}

}  // namespace runout
