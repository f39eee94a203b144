// `tandem export`: runs a scene, samples it at a frame rate and writes glTF or OBJ frames.
#include "export_command.h"

#include "scene_loading.h"

#include "export/run_frames.h"
#include "export/scene_export.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include <unistd.h>

namespace tandem::cli {
namespace {

struct ExportOptions {
  std::string scene;
  std::string out;
  double fps = 30.0;
  double seconds = 0.0;  // 0: the scene's duration
  int iterations = 0;
};

int exportRun(const ExportOptions& options) {
  if (!std::isfinite(options.fps) || !std::isfinite(options.seconds)) {  // CLI11's ranges let NaN through
    std::fprintf(stderr, "tandem: --fps and --seconds must be finite numbers\n");
    return 2;
  }
  const std::filesystem::path out(options.out);
  const bool folder = options.out.ends_with('/') || (!out.has_extension() && std::filesystem::is_directory(out));
  const bool gltf = out.extension() == ".gltf" || out.extension() == ".glb";
  if (!folder && !gltf) {
    std::fprintf(stderr, "tandem: --out %s: give FILE.gltf, FILE.glb or a folder (DIR/) for OBJ frames\n",
                 options.out.c_str());
    return 2;
  }
  if (folder) {
    std::error_code error;
    std::filesystem::create_directories(out, error);
    if (error) {
      std::fprintf(stderr, "tandem: cannot make the folder %s: %s\n", options.out.c_str(), error.message().c_str());
      return 2;
    }
  }
  World world;
  const std::optional<SceneInfo> scene = buildInto(world, options.scene);
  if (!scene || !overrideSolver(world, options.iterations)) return 1;
  const double seconds = options.seconds > 0 ? options.seconds : scene->duration;
  const bool progress = isatty(fileno(stderr));
  Result<std::vector<exporting::Frame>> frames =
      exporting::captureRun(world, scene->timeStep, options.fps, seconds, [&](int done, int total) {
        if (!progress) return;
        std::fprintf(stderr, "\r  [%-40s] %d/%d frames", std::string(40 * done / total, '#').c_str(), done, total);
        if (done == total) std::fprintf(stderr, "\n");
      });
  if (!frames) {
    std::fprintf(stderr, "tandem: %s\n", frames.message().c_str());
    return 1;
  }
  const exporting::ExportLooks looks{scene->rigidColours, scene->deformableColours};
  const Status written = folder ? exporting::writeObjFrames(world, *frames, looks, options.out)
                                : exporting::writeGltf(world, *frames, looks, options.out);
  if (!written) {
    std::fprintf(stderr, "tandem: %s\n", written.message().c_str());
    return 1;
  }
  std::printf("Exported %zu frames of '%s' (t = 0 to %.3f s at %g frames per second) to %s\n", frames->size(),
              scene->name.c_str(), frames->back().time, options.fps, options.out.c_str());
  return 0;
}

}  // namespace

std::function<int()> addExportCommand(CLI::App& app) {
  auto options = std::make_shared<ExportOptions>();
  CLI::App* command = app.add_subcommand(
      "export", "Run a scene and write it for other tools: glTF 2.0 (Blender, three.js) or an OBJ per frame");
  command->add_option("scene", options->scene, "A scene file (.json) or a built-in scene's name")->required();
  command->add_option("--out", options->out, "FILE.gltf (with FILE.bin), FILE.glb, or DIR/ (frame_00000.obj, ...)")
      ->required();
  command->add_option("--fps", options->fps, "Frames per simulated second")->check(CLI::Range(0.1, 1000.0));
  command->add_option("--seconds", options->seconds, "Simulated seconds (default: the scene's duration)")
      ->check(CLI::Range(1e-6, 1e5));
  command->add_option("--iterations", options->iterations, "Solver iterations K")->check(CLI::Range(1, 1000));
  return [=]() { return command->parsed() ? exportRun(*options) : -1; };
}

}  // namespace tandem::cli
