#pragma once
// Scene files (TOML, schema in docs/scene-format.md): parsing, validation
// and the resolved form written beside a run's frames.
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "runout/scene/scene.hpp"

namespace runout {

// Any problem with a scene: syntax, unknown key, wrong type, missing key,
// impossible value. what() names the key (dotted path, e.g.
// "body[1].polygon") and the line; line() is 0 when no line applies (file
// missing).
class SceneError : public std::runtime_error {
 public:
  SceneError(const std::string& message, int line)
      : std::runtime_error(message), line_(line) {}
  int line() const { return line_; }

 private:
  int line_;
};

// The scene file does not exist or cannot be read (line() is 0).
class SceneFileError : public SceneError {
 public:
  explicit SceneFileError(const std::string& message) : SceneError(message, 0) {}
};

// source_name is used in messages ("default.toml:12: ...").
Scene parse_scene(std::string_view text, const std::string& source_name);
Scene load_scene_file(const std::string& path);  // throws SceneFileError or SceneError

// The largest scene file read (docs/scene-format.md): a scene is text, and
// a path to something endless (/dev/zero behind a link) must not fill the
// memory.
inline constexpr std::uint64_t kMaxSceneBytes = std::uint64_t{16} << 20;

// The text of the scene file at path; throws SceneFileError unless it is a
// regular file of at most kMaxSceneBytes that can be read.
std::string read_scene_text(const std::string& path);

// The scene with every default filled in, as TOML that parse_scene accepts
// and that reproduces the same Scene.
std::string to_toml(const Scene& scene);

// The built-in default scene (scenes/default.toml embedded at build time).
std::string_view default_scene_toml();

// Command-line overrides (--cell, --ppc, --end); each one is recorded in
// scene.overrides. Throws SceneError for an impossible value.
// --method, --shear-rate and --elements: scene.method, dam.shear_rate and
// dam.elements, by the names the scene file uses; recorded like the others.
// Throws SceneError for an unknown name or a negative count.
void apply_method_overrides(Scene& scene, const std::optional<std::string>& method,
                            const std::optional<std::string>& shear_rate,
                            std::optional<int> elements);
void apply_overrides(Scene& scene, std::optional<double> cell_size, std::optional<int> ppc,
                     std::optional<double> end_time = std::nullopt);
// --shape: grid.shape by its scene-file name ("gimp", "linear"); recorded
// like the others. Throws SceneError for an unknown name.
void apply_shape_override(Scene& scene, const std::optional<std::string>& shape);

}  // namespace runout
