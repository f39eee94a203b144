// What every `tandem` command that runs a scene needs: build a scene file or a built-in scene
// into a World, and apply the command line's overrides of its solver settings.
#pragma once

#include <tandem/world.h>

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tandem::cli {

// What a command needs to know about a scene besides the world it built.
struct SceneInfo {
  std::string name;
  std::string description;
  double timeStep = 0;
  double duration = 0;
  // A scene file's colours by body index (built-in scenes have none): unset, the palette's.
  std::vector<std::optional<std::array<double, 3>>> rigidColours;
  std::vector<std::optional<std::array<double, 3>>> deformableColours;
};

// Builds a scene file or a built-in scene into `world`; prints the problem and returns nothing
// when it cannot.
std::optional<SceneInfo> buildInto(World& world, const std::string& scene);

// Sets the solver's iterations and substeps where given (> 0); prints the problem when refused.
bool overrideSolver(World& world, int iterations, int substeps = 0);

int nodeCount(const World& world);

// Where the shipped scene files are: beside an installed `tandem` (PREFIX/share/tandem/scenes),
// else the source tree's scenes/.
std::filesystem::path sceneDirectory();
// The scene files there, sorted by name.
std::vector<std::filesystem::path> shippedSceneFiles();

}  // namespace tandem::cli
