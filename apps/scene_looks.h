// A scene file's colours handed to the renderer (by body index, as the scene built them).
#pragma once

#include "scene_loading.h"

#include "render/renderer.h"

namespace tandem::cli {

inline void applySceneColours(const SceneInfo& scene, render::RenderOptions& options) {
  auto convert = [](const std::vector<std::optional<std::array<double, 3>>>& colours) {
    std::vector<std::optional<render::Rgb>> out;
    for (const auto& c : colours)
      out.push_back(c ? std::optional<render::Rgb>(render::Rgb{float((*c)[0]), float((*c)[1]), float((*c)[2])})
                      : std::nullopt);
    return out;
  };
  options.rigidColours = convert(scene.rigidColours);
  options.deformableColours = convert(scene.deformableColours);
}

}  // namespace tandem::cli
