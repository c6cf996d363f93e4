// libFuzzer target: the scene parser on arbitrary bytes (docs/fuzzing.md).
// A SceneError is the expected answer to bad input. Anything else is a bug:
// a crash, another exception, a sanitizer report, or a scene the parser
// accepts whose resolved form (to_toml) it then rejects. A scene small
// enough is seeded too, so the memory estimate and the seeding of any
// outline the parser lets through are exercised as well.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "runout/run/memory_estimate.hpp"
#include "runout/scene/scene_parser.hpp"
#include "runout/mpm/seeding.hpp"

namespace {

// Seeding beyond this would make the fuzzer slow, not find more.
constexpr double kSeedBudgetBytes = 16.0 * 1024 * 1024;

void seed_if_small(const runout::Scene& scene) {
  try {
    runout::require_memory(scene, runout::Method::Mpm, kSeedBudgetBytes);
  } catch (const runout::SceneError&) {
    return;
  }
  runout::seed_particles(scene);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  runout::Scene scene;
  try {
    scene = runout::parse_scene(std::string_view(reinterpret_cast<const char*>(data), size),
                                "fuzz.toml");
  } catch (const runout::SceneError&) {
    return 0;
  }
  const std::string resolved = runout::to_toml(scene);
  try {
    runout::parse_scene(resolved, "resolved.toml");
  } catch (const runout::SceneError& e) {
    std::fprintf(stderr, "the resolved scene does not parse back: %s\n%s\n", e.what(),
                 resolved.c_str());
    std::abort();
  }
  try {
    seed_if_small(scene);
  } catch (const runout::SceneError&) {
    // A body that holds no particle: a scene error found at seeding.
  }
  return 0;
}
