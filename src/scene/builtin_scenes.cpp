#include <tandem/scenes.h>

#include <array>

namespace tandem {
namespace {

// Unwraps a Result inside a scene builder, returning its error from the builder.
#define TANDEM_TRY(var, expr)                       \
  auto var##Result = (expr);                        \
  if (!var##Result) return var##Result.status();    \
  auto var = std::move(var##Result).value()

#define TANDEM_CHECK(expr)                          \
  do {                                              \
    if (Status status_ = (expr); !status_) return status_; \
  } while (0)

RigidBodyDesc boxBody(std::string name, const Vec3& halfExtents, double mass, const Vec3& position) {
  RigidBodyDesc desc;
  desc.name = std::move(name);
  desc.shape = RigidShape::box(halfExtents);
  desc.mass = mass;
  desc.position = position;
  return desc;
}

DeformableDesc ropeDesc(std::string name, DeformableMesh mesh) {
  DeformableDesc desc;
  desc.name = std::move(name);
  desc.mesh = std::move(mesh);
  desc.inextensibility.enabled = true;
  return desc;
}

// A 20-node, 1 m, 0.2 kg rope hanging from a fixed point, a 1 kg box anchored at its end.
Status buildHangingRope(World& world) {
  TANDEM_TRY(mesh, makeRope({0, 2, 0}, {0, 1, 0}, 20, 0.2));
  TANDEM_TRY(rope, world.addDeformable(ropeDesc("rope", std::move(mesh))));
  TANDEM_TRY(box, world.addRigidBody(boxBody("box", {0.1, 0.1, 0.1}, 1.0, {0, 0.9, 0})));
  TANDEM_CHECK(world.addFixedPoint(rope, 0, {0, 2, 0}).status());
  TANDEM_CHECK(world.addAnchor(AnchorDesc::node(rope, 19, box)).status());
  return {};
}

// A 5 kg beam on two static supports; a rope from its middle holds a 1 kg box.
Status buildBeamOnSupports(World& world) {
  RigidBodyDesc support = boxBody("support left", {0.1, 0.5, 0.2}, 0, {-0.8, 0.5, 0});
  support.motion = MotionType::Static;
  TANDEM_CHECK(world.addRigidBody(support).status());
  support.name = "support right";
  support.position = {0.8, 0.5, 0};
  TANDEM_CHECK(world.addRigidBody(support).status());
  TANDEM_TRY(beam, world.addRigidBody(boxBody("beam", {1.0, 0.05, 0.1}, 5.0, {0, 1.05, 0})));
  TANDEM_TRY(mesh, makeRope({0, 1.0, 0}, {0, 0.5, 0}, 10, 0.1));
  TANDEM_TRY(rope, world.addDeformable(ropeDesc("rope", std::move(mesh))));
  TANDEM_TRY(box, world.addRigidBody(boxBody("box", {0.1, 0.1, 0.1}, 1.0, {0, 0.4, 0})));
  TANDEM_CHECK(world.addAnchor(AnchorDesc::node(rope, 0, beam)).status());
  TANDEM_CHECK(world.addAnchor(AnchorDesc::node(rope, 9, box)).status());
  return {};
}

// A bar on a hinge through its centre; a rope at one end holds a 1 kg box, so the bar turns.
Status buildHingedBar(World& world) {
  TANDEM_TRY(bar, world.addRigidBody(boxBody("bar", {0.5, 0.025, 0.025}, 1.0, {0, 2, 0})));
  TANDEM_CHECK(world.addHinge({bar, std::nullopt, {0, 2, 0}, {0, 0, 1}}).status());
  TANDEM_TRY(mesh, makeRope({0.5, 2, 0}, {0.5, 1.5, 0}, 10, 0.1));
  TANDEM_TRY(rope, world.addDeformable(ropeDesc("rope", std::move(mesh))));
  TANDEM_TRY(box, world.addRigidBody(boxBody("box", {0.1, 0.1, 0.1}, 1.0, {0.5, 1.4, 0})));
  TANDEM_CHECK(world.addAnchor(AnchorDesc::node(rope, 0, bar)).status());
  TANDEM_CHECK(world.addAnchor(AnchorDesc::node(rope, 9, box)).status());
  return {};
}

// The flagship: a 21×21 cloth curtain hangs from a rigid rod, which hangs on two ropes from
// the ceiling; a 1 kg weight is tied to one bottom corner. Everything is coupled two-way: the
// weight pulls the cloth, the cloth tilts the rod, the rod swings on the ropes.
Status buildCurtain(World& world) {
  TANDEM_TRY(rod, world.addRigidBody(boxBody("rod", {1.1, 0.025, 0.025}, 2.0, {0, 2.0, 0})));
  for (int side : {-1, 1}) {
    TANDEM_TRY(mesh, makeRope({side * 1.0, 3.0, 0}, {side * 1.0, 2.0, 0}, 15, 0.05));
    TANDEM_TRY(rope, world.addDeformable(ropeDesc(side < 0 ? "rope left" : "rope right", std::move(mesh))));
    TANDEM_CHECK(world.addFixedPoint(rope, 0, {side * 1.0, 3.0, 0}).status());
    TANDEM_CHECK(world.addAnchor(AnchorDesc::node(rope, 14, rod)).status());
  }
  constexpr int kSide = 21;
  TANDEM_TRY(clothMesh, makeClothGrid({-0.9, 0.15, 0}, {1.8, 0, 0}, {0, 1.8, 0}, kSide, kSide, 0.5));
  DeformableDesc cloth;
  cloth.name = "curtain";
  cloth.mesh = std::move(clothMesh);
  cloth.inextensibility.enabled = true;
  cloth.bending.enabled = true;
  cloth.bending.maxForce = 0.5;
  TANDEM_TRY(curtain, world.addDeformable(cloth));
  for (int column = 0; column < kSide; ++column)
    TANDEM_CHECK(world.addAnchor(AnchorDesc::node(curtain, (kSide - 1) * kSide + column, rod)).status());
  TANDEM_TRY(weight, world.addRigidBody(boxBody("weight", {0.1, 0.1, 0.1}, 1.0, {0.9, 0.05, 0})));
  TANDEM_CHECK(world.addAnchor(AnchorDesc::node(curtain, kSide - 1, weight)).status());
  // A push out of the curtain's plane, so it swings.
  for (int node = 0; node < kSide * kSide; ++node) TANDEM_CHECK(world.setNodeVelocity(curtain, node, {0, 0, 1.0}));
  return {};
}

constexpr std::array kScenes{
    BuiltinScene{"curtain", "21x21 cloth on a rigid rod hung by two ropes, a 1 kg weight at one corner", 1.0 / 60,
                 10.0, buildCurtain},
    BuiltinScene{"hanging_rope", "20-node rope from a fixed point holding a 1 kg box", 1.0 / 60, 5.0,
                 buildHangingRope},
    BuiltinScene{"beam_on_supports", "5 kg beam on two static supports, a rope from its middle holds a 1 kg box",
                 1.0 / 60, 3.0, buildBeamOnSupports},
    BuiltinScene{"hinged_bar", "a bar hinged at its centre turned by a rope and box at one end", 1.0 / 60, 3.0,
                 buildHingedBar},
};

}  // namespace

std::span<const BuiltinScene> builtinScenes() { return kScenes; }

const BuiltinScene* findBuiltinScene(std::string_view name) {
  for (const BuiltinScene& scene : kScenes)
    if (scene.name == name) return &scene;
  return nullptr;
}

}  // namespace tandem
