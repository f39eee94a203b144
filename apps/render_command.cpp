// `tandem render SCENE`: frames of a scene drawn offscreen (EGL, no display) by the viewer's
// renderer, written as PNG files or an mp4.
#include "render_command.h"

#include "exit_codes.h"

#include "scene_loading.h"
#include "scene_looks.h"
#include "viewer.h"

#include "render/camera.h"
#include "render/image_output.h"
#include "render/offscreen.h"
#include "render/renderer.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <unistd.h>

namespace tandem::cli {
namespace {

struct RenderCommandOptions {
  std::string scene;
  std::string out;
  int frames = 1;
  double fps = 30.0;
  double start = 0.0;
  int width = 960;
  int height = 540;
  std::vector<double> camera;  // eye x y z, target x y z
  bool wireframe = false;
  bool contacts = false;
  bool follow = false;
  bool noShadows = false;
  int iterations = 0;
};

enum class OutputKind { Png, Folder, Video };

// Steps `world` with `h` until its clock reaches `time` (to within half a step).
Status advanceTo(World& world, double time, double h) {
  while (world.time() + 0.5 * h < time)
    if (Status s = world.step(h); !s) return s;
  return {};
}

int render(const RenderCommandOptions& options) {
  const std::filesystem::path out(options.out);
  OutputKind kind = OutputKind::Folder;
  if (out.extension() == ".png") kind = OutputKind::Png;
  if (out.extension() == ".mp4") kind = OutputKind::Video;
  if (kind == OutputKind::Folder && !options.out.ends_with('/') && out.has_extension()) {
    std::fprintf(stderr, "tandem: --out %s: give FILE.png, FILE.mp4 or a folder (DIR/)\n", options.out.c_str());
    return 2;
  }
  if (kind == OutputKind::Png && options.frames > 1) {
    std::fprintf(stderr, "tandem: --out %s holds one frame; for %d frames give a folder (DIR/) or an .mp4 file\n",
                 options.out.c_str(), options.frames);
    return 2;
  }
  if (kind == OutputKind::Folder) {
    std::error_code error;
    std::filesystem::create_directories(out, error);
    if (error) {
      std::fprintf(stderr, "tandem: cannot make the folder %s: %s\n", options.out.c_str(), error.message().c_str());
      return kExitOutputFailed;
    }
  }

  World world;
  const std::optional<SceneInfo> scene = buildInto(world, options.scene);
  if (!scene) return kExitBadInput;
  if (!overrideSolver(world, options.iterations)) return kExitUsage;
  const double h = scene->timeStep;
  if (Status s = advanceTo(world, options.start, h); !s) {
    std::fprintf(stderr, "tandem: %s\n", s.message().c_str());
    return kExitDiverged;
  }
  render::Camera camera;
  if (options.camera.empty()) {
    const auto [low, high] = render::sceneBounds(world);
    camera = render::Camera::framing(low, high, double(options.width) / options.height);
  } else {
    camera = render::Camera::lookAt(Vec3(options.camera[0], options.camera[1], options.camera[2]),
                                    Vec3(options.camera[3], options.camera[4], options.camera[5]));
  }

  Result<std::unique_ptr<render::OffscreenTarget>> target = render::OffscreenTarget::create(options.width, options.height);
  Result<std::unique_ptr<render::Renderer>> renderer =
      target ? render::Renderer::create() : Result<std::unique_ptr<render::Renderer>>(Error{target.message()});
  if (!renderer) {
    std::fprintf(stderr, "tandem: %s\n", renderer.message().c_str());
    return 1;
  }
  std::unique_ptr<render::VideoWriter> video;
  if (kind == OutputKind::Video) {
    Result<std::unique_ptr<render::VideoWriter>> opened =
        render::VideoWriter::open(options.out, options.width, options.height, options.fps);
    if (!opened) {
      std::fprintf(stderr, "tandem: %s\n", opened.message().c_str());
      return kExitOutputFailed;
    }
    video = std::move(opened).value();
  }

  render::RenderOptions drawing;
  drawing.wireframe = options.wireframe;
  drawing.contacts = options.contacts;
  drawing.shadows = !options.noShadows;
  applySceneColours(*scene, drawing);
  const bool progress = isatty(fileno(stderr)) && options.frames > 1;
  const auto wallStart = std::chrono::steady_clock::now();
  for (int frame = 0; frame < options.frames; ++frame) {
    if (Status s = advanceTo(world, options.start + frame / options.fps, h); !s) {
      std::fprintf(stderr, "\ntandem: %s\n", s.message().c_str());
      return kExitDiverged;
    }
    if (options.follow) render::follow(camera, world, double(options.width) / options.height);
    (*target)->bind();
    (*renderer)->draw(world, camera, options.width, options.height, drawing);
    const std::vector<uint8_t> pixels = (*target)->readPixels();
    Status written;
    if (kind == OutputKind::Video) written = video->write(pixels);
    if (kind == OutputKind::Png) written = render::writePng(options.out, options.width, options.height, pixels);
    if (kind == OutputKind::Folder) {
      char name[32];
      std::snprintf(name, sizeof name, "frame_%05d.png", frame);
      written = render::writePng((out / name).string(), options.width, options.height, pixels);
    }
    if (!written) {
      std::fprintf(stderr, "\ntandem: %s\n", written.message().c_str());
      return kExitOutputFailed;
    }
    if (progress) {
      std::fprintf(stderr, "\r  [%-40s] %d/%d frames", std::string(40 * (frame + 1) / options.frames, '#').c_str(),
                   frame + 1, options.frames);
      std::fflush(stderr);
    }
  }
  if (progress) std::fprintf(stderr, "\n");
  if (video)
    if (Status s = video->close(); !s) {
      std::fprintf(stderr, "tandem: %s\n", s.message().c_str());
      return kExitOutputFailed;
    }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
  std::printf("Rendered %d frame%s of '%s' (t = %.2f to %.2f s) at %dx%d to %s in %.2f s\n", options.frames,
              options.frames == 1 ? "" : "s", scene->name.c_str(), options.start,
              options.start + (options.frames - 1) / options.fps, options.width, options.height, options.out.c_str(),
              wall);
  return 0;
}

}  // namespace

std::function<int()> addRenderCommands(CLI::App& app) {
  auto renderOptions = std::make_shared<RenderCommandOptions>();
  CLI::App* renderCommand =
      app.add_subcommand("render", "Draw a scene's frames with no display: a PNG, a folder of PNGs or an mp4");
  renderCommand->add_option("scene", renderOptions->scene, "A scene file (.json) or a built-in scene's name")
      ->required();
  renderCommand->add_option("--out", renderOptions->out, "FILE.png (one frame), DIR/ (frame_00000.png, ...) or FILE.mp4")
      ->required();
  renderCommand->add_option("--frames", renderOptions->frames, "How many frames")->check(CLI::Range(1, 100000));
  renderCommand->add_option("--fps", renderOptions->fps, "Frames per simulated second")->check(CLI::Range(1.0, 1000.0));
  renderCommand->add_option("--start", renderOptions->start, "Simulated seconds before the first frame")
      ->check(CLI::Range(0.0, 1e6));
  renderCommand->add_option("--width", renderOptions->width, "Pixels")->check(CLI::Range(16, 8192));
  renderCommand->add_option("--height", renderOptions->height, "Pixels")->check(CLI::Range(16, 8192));
  renderCommand->add_option("--camera", renderOptions->camera, "Eye and target: ex,ey,ez,tx,ty,tz (default: framed)")
      ->delimiter(',')
      ->expected(6);
  renderCommand->add_flag("--wireframe", renderOptions->wireframe, "Draw the edges too");
  renderCommand->add_flag("--contacts", renderOptions->contacts, "Draw contact points and force arrows");
  renderCommand->add_flag("--follow", renderOptions->follow,
                          "Turn the camera to keep what moves in view, backing off when it would not fit");
  renderCommand->add_flag("--no-shadows", renderOptions->noShadows, "Draw without the key light's shadows");
  renderCommand->add_option("--iterations", renderOptions->iterations, "Solver iterations K")
      ->check(CLI::Range(1, 1000));

  auto viewOptions = std::make_shared<ViewOptions>();
  CLI::App* viewCommand = addViewCommand(app, *viewOptions);

  return [=]() {
    if (renderCommand->parsed()) return render(*renderOptions);
    if (viewCommand->parsed()) return view(*viewOptions);
    return -1;
  };
}

}  // namespace tandem::cli
