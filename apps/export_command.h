// `tandem export SCENE --out FILE.gltf|FILE.glb|DIR/`: a run written for other tools (glTF 2.0
// for Blender and three.js, or an OBJ per frame). Built when tinygltf is there
// (TANDEM_HAS_EXPORT).
#pragma once

#include <CLI/CLI.hpp>

#include <functional>

namespace tandem::cli {

// Adds the `export` subcommand; the returned function runs it when it was parsed and returns
// the exit status, or -1 when it was not.
std::function<int()> addExportCommand(CLI::App& app);

}  // namespace tandem::cli
