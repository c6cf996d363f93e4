#pragma once
// `runout study --set KEY=VALUE`: any key of a scene file set by its table
// path (material.clay.su0, base.shear_strength, time.end), into the scene's
// TOML, which is then parsed again, so a setting is validated exactly as
// the scene file is (docs/study.md).
#include <string>
#include <string_view>
#include <vector>

#include "runout/scene/scene.hpp"

namespace runout {

// A table path: dotted keys; in an array of tables ([[material]],
// [[body]]) the element is picked by its name or by its index from 0.
struct SceneSetting {
  std::string key;
  std::string value;  // a TOML value (2500, 1e3, true, "coulomb"), or a bare word as a string
};

// "material.clay.su0=2000,2500" -> the key and its values (split at commas).
// Throws SceneError naming the text when there is no '=' or no value.
std::pair<std::string, std::vector<std::string>> parse_setting_list(const std::string& text);

// The scene text with every setting applied and parsed again. Throws
// SceneError "--set KEY=VALUE: why" when the path does not lead to a key
// of the scene (no such table or array element, a table or an array
// where a value is wanted) or when the scene refuses the value (unknown
// key, wrong type, out of range: the parser's message).
Scene scene_with_settings(std::string_view toml_text, const std::string& source,
                          const std::vector<SceneSetting>& settings);

}  // namespace runout
