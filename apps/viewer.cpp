// The interactive viewer: a GLFW window, the shared renderer, Dear ImGui panels.
//
// Mouse: left-drag on a body grabs it (a grab row pulls the picked point towards the cursor,
// kept at the depth where it was picked); left-drag elsewhere orbits; right- or middle-drag
// pans; the wheel zooms. Keys: space pauses, S steps, R resets, W wireframe, Escape quits.
// SIGTERM or SIGINT (Ctrl-C) quits the same way, after the frame being drawn: a script that
// drives the window tells the viewer when it is done instead of racing a wall-clock limit.
// SIGUSR1 prints the simulated time ("simulated T s") after the frame being drawn: such a script
// waits for simulated seconds, which a loaded machine stretches, not for wall-clock ones.
#include "viewer.h"

#include "exit_codes.h"
#include "scene_loading.h"
#include "scene_looks.h"

#include "render/camera.h"
#include "render/gl.h"
#include "render/image_output.h"
#include "render/offscreen.h"
#include "render/renderer.h"

#include <tandem/scenes.h>

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace tandem::cli {
namespace {

using Clock = std::chrono::steady_clock;

volatile std::sig_atomic_t quitRequested = 0;  // set by SIGTERM or SIGINT
extern "C" void requestQuit(int) { quitRequested = 1; }
volatile std::sig_atomic_t timeRequested = 0;  // set by SIGUSR1
extern "C" void requestTime(int) { timeRequested = 1; }

// Every scene the picker offers: the built-ins, then the shipped scene files.
std::vector<std::string> availableScenes() {
  std::vector<std::string> scenes;
  for (const BuiltinScene& scene : builtinScenes()) scenes.emplace_back(scene.name);
  for (const std::filesystem::path& file : shippedSceneFiles()) scenes.push_back(file.string());
  return scenes;
}

double g_wheelSteps = 0.0;  // GLFW's scroll callback adds here; the frame loop takes it
void onScroll(GLFWwindow*, double, double y) { g_wheelSteps += y; }

constexpr int kMaxStepsPerFrame = 4;  // behind real time by more than this, the viewer slows down
constexpr float kPanelWidth = 380.0f;  // screen units: the panel is a sidebar, the scene is drawn beside it
constexpr size_t kStepHistory = 300;

class Viewer {
 public:
  Viewer(const ViewOptions& options, GLFWwindow* window, std::unique_ptr<render::Renderer> renderer)
      : m_options(options), m_window(window), m_renderer(std::move(renderer)), m_scenes(availableScenes()),
        m_paused(options.paused) {}

  // Builds `scene` afresh, keeping the solver settings the panels set when `keepSettings`.
  bool load(const std::string& scene, bool keepSettings) {
    auto world = std::make_unique<World>();
    const std::optional<SceneInfo> info = buildInto(*world, scene);
    if (!info) {
      m_error = "cannot load " + scene + " (see the terminal)";
      return false;
    }
    if (keepSettings && m_world) {
      WorldSettings settings = world->settings();
      settings.solver = m_world->settings().solver;
      (void)world->setSettings(settings);
    }
    const bool first = !m_world;
    m_renderer->forgetWorld();
    m_world = std::move(world);
    m_info = *info;
    m_scene = scene;
    if (!keepSettings) m_timeStep = info->timeStep;
    m_baumgarte = float(m_world->settings().solver.baumgarte);
    m_grab.reset();
    m_error.clear();
    m_stepMs.clear();
    m_lag = 0.0;
    if (first && m_options.camera.size() == 6) {
      const auto& c = m_options.camera;
      m_camera = render::Camera::lookAt({c[0], c[1], c[2]}, {c[3], c[4], c[5]});
    } else if (!keepSettings || first) {
      const auto [low, high] = render::sceneBounds(*m_world);
      const auto [x, width, height] = sceneViewport();
      m_camera = render::Camera::framing(low, high, double(std::max(width, 1)) / std::max(height, 1));
    }
    return true;
  }

  int run() {
    const auto start = Clock::now();
    auto last = start;
    long frame = 0;
    while (!glfwWindowShouldClose(m_window)) {
      glfwPollEvents();
      const auto now = Clock::now();
      const double elapsed = std::chrono::duration<double>(now - last).count();
      last = now;
      handleKeys();
      handleMouse();
      if (!m_paused) advance(std::min(elapsed, 0.25));

      int width = 0, height = 0;
      glfwGetFramebufferSize(m_window, &width, &height);
      const auto [sceneX, sceneWidth, sceneHeight] = sceneViewport();
      if (sceneWidth > 0 && sceneHeight > 0) m_renderer->draw(*m_world, m_camera, sceneWidth, sceneHeight, drawOptions(sceneX));
      drawPanels();
      ++frame;
      if (timeRequested != 0) {
        timeRequested = 0;
        std::printf("simulated %.4f s\n", m_world->time());
        std::fflush(stdout);
      }
      const bool lastFrame =
          quitRequested != 0 || (m_options.frames > 0 && frame >= m_options.frames) ||
          (m_options.maxSeconds > 0 && std::chrono::duration<double>(Clock::now() - start).count() > m_options.maxSeconds);
      if ((lastFrame || glfwWindowShouldClose(m_window)) && !m_options.screenshot.empty())
        if (!screenshot(width, height)) return kExitOutputFailed;
      glfwSwapBuffers(m_window);
      if (lastFrame) break;
    }
    std::printf("Viewed '%s' for %ld frames: %.2f s simulated in %lld steps\n", m_info.name.c_str(), frame,
                m_world->time(), static_cast<long long>(m_world->stepCount()));
    for (int b = 0; b < m_world->rigidBodyCount(); ++b) {
      const RigidBodyId id{b};
      if (m_world->rigidMass(id) == 0) continue;
      const Vec3 p = m_world->rigidPosition(id);
      std::printf("  rigid '%s' at (%.4f, %.4f, %.4f) m\n", m_world->rigidName(id).c_str(), p.x(), p.y(), p.z());
    }
    return m_error.empty() ? kExitSuccess : kExitDiverged;
  }

 private:
  struct Grab {
    GrabId id;
    double depth = 0.0;  // of the picked point along the camera's forward axis
    Vec3 target = Vec3::Zero();
    std::optional<RigidBodyId> rigid;
    std::optional<DeformableId> deformable;
  };
  enum class Drag { None, Grab, Orbit, Pan };

  // Fixed steps of the scene's time step, as many as real time asks, at most a few a frame.
  void advance(double elapsed) {
    m_lag = std::min(m_lag + elapsed, kMaxStepsPerFrame * m_timeStep);
    while (m_lag >= m_timeStep) {
      m_lag -= m_timeStep;
      if (!step()) return;
    }
  }

  bool step() {
    const auto before = Clock::now();
    if (Status s = m_world->step(m_timeStep); !s) {
      m_error = s.message();
      std::fprintf(stderr, "tandem: %s\n", m_error.c_str());
      m_paused = true;
      return false;
    }
    m_stepMs.push_back(float(std::chrono::duration<double, std::milli>(Clock::now() - before).count()));
    if (m_stepMs.size() > kStepHistory) m_stepMs.pop_front();
    return true;
  }

  void handleKeys() {
    if (ImGui::GetIO().WantCaptureKeyboard) return;
    auto pressed = [&](int key) {
      const bool down = glfwGetKey(m_window, key) == GLFW_PRESS;
      const bool was = m_keysDown[key];
      m_keysDown[key] = down;
      return down && !was;
    };
    if (pressed(GLFW_KEY_ESCAPE)) glfwSetWindowShouldClose(m_window, GLFW_TRUE);
    if (pressed(GLFW_KEY_SPACE)) m_paused = !m_paused;
    if (pressed(GLFW_KEY_S) && m_paused) step();
    if (pressed(GLFW_KEY_R)) load(m_scene, true);
    if (pressed(GLFW_KEY_W)) m_wireframe = !m_wireframe;
  }

  // Where the scene is drawn, in framebuffer pixels: right of the panel, as tall as the window
  // (left edge, width, height). A window may have more pixels than screen units.
  std::array<int, 3> sceneViewport() const {
    int width = 0, height = 0, windowWidth = 1, windowHeight = 1;
    glfwGetFramebufferSize(m_window, &width, &height);
    glfwGetWindowSize(m_window, &windowWidth, &windowHeight);
    const int left = std::min(width / 2, static_cast<int>(kPanelWidth * width / std::max(windowWidth, 1)));
    return {left, width - left, height};
  }

  // The cursor in pixels of the scene's viewport (see sceneViewport), and its size.
  std::pair<double, double> cursor(int& width, int& height) const {
    double x = 0, y = 0;
    int windowWidth = 1, windowHeight = 1, framebufferWidth = 0;
    glfwGetCursorPos(m_window, &x, &y);
    glfwGetWindowSize(m_window, &windowWidth, &windowHeight);
    glfwGetFramebufferSize(m_window, &framebufferWidth, &height);
    const auto [left, sceneWidth, sceneHeight] = sceneViewport();
    width = sceneWidth;
    return {x * framebufferWidth / std::max(windowWidth, 1) - left, y * height / std::max(windowHeight, 1)};
  }

  void handleMouse() {
    int width = 0, height = 0;
    const auto [x, y] = cursor(width, height);
    if (width <= 0 || height <= 0) return;
    const bool overPanel = ImGui::GetIO().WantCaptureMouse;
    const bool left = glfwGetMouseButton(m_window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    const bool other = glfwGetMouseButton(m_window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
                       glfwGetMouseButton(m_window, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
    if (m_drag == Drag::None && !overPanel) {
      if (left) startLeftDrag(x, y, width, height);
      else if (other) m_drag = Drag::Pan;
    } else if (m_drag != Drag::None && !left && !other) {
      if (m_grab) (void)m_world->removeGrab(m_grab->id);
      m_grab.reset();
      m_drag = Drag::None;
    }
    const double dx = x - m_lastX, dy = y - m_lastY;
    m_lastX = x;
    m_lastY = y;
    if (m_drag == Drag::Orbit) m_camera.orbit(dx, dy);
    if (m_drag == Drag::Pan) m_camera.pan(dx, dy, height);
    if (m_drag == Drag::Grab && m_grab) {
      const render::Ray ray = m_camera.ray(x, y, width, height);
      const Vec3 forward = (m_camera.target - m_camera.eye()).normalized();
      m_grab->target = ray.origin + ray.direction * (m_grab->depth / ray.direction.dot(forward));
      (void)m_world->setGrabTarget(m_grab->id, m_grab->target);
    }
    if (!overPanel && g_wheelSteps != 0.0) m_camera.zoom(g_wheelSteps);
    g_wheelSteps = 0.0;
  }

  // Picks what is under the cursor: a dynamic body or a deformable is grabbed; anything else
  // (a static body, the sky) starts an orbit.
  void startLeftDrag(double x, double y, int width, int height) {
    m_lastX = x;
    m_lastY = y;
    m_drag = Drag::Orbit;
    const render::Ray ray = m_camera.ray(x, y, width, height);
    const std::optional<RayHit> hit = m_world->castRay(ray.origin, ray.direction);
    if (!hit) return;
    GrabDesc desc;
    desc.target = hit->point;
    desc.frequency = m_grabFrequency;
    double mass = 0.0;
    if (hit->rigid) {
      mass = m_world->rigidMass(*hit->rigid);
      if (mass == 0.0) return;  // static or kinematic: orbit instead
      desc.body = hit->rigid;
      desc.point = hit->point;
    } else {
      desc.deformable = hit->deformable;
      desc.nodes = {hit->nodes[0], hit->nodes[1], hit->nodes[2], -1};
      desc.weights = {hit->weights[0], hit->weights[1], hit->weights[2], 0.0};
      desc.nodeCount = 3;
      for (double inverse : m_world->nodeInverseMasses(*hit->deformable))
        if (inverse > 0) mass += 1.0 / inverse;
    }
    desc.maxForce = std::max(m_grabStrength * mass * m_world->settings().gravity.norm(), 1e-3);
    Result<GrabId> grab = m_world->addGrab(desc);
    if (!grab) {
      m_error = grab.message();
      return;
    }
    const Vec3 forward = (m_camera.target - m_camera.eye()).normalized();
    m_grab = Grab{*grab, (hit->point - m_camera.eye()).dot(forward), hit->point, hit->rigid, hit->deformable};
    m_drag = Drag::Grab;
  }

  render::RenderOptions drawOptions(int viewportX) const {
    render::RenderOptions options;
    applySceneColours(m_info, options);
    options.viewportX = viewportX;
    options.shadows = m_shadows;
    options.wireframe = m_wireframe;
    options.contacts = m_contacts;
    options.forceScale = m_forceScale;
    if (m_grab) {
      options.grabLine = std::make_pair(m_world->grabPoint(m_grab->id), m_grab->target);
      options.highlightRigid = m_grab->rigid;
      options.highlightDeformable = m_grab->deformable;
    }
    return options;
  }

  void drawPanels() {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(kPanelWidth, ImGui::GetIO().DisplaySize.y), ImGuiCond_Always);
    ImGui::Begin("Tandem", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::PushItemWidth(-175);  // room for the labels
    scenePanel();
    solverPanel();
    displayPanel();
    statsPanel();
    ImGui::PopItemWidth();
    ImGui::End();
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  }

  void scenePanel() {
    ImGui::TextWrapped("%s", m_info.description.c_str());
    if (ImGui::BeginCombo("scene", std::filesystem::path(m_scene).filename().string().c_str())) {
      for (const std::string& scene : m_scenes)
        if (ImGui::Selectable(std::filesystem::path(scene).filename().string().c_str(), scene == m_scene))
          load(scene, false);
      ImGui::EndCombo();
    }
    if (ImGui::Button(m_paused ? "Run" : "Pause")) m_paused = !m_paused;
    ImGui::SameLine();
    if (ImGui::Button("Step") && m_paused) step();
    ImGui::SameLine();
    if (ImGui::Button("Reset")) load(m_scene, true);
    ImGui::SameLine();
    ImGui::Text("t = %.2f s", m_world->time());
    if (!m_error.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "%s", m_error.c_str());
  }

  void solverPanel() {
    if (!ImGui::CollapsingHeader("Solver", ImGuiTreeNodeFlags_DefaultOpen)) return;
    WorldSettings settings = m_world->settings();
    SolverSettings& solver = settings.solver;
    bool changed = ImGui::SliderInt("iterations K", &solver.iterations, 1, 50);
    changed |= ImGui::SliderInt("substeps n", &solver.substeps, 1, 16);
    changed |= ImGui::SliderFloat("beta h", &m_baumgarte, 0.0f, 1.0f, "%.2f");
    changed |= ImGui::Checkbox("warm start", &solver.warmStart);
    int friction = solver.friction == FrictionModel::Coulomb ? 0 : 1;
    changed |= ImGui::Combo("friction", &friction, "Coulomb\0pressure (paper)\0");
    solver.friction = friction == 0 ? FrictionModel::Coulomb : FrictionModel::Pressure;
    solver.baumgarte = m_baumgarte;
    if (changed)
      if (Status s = m_world->setSettings(settings); !s) m_error = s.message();
    float stepMs = float(m_timeStep * 1000.0);
    if (ImGui::SliderFloat("time step (ms)", &stepMs, 1.0f, 40.0f, "%.2f")) m_timeStep = stepMs / 1000.0;
    ImGui::SliderFloat("grab frequency (Hz)", &m_grabFrequency, 0.5f, 20.0f, "%.1f");
    ImGui::SliderFloat("grab strength (x weight)", &m_grabStrength, 1.0f, 200.0f, "%.0f");
  }

  void displayPanel() {
    if (!ImGui::CollapsingHeader("Display", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::Checkbox("wireframe", &m_wireframe);
    ImGui::SameLine();
    ImGui::Checkbox("contacts and forces", &m_contacts);
    ImGui::Checkbox("shadows", &m_shadows);
    ImGui::SliderFloat("force arrows (m/N)", &m_forceScale, 0.001f, 1.0f, "%.3f", ImGuiSliderFlags_Logarithmic);
  }

  void statsPanel() {
    if (!ImGui::CollapsingHeader("Stats", ImGuiTreeNodeFlags_DefaultOpen)) return;
    const StepReport& report = m_world->lastReport();
    ImGui::Text("%.0f frames per second (%.1f ms a frame)", ImGui::GetIO().Framerate,
                1000.0f / std::max(ImGui::GetIO().Framerate, 1e-3f));
    ImGui::Text("%d deformables (%d nodes), %d rigid bodies", m_world->deformableCount(), nodeCount(*m_world),
                m_world->rigidBodyCount());
    for (size_t s = 0; s < report.stageSeconds.size(); ++s)
      ImGui::Text("%-20s %7.3f ms", std::string(kStageNames[s]).c_str(), 1000.0 * report.stageSeconds[s]);
    ImGui::Text("rows: %d", report.totalRows());
    for (size_t t = 0; t < report.rowCounts.size(); ++t)
      if (report.rowCounts[t]) ImGui::Text("  %-16s %d", std::string(kRowTypeNames[t]).c_str(), report.rowCounts[t]);
    ImGui::Text("Bullet: %d manifolds, %d joints", report.bulletContactManifolds, report.bulletJoints);
    ImGui::Text("impact zones: %d (%d nodes)", report.impactZones, report.impactZoneNodes);
    std::vector<float> rms(report.rmsDeltaLambda.begin(), report.rmsDeltaLambda.end());
    ImGui::PlotLines("RMS dlambda", rms.data(), int(rms.size()), 0, "per iteration (N s)", 0.0f, FLT_MAX,
                     ImVec2(0, 60));
    std::vector<float> ms(m_stepMs.begin(), m_stepMs.end());
    char overlay[64];
    std::snprintf(overlay, sizeof overlay, "ms per step (last: %.2f)", ms.empty() ? 0.0f : ms.back());
    ImGui::PlotLines("step time", ms.data(), int(ms.size()), 0, overlay, 0.0f, FLT_MAX, ImVec2(0, 60));
  }

  bool screenshot(int width, int height) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    if (Status s = render::writePng(m_options.screenshot, width, height, render::readFramebufferPixels(width, height));
        !s) {
      std::fprintf(stderr, "tandem: %s\n", s.message().c_str());
      return false;
    }
    std::printf("Screenshot %dx%d written to %s\n", width, height, m_options.screenshot.c_str());
    return true;
  }

  const ViewOptions& m_options;
  GLFWwindow* m_window;
  std::unique_ptr<render::Renderer> m_renderer;
  std::vector<std::string> m_scenes;
  bool m_paused;
  std::unique_ptr<World> m_world;
  SceneInfo m_info;
  std::string m_scene;
  double m_timeStep = 1.0 / 60;
  double m_lag = 0.0;
  render::Camera m_camera;
  Drag m_drag = Drag::None;
  std::optional<Grab> m_grab;
  double m_lastX = 0, m_lastY = 0;
  bool m_keysDown[GLFW_KEY_LAST + 1] = {};
  bool m_wireframe = false, m_contacts = false, m_shadows = true;
  float m_forceScale = 0.05f, m_baumgarte = 0.1f, m_grabFrequency = 5.0f, m_grabStrength = 30.0f;
  std::deque<float> m_stepMs;
  std::string m_error;
};

}  // namespace

CLI::App* addViewCommand(CLI::App& app, ViewOptions& options) {
  CLI::App* command = app.add_subcommand("view", "Open a scene in a window: run it in real time, drag bodies with the mouse");
  command->add_option("scene", options.scene, "A scene file (.json) or a built-in scene's name")->required();
  command->add_option("--width", options.width, "Window width in pixels")->check(CLI::Range(64, 8192));
  command->add_option("--height", options.height, "Window height in pixels")->check(CLI::Range(64, 8192));
  command->add_option("--camera", options.camera, "Eye and target: ex,ey,ez,tx,ty,tz (default: framed)")
      ->delimiter(',')
      ->expected(6);
  command->add_flag("--paused", options.paused, "Start paused");
  command->add_option("--frames", options.frames, "Quit after this many frames")->check(CLI::PositiveNumber);
  command->add_option("--max-seconds", options.maxSeconds, "Quit after this many seconds of wall time")
      ->check(CLI::PositiveNumber);
  command->add_option("--screenshot", options.screenshot, "Write the last frame to this PNG when quitting");
  return command;
}

int view(const ViewOptions& options) {
  // First: a script may signal the viewer as soon as its window shows (SIGUSR1's default ends it).
  std::signal(SIGTERM, requestQuit);
  std::signal(SIGINT, requestQuit);
  std::signal(SIGUSR1, requestTime);
  glfwSetErrorCallback([](int code, const char* message) { std::fprintf(stderr, "tandem: GLFW %d: %s\n", code, message); });
  if (!glfwInit()) {
    std::fprintf(stderr, "tandem: the viewer needs a display (set DISPLAY, or use `tandem render` with none)\n");
    return kExitOther;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_SAMPLES, 4);
  GLFWwindow* window = glfwCreateWindow(options.width, options.height, "Tandem", nullptr, nullptr);
  if (!window) {
    glfwTerminate();
    std::fprintf(stderr, "tandem: cannot open an OpenGL 3.3 window\n");
    return kExitOther;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(1);
  glfwSetScrollCallback(window, onScroll);  // before ImGui, which chains it
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left behind
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 330");
  int status = kExitOther;
  {
    Result<std::unique_ptr<render::Renderer>> renderer = render::Renderer::create();
    if (!renderer) {
      std::fprintf(stderr, "tandem: %s\n", renderer.message().c_str());
    } else {
      Viewer viewer(options, window, std::move(renderer).value());
      status = kExitBadInput;
      if (viewer.load(options.scene, false)) {
        glfwSetWindowTitle(window, ("Tandem: " + options.scene).c_str());
        status = viewer.run();
      }
    }
  }
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
  return status;
}

}  // namespace tandem::cli
