#include "scene_loading.hpp"

#include "runout/scene/scene_parser.hpp"

namespace runout::cli {

SceneSource scene_source(const std::string& path) {
  if (path.empty()) return {"default.toml", std::string(default_scene_toml())};
  return {path, read_scene_text(path)};
}

Scene load_scene(const SceneSource& source, const SceneOverrides& overrides) {
  Scene scene = parse_scene(source.text, source.name);
  apply_overrides(scene, overrides.cell, overrides.ppc, overrides.end);
  apply_method_overrides(scene, overrides.method, overrides.shear_rate, overrides.elements);
  apply_shape_override(scene, overrides.shape);
  return scene;
}

}  // namespace runout::cli
