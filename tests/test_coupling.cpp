// Two-way coupling between Bullet rigid bodies and deformables, for every kind of rigid body.
#include <tandem/scene_file.h>
#include <tandem/scenes.h>
#include <tandem/world.h>

#include <gtest/gtest.h>

namespace tandem {
namespace {

constexpr double kStep = 1.0 / 60.0;
constexpr double kGravity = 9.81;

RigidBodyDesc box(std::string name, const Vec3& position, double mass = 1.0, const Vec3& half = {0.1, 0.1, 0.1}) {
  RigidBodyDesc desc;
  desc.name = std::move(name);
  desc.shape = RigidShape::box(half);
  desc.mass = mass;
  desc.position = position;
  return desc;
}

DeformableId addRope(World& world, const Vec3& top, const Vec3& bottom, int nodes, double mass) {
  DeformableDesc desc;
  desc.name = "rope";
  desc.mesh = *makeRope(top, bottom, nodes, mass);
  desc.inextensibility.enabled = true;
  return *world.addDeformable(desc);
}

// With n substeps, what a step reports (Bullet's contact impulses, the rope's impulse on the beam)
// is the sum over its n solves.
class SupportsCarry : public testing::TestWithParam<int> {};

TEST_P(SupportsCarry, BeamRopeAndBoxWeight) {
  World world;
  ASSERT_TRUE(findBuiltinScene("beam_on_supports")->build(world).ok());
  WorldSettings settings = world.settings();
  settings.solver.substeps = GetParam();
  ASSERT_TRUE(world.setSettings(settings).ok());
  const RigidBodyId left = *world.findRigidBody("support left");
  const RigidBodyId right = *world.findRigidBody("support right");
  const RigidBodyId beam = *world.findRigidBody("beam");
  const RigidBodyId load = *world.findRigidBody("box");
  for (int step = 0; step < 240; ++step) ASSERT_TRUE(world.step(kStep).ok());  // settle, past Bullet's 2 s to sleep
  // Anchored bodies do not fall asleep on their own: they keep carrying, and reporting, the load.
  EXPECT_TRUE(world.rigidIsAwake(beam));
  EXPECT_TRUE(world.rigidIsAwake(load));
  const Vec3 beamStart = world.rigidPosition(beam), boxStart = world.rigidPosition(load);
  const double weightImpulse = (5.0 + 0.1 + 1.0) * kGravity * kStep;
  for (int step = 0; step < 60; ++step) {
    ASSERT_TRUE(world.step(kStep).ok());
    const double supports = world.rigidContactImpulse(beam, left) + world.rigidContactImpulse(beam, right);
    EXPECT_NEAR(supports, weightImpulse, 0.02 * weightImpulse) << "step " << step;
    // What the rope puts on the beam is the weight of rope and box.
    EXPECT_NEAR(-world.deformableImpulseOnRigid(beam).y(), 1.1 * kGravity * kStep, 0.02 * 1.1 * kGravity * kStep);
  }
  // Nothing creeps.
  EXPECT_LT((world.rigidPosition(beam) - beamStart).norm(), 1e-3);
  EXPECT_LT((world.rigidPosition(load) - boxStart).norm(), 1e-3);
}
INSTANTIATE_TEST_SUITE_P(Coupling, SupportsCarry, testing::Values(1, 4),
                         [](const testing::TestParamInfo<int>& param) { return std::to_string(param.param) + "Substeps"; });

// A 0.3 kg weight hung from one face of a 0.04 kg flag (tests/data/flag_weight.json), started
// 11 cm from where it hangs. The flag's block solves the friction of its contacts with
// the weight; a contact it lets go must take that friction back through the whole block, as it
// was given: taken back on its own 0.4 g node by the sweep instead, it sent the node to 114 m/s
// and threw the weight up at 40 m/s at step 60, its anchor 1.95 m open.
TEST(Coupling, WeightHungFromAClothFaceIsNotThrownWhenItsContactsAreLetGo) {
  Result<Scene> scene = loadScene(std::string(TANDEM_SOURCE_DIR) + "/tests/data/flag_weight.json");
  ASSERT_TRUE(scene.ok()) << scene.message();
  World world;
  ASSERT_TRUE(buildScene(*scene, world).ok());
  const RigidBodyId weight = *world.findRigidBody("weight");
  const AnchorState start = world.anchorState(AnchorId{0});
  const double startGap = (start.worldPointOnBody - start.worldPointOnDeformable).norm();
  double worstGap = 0.0, fastest = 0.0;
  for (int step = 0; step < 150; ++step) {
    ASSERT_TRUE(world.step(scene->timeStep).ok()) << "step " << step;
    const AnchorState anchor = world.anchorState(AnchorId{0});
    worstGap = std::max(worstGap, (anchor.worldPointOnBody - anchor.worldPointOnDeformable).norm());
    fastest = std::max(fastest, world.rigidLinearVelocity(weight).norm());
  }
  EXPECT_LE(worstGap, startGap + 1e-3);  // it closes (0.5 mm more after the first step)
  EXPECT_LT(fastest, 1.5) << "m/s";  // swinging on the flag, not thrown
}

// A direct block starts its anchors to dynamic bodies from last step's impulse (the body's share
// before Bullet's first iteration, the nodes' as a known load in the block's first solve). The
// block is exact, so its answer cannot depend on where it starts: the Atwood machine (a rope over
// a hinged wheel, both loads anchored, its contacts in the block) steps the same with warm
// starting on and off, to rounding and the kept factorisation's refinement. With the kept
// factorisation judged against a scale that held the nodes' load, it let 17 contacts go in one
// sweep and the light load fell.
TEST(Coupling, WarmStartedAnchorsLeaveAnExactBlocksAnswerAsItWas) {
  auto run = [](bool warmStart) {
    Result<Scene> scene = loadScene(std::string(TANDEM_SOURCE_DIR) + "/scenes/gauntlet/atwood.json");
    EXPECT_TRUE(scene.ok()) << scene.message();
    scene->settings.solver.iterations = 4;
    scene->settings.solver.substeps = 1;
    scene->settings.solver.warmStart = warmStart;
    World world;
    EXPECT_TRUE(buildScene(*scene, world).ok());
    for (int step = 0; step < 50; ++step) EXPECT_TRUE(world.step(scene->timeStep).ok());
    std::vector<Vec3> velocities;
    for (const char* name : {"light", "heavy", "wheel"}) {
      velocities.push_back(world.rigidLinearVelocity(*world.findRigidBody(name)));
      velocities.push_back(world.rigidAngularVelocity(*world.findRigidBody(name)));
    }
    for (const Vec3& v : world.nodeVelocities(*world.findDeformable("rope"))) velocities.push_back(v);
    return velocities;
  };
  const std::vector<Vec3> warm = run(true), cold = run(false);
  ASSERT_EQ(warm.size(), cold.size());
  EXPECT_GT(warm[0].norm(), 1.0);  // the light load rising at about 1.35 m/s after 1 s
  for (size_t i = 0; i < warm.size(); ++i) EXPECT_LT((warm[i] - cold[i]).norm(), 1e-6) << "entry " << i;
}

// A rope hung from the end of a hinged bar, a ball on its other end (tests/data/
// rope_on_hinged_bar.json; anchored 9 cm off where it starts, closed in the first steps). The bar swings and turns
// the rope with it; its block moves bar and ball by position with the rope, anchors closed
// too. With the anchors left to their bias, the bar's opened up to 2.5 cm and the ball's 3.2 cm.
TEST(Coupling, RopeOnASwingingHingedBarKeepsItsAnchorsShut) {
  Result<Scene> scene = loadScene(std::string(TANDEM_SOURCE_DIR) + "/tests/data/rope_on_hinged_bar.json");
  ASSERT_TRUE(scene.ok()) << scene.message();
  World world;
  ASSERT_TRUE(buildScene(*scene, world).ok());
  double worstBar = 0.0, worstBall = 0.0;
  for (int step = 0; step < 250; ++step) {
    ASSERT_TRUE(world.step(scene->timeStep).ok()) << "step " << step;
    auto gap = [&](int32_t anchor) {
      const AnchorState state = world.anchorState(AnchorId{anchor});
      return (state.worldPointOnBody - state.worldPointOnDeformable).norm();
    };
    if (step < 10) continue;
    worstBar = std::max(worstBar, gap(0));
    worstBall = std::max(worstBall, gap(1));
  }
  EXPECT_LT(worstBar, 2e-3);  // 0.9 mm
  EXPECT_LT(worstBall, 2e-3);
}

TEST(Coupling, RopeTurnsAHingedBar) {
  World world;
  ASSERT_TRUE(findBuiltinScene("hinged_bar")->build(world).ok());
  const RigidBodyId bar = *world.findRigidBody("bar");
  for (int step = 0; step < 15; ++step) ASSERT_TRUE(world.step(kStep).ok());
  // The load hangs at +x, so the bar turns clockwise about +z.
  EXPECT_LT(world.rigidAngularVelocity(bar).z(), -0.5);
  const double angle = 2.0 * std::atan2(world.rigidOrientation(bar).z(), world.rigidOrientation(bar).w());
  EXPECT_LT(angle, -0.05);
  // And the hinge holds it at its pivot.
  EXPECT_LT((world.rigidPosition(bar) - Vec3(0, 2, 0)).norm(), 5e-3);
}

// A top body of the given motion at y = 2.05, a 0.5 m rope hanging from it, a 1 kg load below.
struct HangingLoad {
  RigidBodyId top, load;
  DeformableId rope;
};
HangingLoad hangLoad(World& world, MotionType topMotion) {
  RigidBodyDesc hook = box("top", {0, 2.05, 0}, 1.0, {0.05, 0.05, 0.05});
  hook.motion = topMotion;
  HangingLoad rig;
  rig.top = *world.addRigidBody(hook);
  rig.rope = addRope(world, {0, 2, 0}, {0, 1.5, 0}, 6, 0.05);
  rig.load = *world.addRigidBody(box("load", {0, 1.4, 0}));
  EXPECT_TRUE(world.addAnchor(AnchorDesc::node(rig.rope, 0, rig.top)).ok());
  EXPECT_TRUE(world.addAnchor(AnchorDesc::node(rig.rope, 5, rig.load)).ok());
  return rig;
}

TEST(Coupling, AnchorToStaticBodyHolds) {
  World world;
  const HangingLoad rig = hangLoad(world, MotionType::Static);
  for (int step = 0; step < 180; ++step) ASSERT_TRUE(world.step(kStep).ok());
  EXPECT_NEAR(world.rigidPosition(rig.load).y(), 1.4, 0.01);
  EXPECT_LT(world.rigidLinearVelocity(rig.load).norm(), 0.01);
  EXPECT_LT((world.rigidPosition(rig.top) - Vec3(0, 2.05, 0)).norm(), 1e-12);
}

TEST(Coupling, KinematicBodyCarriesTheRopeAndLoad) {
  World world;
  const HangingLoad rig = hangLoad(world, MotionType::Kinematic);
  for (int step = 0; step < 60; ++step) ASSERT_TRUE(world.step(kStep).ok());
  // Lift the top at 0.5 m/s for one second: the load follows, 0.5 m higher.
  for (int step = 1; step <= 60; ++step) {
    ASSERT_TRUE(world.setKinematicTarget(rig.top, {0, 2.05 + 0.5 * step * kStep, 0}, Quat::Identity()).ok());
    ASSERT_TRUE(world.step(kStep).ok());
  }
  EXPECT_NEAR(world.rigidPosition(rig.top).y(), 2.55, 1e-9);
  EXPECT_NEAR(world.rigidPosition(rig.load).y(), 1.9, 0.01);
  EXPECT_NEAR(world.rigidLinearVelocity(rig.load).y(), 0.5, 0.05);
}

TEST(Coupling, SleepingBodyHoldsAndWakesWhenTheRopeMoves) {
  World world;
  const RigidBodyId anchorBody = *world.addRigidBody(box("anchor", {0, 2.05, 0}, 5.0, {0.8, 0.05, 0.2}));
  RigidBodyDesc shelf = box("shelf", {0, 1.9, 0}, 0, {0.5, 0.1, 0.5});
  shelf.motion = MotionType::Static;
  ASSERT_TRUE(world.addRigidBody(shelf).ok());
  const DeformableId rope = *world.addDeformable([&] {
    DeformableDesc desc;
    desc.name = "rope";
    desc.mesh = *makeRope({0.7, 2.0, 0}, {0.7, 1.5, 0}, 6, 0.05);  // clear of the shelf
    desc.inextensibility.enabled = true;
    return desc;
  }());
  ASSERT_TRUE(world.addAnchor(AnchorDesc::node(rope, 0, anchorBody)).ok());
  ASSERT_TRUE(world.putRigidToSleep(anchorBody).ok());
  for (int step = 0; step < 60; ++step) ASSERT_TRUE(world.step(kStep).ok());
  // Asleep, the body acts as a fixed support: the rope hangs from it, the body does not move.
  EXPECT_FALSE(world.rigidIsAwake(anchorBody));
  EXPECT_LT((world.anchorState(AnchorId{0}).worldPointOnBody - world.nodePositions(rope)[0]).norm(), 1e-3);
  const Vec3 before = world.rigidPosition(anchorBody);
  // A hard sideways swing of the rope wakes it, and it is pulled towards the swing (later the
  // rope goes over the top and pulls it back), the rope still on its anchor. (Before the
  // strain-limiting passes held anchored nodes, they pulled the rope's end 23 cm off it.)
  for (int node = 1; node < 6; ++node) ASSERT_TRUE(world.setNodeVelocity(rope, node, {20.0, 0, 0}));
  double furthest = 0.0, widestGap = 0.0;
  for (int step = 0; step < 10; ++step) {
    ASSERT_TRUE(world.step(kStep).ok());
    furthest = std::max(furthest, world.rigidPosition(anchorBody).x() - before.x());
    widestGap = std::max(widestGap, (world.anchorState(AnchorId{0}).worldPointOnBody - world.nodePositions(rope)[0]).norm());
  }
  EXPECT_TRUE(world.rigidIsAwake(anchorBody));
  EXPECT_GT(furthest, 1e-3);
  EXPECT_LT(widestGap, 0.02);
}

// With gravity off and no Bullet constraints, every impulse between a rope and the bodies
// at its ends is internal: total momentum is conserved, in the same step, both ways.
TEST(Coupling, AnchorImpulsesAreEqualAndOpposite) {
  World world;
  WorldSettings settings = world.settings();
  settings.gravity.setZero();
  ASSERT_TRUE(world.setSettings(settings).ok());
  const RigidBodyId a = *world.addRigidBody(box("a", {-0.1, 0, 0}, 2.0));
  const RigidBodyId b = *world.addRigidBody(box("b", {1.1, 0, 0}, 0.5));
  const DeformableId rope = addRope(world, {0, 0, 0}, {1, 0, 0}, 11, 0.1);
  ASSERT_TRUE(world.addAnchor(AnchorDesc::node(rope, 0, a)).ok());
  ASSERT_TRUE(world.addAnchor(AnchorDesc::node(rope, 10, b)).ok());
  for (int node = 0; node < 11; ++node) ASSERT_TRUE(world.setNodeVelocity(rope, node, {0.3 * node, 1.0, -0.2}));
  const Vec3 initial = world.totalLinearMomentum();
  ASSERT_TRUE(world.step(kStep).ok());
  // One step: the bodies already move, pulled by the rope.
  EXPECT_GT(world.rigidLinearVelocity(b).norm(), 0.02);
  EXPECT_LT((world.deformableImpulseOnRigid(a) + world.deformableImpulseOnRigid(b) +
             world.anchorState(AnchorId{0}).impulse + world.anchorState(AnchorId{1}).impulse)
                .norm(),
            1e-12);
  for (int step = 0; step < 120; ++step) ASSERT_TRUE(world.step(kStep).ok());
  EXPECT_LT((world.totalLinearMomentum() - initial).norm(), 1e-9 * initial.norm());
}

}  // namespace
}  // namespace tandem
