#include "scene_loading.h"

#include <tandem/scene_file.h>
#include <tandem/scenes.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

namespace tandem::cli {
namespace {
bool isSceneFile(const std::string& scene) {
  return scene.ends_with(".json") || scene.find('/') != std::string::npos || std::filesystem::is_regular_file(scene);
}
}  // namespace

std::optional<SceneInfo> buildInto(World& world, const std::string& scene) {
  if (isSceneFile(scene)) {
    Result<Scene> loaded = loadScene(scene);
    Status built = loaded ? buildScene(*loaded, world) : loaded.status();
    if (!built) {
      std::fprintf(stderr, "tandem: %s\n", built.message().c_str());
      return std::nullopt;
    }
    const std::string name = loaded->name.empty() ? std::filesystem::path(scene).stem().string() : loaded->name;
    SceneInfo info{name, loaded->description, loaded->timeStep, loaded->duration, {}, {}};
    for (const SceneRigidBody& body : loaded->rigidBodies) info.rigidColours.push_back(body.colour);
    for (const SceneDeformable& deformable : loaded->deformables) info.deformableColours.push_back(deformable.colour);
    return info;
  }
  const BuiltinScene* builtin = findBuiltinScene(scene);
  if (!builtin) {
    std::fprintf(stderr, "tandem: no scene file or built-in scene named '%s' (see `tandem list`)\n", scene.c_str());
    return std::nullopt;
  }
  if (Status s = builtin->build(world); !s) {
    std::fprintf(stderr, "tandem: scene '%s': %s\n", scene.c_str(), s.message().c_str());
    return std::nullopt;
  }
  return SceneInfo{std::string(builtin->name), std::string(builtin->description), builtin->timeStep,
                   builtin->defaultSeconds, {}, {}};
}

bool overrideSolver(World& world, int iterations, int substeps) {
  if (iterations <= 0 && substeps <= 0) return true;
  WorldSettings settings = world.settings();
  if (iterations > 0) settings.solver.iterations = iterations;
  if (substeps > 0) settings.solver.substeps = substeps;
  if (Status s = world.setSettings(settings); !s) {
    std::fprintf(stderr, "tandem: %s\n", s.message().c_str());
    return false;
  }
  return true;
}

int nodeCount(const World& world) {
  int nodes = 0;
  for (int d = 0; d < world.deformableCount(); ++d)
    nodes += static_cast<int>(world.nodePositions(DeformableId{d}).size());
  return nodes;
}

std::filesystem::path sceneDirectory() {
#ifdef TANDEM_INSTALLED_SCENE_DIR
  std::error_code error;
  const std::filesystem::path command = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) {
    const std::filesystem::path installed = (command.parent_path() / TANDEM_INSTALLED_SCENE_DIR).lexically_normal();
    if (std::filesystem::is_directory(installed, error)) return installed;
  }
#endif
  return TANDEM_SCENE_DIR;
}

std::vector<std::filesystem::path> shippedSceneFiles() {
  std::vector<std::filesystem::path> files;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(sceneDirectory(), error))
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace tandem::cli
