// A program that uses an installed Tandem, as a user's would: a 1 m rope from a fixed point holds
// a 1 kg box. It checks what the physics says (the box hangs 1 m below the fixed point, plus its
// half height; the fixed point carries rope and box, the anchor the box) and exits non-zero
// if anything is off. Built by tests/consumer_cmake.sh (find_package) and
// tests/consumer_pkg_config.sh (pkg-config).
#include <tandem/record.h>
#include <tandem/scene_file.h>
#include <tandem/scenes.h>
#include <tandem/shape_surface.h>
#include <tandem/version.h>
#include <tandem/world.h>

#include <cmath>
#include <cstdio>
#include <cstring>

namespace {

int failures = 0;

void expectNear(const char* what, double value, double expected, double tolerance) {
  const bool ok = std::abs(value - expected) <= tolerance;
  std::printf("%-34s %10.5f  (expected %.5f +- %.5f)%s\n", what, value, expected, tolerance, ok ? "" : "  WRONG");
  if (!ok) ++failures;
}

}  // namespace

int main() {
  using namespace tandem;
  std::printf("Tandem %s (headers %s)\n", version(), TANDEM_VERSION_STRING);
  if (std::strcmp(version(), TANDEM_VERSION_STRING) != 0) ++failures;

  constexpr double h = 1.0 / 60, g = 9.81;
  World world;
  DeformableDesc rope;
  rope.name = "rope";
  rope.mesh = *makeRope({0, 2, 0}, {0, 1, 0}, 20, 0.2);
  rope.inextensibility.enabled = true;
  const DeformableId ropeId = *world.addDeformable(rope);

  RigidBodyDesc box;
  box.name = "box";
  box.shape = RigidShape::box({0.1, 0.1, 0.1});
  box.mass = 1.0;
  box.position = {0, 0.9, 0};
  const RigidBodyId boxId = *world.addRigidBody(box);
  const FixedPointId top = *world.addFixedPoint(ropeId, 0, {0, 2, 0});
  const AnchorId knot = *world.addAnchor(AnchorDesc::node(ropeId, 19, boxId));

  for (int i = 0; i < 120; ++i)
    if (Status s = world.step(h); !s) {
      std::printf("step %d failed: %s\n", i, s.message().c_str());
      return 1;
    }
  expectNear("box height (m)", world.rigidPosition(boxId).y(), 2.0 - 1.0 - 0.1, 0.01);
  expectNear("box speed (m/s)", world.rigidLinearVelocity(boxId).norm(), 0.0, 0.01);
  expectNear("fixed point force (N)", world.fixedPointImpulse(top).y() / h, (0.2 + 1.0) * g, 0.02 * 1.2 * g);
  expectNear("anchor force on the rope (N)", world.anchorState(knot).impulse.y() / h, -1.0 * g, 0.02 * g);

  // Bad input is an error with a message, not a crash.
  const Result<DeformableMesh> bad = makeRope({0, 0, 0}, {1, 0, 0}, 1, 0.1);
  std::printf("a one-node rope: %s\n", bad.message().c_str());
  if (bad.ok()) ++failures;

  // The rest of the public API links: built-in scenes, scene files, shapes as triangles.
  World pendulum;
  const BuiltinScene* scene = findBuiltinScene("hanging_rope");
  if (!scene || !scene->build(pendulum).ok()) ++failures;
  const Result<Scene> notJson = parseScene("{", "broken.json", ".");
  std::printf("a broken scene file: %s\n", notJson.message().c_str());
  if (notJson.ok()) ++failures;
  expectNear("box surface triangles", static_cast<double>(shapeSurface(box.shape).triangles.size()), 12, 0);

  std::printf("%s\n", failures == 0 ? "consumer: all as expected" : "consumer: WRONG");
  return failures == 0 ? 0 : 1;
}
