// Draws a World with OpenGL 3.3 core: shaded rigid shapes and deformable surfaces (smooth
// normals, both sides lit, ropes as tubes, open rims as thin tubes so no strip vanishes
// edge-on), shadows of one light from a shadow map, infinite planes as gridded ground,
// optional wireframe, contact points and contact-force arrows. The same renderer serves the viewer's window and
// `tandem render`'s offscreen images. It needs a current GL 3.3 context to be made and used.
#pragma once

#include "render/camera.h"

#include <tandem/world.h>

#include <array>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace tandem::render {

// A body's colour, red, green and blue in [0, 1] as displayed.
using Rgb = std::array<float, 3>;

struct RenderOptions {
  bool wireframe = false;
  bool shadows = true;              // the key light's, from a shadow map
  int viewportX = 0;                // pixels left of the drawing (the viewer's panel)
  // Colours by body index (a scene file's `colour`); unset or missing: the palette below.
  std::vector<std::optional<Rgb>> rigidColours;
  std::vector<std::optional<Rgb>> deformableColours;
  bool contacts = false;            // contact points, and force arrows
  double forceScale = 0.05;         // m of arrow per N of contact force
  std::optional<std::pair<Vec3, Vec3>> grabLine;  // from the grabbed point to the cursor
  std::optional<RigidBodyId> highlightRigid;      // drawn brighter (hovered or grabbed)
  std::optional<DeformableId> highlightDeformable;
};

// Colours (linear RGB in [0, 1]) by body index: warm for deformables, cool for rigid bodies,
// grey for static ones; the tests tell a body's pixels by them.
std::array<float, 3> deformableColour(int index);
std::array<float, 3> rigidColour(int index, bool isStatic);

class Renderer {
 public:
  // Compiles the shaders; an error names what the driver said.
  static Result<std::unique_ptr<Renderer>> create();
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Draws into the bound framebuffer's (options.viewportX, 0, width, height) viewport, clearing
  // the framebuffer first. The key light's shadow map is drawn first, into its own framebuffer.
  // Rigid shapes are turned into meshes once, by body index: call forgetWorld() before drawing
  // a different World with the same renderer.
  void draw(const World& world, const Camera& camera, int width, int height, const RenderOptions& options);
  void forgetWorld();

 private:
  Renderer();
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace tandem::render
