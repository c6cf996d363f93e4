#pragma once
// The scene of a command that takes one (run, check, study): its file or
// the built-in default scene, parsed, with the options that override it.
#include <optional>
#include <string>

#include "runout/run/memory_estimate.hpp"
#include "runout/scene/scene.hpp"

namespace runout::cli {

// The options of `runout run` that replace a scene's own settings; empty:
// the scene's.
struct SceneOverrides {
  std::optional<double> cell;
  std::optional<int> ppc;
  std::optional<double> end;
  std::optional<std::string> method, shear_rate, shape;
  std::optional<int> elements;
};

// The text of the scene file at `path`, named by its path, or of the
// built-in default scene (default.toml) where `path` is empty. Throws
// SceneFileError for a file that cannot be read.
SceneSource scene_source(const std::string& path);

// The scene of `source` as `runout run` runs it with `overrides`. Throws
// SceneError for a scene or an override it cannot take.
Scene load_scene(const SceneSource& source, const SceneOverrides& overrides = {});

}  // namespace runout::cli
