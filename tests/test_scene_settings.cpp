// `runout study --set`: a scene key by its table path, set in the scene's
// TOML and parsed again, and refused, naming the key, where the path leads
// nowhere or the scene refuses the value.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "runout/scene/scene_parser.hpp"
#include "runout/scene/scene_settings.hpp"

using namespace runout;

namespace {

const std::string kScene = std::string(RUNOUT_SOURCE_DIR) + "/scenes/case1_elongation.toml";

std::string case1_text() {
  std::ifstream in(kScene, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The message of the refusal of these settings; empty when they are taken.
std::string refusal(const std::vector<SceneSetting>& settings) {
  try {
    scene_with_settings(case1_text(), kScene, settings);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SceneSettings, SetsAKeyByItsTablePath) {
  const Scene plain = load_scene_file(kScene);
  const Scene s = scene_with_settings(case1_text(), kScene,
                                      {{"material.clay.su0", "3000"},
                                       {"base.shear_strength", "1.5e3"},
                                       {"time.end", "12"}});
  EXPECT_EQ(s.materials[0].su0, 3000.0);
  EXPECT_EQ(s.base.shear_strength, 1500.0);
  EXPECT_EQ(s.time.end, 12.0);
  // Everything else as the file has it.
  EXPECT_EQ(s.grid.cell_size, plain.grid.cell_size);
  EXPECT_EQ(s.materials[0].density, plain.materials[0].density);
  EXPECT_EQ(to_toml(scene_with_settings(case1_text(), kScene, {})), to_toml(plain));
  // An element of an array of tables by its index, and a bare word as a string.
  EXPECT_EQ(scene_with_settings(case1_text(), kScene, {{"material.0.su0", "2000"}}).materials[0].su0,
            2000.0);
  EXPECT_EQ(scene_with_settings(case1_text(), kScene, {{"grid.shape", "linear"}}).grid.shape,
            ShapeKind::Linear);
  // A table the file leaves out ([output]) is added with the key.
  EXPECT_FALSE(scene_with_settings(case1_text(), kScene, {{"output.compress", "false"}})
                   .output.compress);
}

TEST(SceneSettings, RefusalsNameTheKey) {
  EXPECT_EQ(refusal({{"material.clay.su1", "5"}}),
            "--set material.clay.su1=5: material[0].su1: unknown key");
  EXPECT_EQ(refusal({{"material.clay.su0", "-5"}}),
            "--set material.clay.su0=-5: material[0].su0: must be > 0 (got -5)");
  EXPECT_EQ(refusal({{"base.shear_strength", "soft"}}),
            "--set base.shear_strength=soft: base.shear_strength: expected a number, got string");
  EXPECT_EQ(refusal({{"material.sand.su0", "5"}}),
            "--set material.sand.su0=5: no [[material]] named or numbered sand");
  EXPECT_EQ(refusal({{"grid", "3"}}), "--set grid=3: grid is a table, not a value");
  EXPECT_EQ(refusal({{"material", "3"}}), "--set material=3: material is a table, not a value");
  EXPECT_EQ(refusal({{"time.foo.bar", "1"}}), "--set time.foo.bar=1: time.foo: unknown key");
  EXPECT_EQ(refusal({{"base..x", "1"}}), "--set base..x=1: an empty key in the path");
  // Of two settings, the one refused on its own is named.
  EXPECT_EQ(refusal({{"base.shear_strength", "800"}, {"material.clay.su0", "0"}}),
            "--set material.clay.su0=0: material[0].su0: must be > 0 (got 0)");
}

TEST(SceneSettings, ListsSplitAtCommas) {
  const auto [key, values] = parse_setting_list("material.clay.su0=2000,2500,3000");
  EXPECT_EQ(key, "material.clay.su0");
  EXPECT_EQ(values, (std::vector<std::string>{"2000", "2500", "3000"}));
  for (const char* bad : {"material.clay.su0", "=5", "base.shear_strength=", "a=1,,2", "a=1,"})
    EXPECT_THROW(parse_setting_list(bad), SceneError) << bad;
}
