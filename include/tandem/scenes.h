// Built-in scenes, made through the public API: the demo's flagship and the scenes the tests
// and benchmarks measure.
#pragma once

#include <tandem/export.h>
#include <tandem/world.h>

#include <span>
#include <string_view>

namespace tandem {

struct BuiltinScene {
  std::string_view name;
  std::string_view description;
  double timeStep;        // s
  double defaultSeconds;  // simulated time a demo run covers
  Status (*build)(World& world);
};

TANDEM_API std::span<const BuiltinScene> builtinScenes();
TANDEM_API const BuiltinScene* findBuiltinScene(std::string_view name);

}  // namespace tandem
