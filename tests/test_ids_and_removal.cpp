// Ids: every call that takes one, given a bad or a stale id, refuses it (a Status naming it) or
// returns a neutral value and records the error. Removal: what refers to a removed thing goes
// with it, and the world steps on.
#include <tandem/mesh.h>
#include <tandem/world.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace tandem {
namespace {

constexpr double kStep = 1.0 / 60;

RigidBodyDesc boxDesc(const std::string& name, double mass, const Vec3& position) {
  RigidBodyDesc desc;
  desc.name = name;
  desc.shape = RigidShape::box({0.1, 0.1, 0.1});
  desc.mass = mass;
  desc.position = position;
  desc.canSleep = false;
  return desc;
}

DeformableDesc ropeDesc(const Vec3& top, double length, int nodes) {
  DeformableDesc desc;
  desc.name = "rope";
  desc.mesh = *makeRope(top, top - Vec3(0, length, 0), nodes, 0.1);
  desc.inextensibility.enabled = true;
  return desc;
}

// Everything a world can hold, then all of it removed: the ids it handed out are stale.
struct Stale {
  World world;
  RigidBodyId body, other;
  DeformableId rope;
  AnchorId anchor;
  FixedPointId fixedPoint;
  JointId hinge;
  GrabId grab;
};

void makeStale(Stale& s) {
  s.body = *s.world.addRigidBody(boxDesc("box", 1.0, {0, 0, 0}));
  s.other = *s.world.addRigidBody(boxDesc("other", 1.0, {1, 0, 0}));
  s.rope = *s.world.addDeformable(ropeDesc({0, 1, 0}, 1.0, 5));
  s.anchor = *s.world.addAnchor(AnchorDesc::node(s.rope, 4, s.body));
  s.fixedPoint = *s.world.addFixedPoint(s.rope, 0, {0, 1, 0});
  s.hinge = *s.world.addHinge({s.body, s.other, {0.5, 0, 0}, {0, 0, 1}});
  GrabDesc grab;
  grab.body = s.other;
  grab.point = {1, 0, 0};
  s.grab = *s.world.addGrab(grab);
  ASSERT_TRUE(s.world.step(kStep).ok());
  ASSERT_TRUE(s.world.removeAnchor(s.anchor).ok());
  ASSERT_TRUE(s.world.removeFixedPoint(s.fixedPoint).ok());
  ASSERT_TRUE(s.world.removeJoint(s.hinge).ok());
  ASSERT_TRUE(s.world.removeGrab(s.grab).ok());
  ASSERT_TRUE(s.world.removeDeformable(s.rope).ok());
  ASSERT_TRUE(s.world.removeRigidBody(s.body).ok());
  ASSERT_TRUE(s.world.removeRigidBody(s.other).ok());
  ASSERT_TRUE(s.world.step(kStep).ok());
}

// Every id-taking call that returns Status or Result, with the id it is given; each must refuse
// it with a message naming it.
std::vector<std::pair<std::string, std::function<std::string(World&)>>> statusCalls(RigidBodyId body,
                                                                                      DeformableId rope, AnchorId anchor,
                                                                                      FixedPointId fixedPoint,
                                                                                      JointId joint, GrabId grab) {
  const Vec3 v(1, 0, 0);
  const Quat q = Quat::Identity();
  using Call = std::function<std::string(World&)>;
  return {
      {"rigid body", Call([=](World& w) { return w.putRigidToSleep(body).message(); })},
      {"rigid body", Call([=](World& w) { return w.setRigidCanSleep(body, true).message(); })},
      {"rigid body", Call([=](World& w) { return w.setKinematicTarget(body, v, q).message(); })},
      {"rigid body", Call([=](World& w) { return w.applyForce(body, v).message(); })},
      {"rigid body", Call([=](World& w) { return w.applyForceAtPoint(body, v, v).message(); })},
      {"rigid body", Call([=](World& w) { return w.applyTorque(body, v).message(); })},
      {"rigid body", Call([=](World& w) { return w.applyImpulse(body, v).message(); })},
      {"rigid body", Call([=](World& w) { return w.applyImpulseAtPoint(body, v, v).message(); })},
      {"rigid body", Call([=](World& w) { return w.applyAngularImpulse(body, v).message(); })},
      {"rigid body", Call([=](World& w) { return w.setRigidLinearVelocity(body, v).message(); })},
      {"rigid body", Call([=](World& w) { return w.setRigidAngularVelocity(body, v).message(); })},
      {"rigid body", Call([=](World& w) { return w.setRigidPose(body, v, q).message(); })},
      {"rigid body", Call([=](World& w) { return w.setRigidCollisionFilter(body, 1, 1).message(); })},
      {"rigid body", Call([=](World& w) { return w.removeRigidBody(body).message(); })},
      {"rigid body", Call([=](World& w) { return w.addHinge({body, std::nullopt, v, v}).message(); })},
      {"rigid body", Call([=](World& w) { return w.addFixedJoint({body, std::nullopt}).message(); })},
      {"rigid body", Call([=](World& w) { return w.addAnchor(AnchorDesc::node(rope, 0, body)).message(); })},
      {"rigid body", Call([=](World& w) {
         GrabDesc g;
         g.body = body;
         return w.addGrab(g).message();
       })},
      {"deformable", Call([=](World& w) { return w.setNodeVelocity(rope, 0, v).message(); })},
      {"deformable", Call([=](World& w) { return w.setNodePosition(rope, 0, v).message(); })},
      {"deformable", Call([=](World& w) { return w.fixNode(rope, 0).message(); })},
      {"deformable", Call([=](World& w) { return w.setDeformableCollisionFilter(rope, 1, 1).message(); })},
      {"deformable", Call([=](World& w) { return w.addFixedPoint(rope, 0, v).message(); })},
      {"deformable", Call([=](World& w) { return w.removeDeformable(rope).message(); })},
      {"deformable", Call([=](World& w) {
         GrabDesc g;
         g.deformable = rope;
         return w.addGrab(g).message();
       })},
      {"anchor", Call([=](World& w) { return w.removeAnchor(anchor).message(); })},
      {"fixed point", Call([=](World& w) { return w.setFixedPointTarget(fixedPoint, v).message(); })},
      {"fixed point", Call([=](World& w) { return w.removeFixedPoint(fixedPoint).message(); })},
      {"joint", Call([=](World& w) { return w.setHingeLimits(joint, 1, -1).message(); })},
      {"joint", Call([=](World& w) { return w.setHingeMotor(joint, false, 0, 0).message(); })},
      {"joint", Call([=](World& w) { return w.removeJoint(joint).message(); })},
      {"grab", Call([=](World& w) { return w.setGrabTarget(grab, v).message(); })},
      {"grab", Call([=](World& w) { return w.removeGrab(grab).message(); })},
  };
}

// Every value-returning query with the id it is given: it must return a neutral value (checked
// by the lambda) and record the error.
std::vector<std::pair<std::string, std::function<bool(const World&)>>> queries(RigidBodyId body, DeformableId rope,
                                                                             AnchorId anchor, FixedPointId fixedPoint,
                                                                             JointId joint, GrabId grab) {
  using Query = std::function<bool(const World&)>;
  return {
      {"rigid body", Query([=](const World& w) { return w.rigidName(body).empty(); })},
      {"rigid body", Query([=](const World& w) { return w.rigidPosition(body).isZero(); })},
      {"rigid body", Query([=](const World& w) { return w.rigidOrientation(body).isApprox(Quat::Identity()); })},
      {"rigid body", Query([=](const World& w) { return w.rigidLinearVelocity(body).isZero(); })},
      {"rigid body", Query([=](const World& w) { return w.rigidAngularVelocity(body).isZero(); })},
      {"rigid body", Query([=](const World& w) { return w.rigidMass(body) == 0.0; })},
      {"rigid body", Query([=](const World& w) { return w.rigidInertia(body).isZero(); })},
      {"rigid body", Query([=](const World& w) { return !w.rigidIsAwake(body); })},
      {"rigid body", Query([=](const World& w) { return w.rigidCollisionGroup(body) == 0; })},
      {"rigid body", Query([=](const World& w) { return w.rigidCollisionMask(body) == 0; })},
      {"rigid body", Query([=](const World& w) { return w.rigidContactImpulse(body, body) == 0.0; })},
      {"rigid body", Query([=](const World& w) { return w.deformableImpulseOnRigid(body).isZero(); })},
      {"rigid body", Query([=](const World& w) { return w.deformableAngularImpulseOnRigid(body).isZero(); })},
      {"rigid body", Query([=](const World& w) { return w.deformableForceOnRigid(body).isZero(); })},
      {"rigid body", Query([=](const World& w) { return w.deformableTorqueOnRigid(body).isZero(); })},
      {"rigid body", Query([=](const World& w) { return w.rigidShape(body).points.empty(); })},
      {"deformable", Query([=](const World& w) { return w.deformableName(rope).empty(); })},
      {"deformable", Query([=](const World& w) { return w.nodePositions(rope).empty(); })},
      {"deformable", Query([=](const World& w) { return w.nodeVelocities(rope).empty(); })},
      {"deformable", Query([=](const World& w) { return w.nodeInverseMasses(rope).empty(); })},
      {"deformable", Query([=](const World& w) { return w.restMesh(rope).positions.empty(); })},
      {"anchor", Query([=](const World& w) { return w.anchorState(anchor).impulse.isZero(); })},
      {"fixed point", Query([=](const World& w) { return w.fixedPointImpulse(fixedPoint).isZero(); })},
      {"joint", Query([=](const World& w) { return w.hingeAngle(joint) == 0.0; })},
      {"joint", Query([=](const World& w) { return w.hingeSpeed(joint) == 0.0; })},
      {"grab", Query([=](const World& w) { return w.grabImpulse(grab).isZero(); })},
      {"grab", Query([=](const World& w) { return w.grabPoint(grab).isZero(); })},
  };
}

TEST(Ids, EveryCallRefusesABadIdNamingIt) {
  World world;  // an empty world: index 99 names nothing
  ASSERT_TRUE(world.addRigidBody(boxDesc("box", 1.0, {0, 0, 0})).ok());
  int checked = 0;
  for (auto& [kind, call] : statusCalls(RigidBodyId{99}, DeformableId{99}, AnchorId{99}, FixedPointId{99}, JointId{99},
                                        GrabId{99})) {
    const std::string message = call(world);
    EXPECT_NE(message.find(kind + " 99: no such " + kind), std::string::npos) << message;
    ++checked;
  }
  for (auto& [kind, query] : queries(RigidBodyId{99}, DeformableId{99}, AnchorId{99}, FixedPointId{99}, JointId{99},
                                     GrabId{99})) {
    EXPECT_TRUE(query(world)) << kind;
    const Status error = world.takeLookupError();
    EXPECT_NE(error.message().find(kind + " 99: no such " + kind), std::string::npos) << error.message();
    EXPECT_TRUE(world.takeLookupError().ok());  // taken: cleared
    ++checked;
  }
  EXPECT_EQ(checked, 33 + 27);
  // The cases issue 13 found: no segfault, no exception.
  EXPECT_TRUE(world.rigidPosition(RigidBodyId{99}).isZero());
  EXPECT_TRUE(world.anchorState(AnchorId{5}).worldPointOnBody.isZero());
  EXPECT_EQ(world.takeLookupError().message(), "rigid body 99: no such rigid body (the world has 1 slot)");
  EXPECT_TRUE(world.rigidPosition(RigidBodyId{-1}).isZero());
  EXPECT_FALSE(world.contains(RigidBodyId{-1}));
  EXPECT_TRUE(world.contains(RigidBodyId{0}));
}

TEST(Ids, EveryCallRefusesAStaleIdAsRemoved) {
  Stale s;
  makeStale(s);
  for (auto& [kind, call] : statusCalls(s.body, s.rope, s.anchor, s.fixedPoint, s.hinge, s.grab)) {
    const std::string message = call(s.world);
    EXPECT_NE(message.find("(generation 0) was removed"), std::string::npos) << message;
    EXPECT_NE(message.find(kind), std::string::npos) << message;
  }
  for (auto& [kind, query] : queries(s.body, s.rope, s.anchor, s.fixedPoint, s.hinge, s.grab)) {
    EXPECT_TRUE(query(s.world)) << kind;
    const std::string message = s.world.takeLookupError().message();
    EXPECT_NE(message.find(kind), std::string::npos) << message;
    EXPECT_NE(message.find("(generation 0) was removed"), std::string::npos) << message;
  }
  EXPECT_EQ(s.world.rigidBodyCount(), 0);
  EXPECT_EQ(s.world.deformableCount(), 0);
  EXPECT_TRUE(s.world.rigidBodies().empty());
  EXPECT_TRUE(s.world.deformableIds().empty());
  EXPECT_FALSE(s.world.findRigidBody("box").has_value());
  EXPECT_FALSE(s.world.findDeformable("rope").has_value());
}

// A freed slot is reused with the next generation: the old id does not name the new body.
TEST(Ids, AReusedSlotRefusesTheOldIdAndServesTheNew) {
  World world;
  const RigidBodyId first = *world.addRigidBody(boxDesc("first", 1.0, {0, 5, 0}));
  ASSERT_TRUE(world.removeRigidBody(first).ok());
  const RigidBodyId second = *world.addRigidBody(boxDesc("second", 2.0, {3, 0, 0}));
  EXPECT_EQ(second.index, first.index);
  EXPECT_EQ(second.generation, first.generation + 1);
  EXPECT_TRUE(world.rigidPosition(first).isZero());
  EXPECT_EQ(world.takeLookupError().message(), "rigid body 0 (generation 0) was removed (its slot now holds generation 1)");
  EXPECT_EQ(world.rigidPosition(second), Vec3(3, 0, 0));
  EXPECT_EQ(world.rigidName(second), "second");
  EXPECT_EQ(world.applyImpulse(first, Vec3(1, 0, 0)).message(),
            "apply impulse: rigid body 0 (generation 0) was removed (its slot now holds generation 1)");
  EXPECT_TRUE(world.rigidLinearVelocity(second).isZero());  // the stale push did not reach it
  EXPECT_EQ(world.applyImpulse(RigidBodyId{0, 7}, Vec3(1, 0, 0)).message(),
            "apply impulse: rigid body 0: generation 7 was never made (the slot is at generation 1)");
  // Anchors reuse slots the same way.
  const DeformableId rope = *world.addDeformable(ropeDesc({3, 1, 0}, 1.0, 4));
  const AnchorId a = *world.addAnchor(AnchorDesc::node(rope, 3, second));
  ASSERT_TRUE(world.removeAnchor(a).ok());
  const AnchorId b = *world.addAnchor(AnchorDesc::node(rope, 3, second));
  EXPECT_EQ(b.index, a.index);
  EXPECT_EQ(b.generation, 1u);
  EXPECT_FALSE(world.contains(a));
  EXPECT_TRUE(world.contains(b));
}

// ---- Removal --------------------------------------------------------------------------------

// A rope hangs from a fixed point and holds a box by an anchor: the world for the removals.
struct Hanging {
  World world;
  DeformableId rope;
  RigidBodyId box;
  FixedPointId top;
  AnchorId anchor;
};

void makeHanging(Hanging& s) {
  s.rope = *s.world.addDeformable(ropeDesc({0, 2, 0}, 1.0, 11));
  s.top = *s.world.addFixedPoint(s.rope, 0, {0, 2, 0});
  s.box = *s.world.addRigidBody(boxDesc("box", 1.0, {0, 0.9, 0}));
  s.anchor = *s.world.addAnchor(AnchorDesc::node(s.rope, 10, s.box));
  for (int i = 0; i < 60; ++i) ASSERT_TRUE(s.world.step(kStep).ok());
  ASSERT_NEAR(-s.world.anchorState(s.anchor).impulse.y(), 9.81 * kStep, 0.05 * 9.81 * kStep);  // holds the box
}

TEST(Removal, RemovingTheRopeLetsTheBoxItHeldFallFreely) {
  Hanging s;
  makeHanging(s);
  const double y0 = s.world.rigidPosition(s.box).y();
  ASSERT_TRUE(s.world.removeDeformable(s.rope).ok());
  EXPECT_FALSE(s.world.contains(s.anchor));  // its anchor and fixed point went with it
  EXPECT_FALSE(s.world.contains(s.top));
  const int steps = 30;
  for (int i = 0; i < steps; ++i) ASSERT_TRUE(s.world.step(kStep).ok());
  EXPECT_NEAR(s.world.rigidLinearVelocity(s.box).y(), -9.81 * kStep * steps, 0.02);
  EXPECT_LT(s.world.rigidPosition(s.box).y(), y0 - 0.4);
  EXPECT_TRUE(s.world.deformableImpulseOnRigid(s.box).isZero());
  EXPECT_TRUE(s.world.contacts().empty());
  EXPECT_EQ(s.world.lastReport().rows(RowType::Anchor), 0);
  // A new deformable steps alongside the removed one's inert nodes.
  const DeformableId second = *s.world.addDeformable(ropeDesc({2, 2, 0}, 1.0, 5));
  ASSERT_TRUE(s.world.addFixedPoint(second, 0, {2, 2, 0}).ok());
  for (int i = 0; i < 60; ++i) ASSERT_TRUE(s.world.step(kStep).ok());
  EXPECT_NEAR(s.world.nodePositions(second).back().y(), 1.0, 0.01);  // hangs its length below
  EXPECT_EQ(s.world.deformableCount(), 1);
}

TEST(Removal, RemovingTheBoxARopeIsAnchoredToLeavesTheRopeHanging) {
  Hanging s;
  makeHanging(s);
  ASSERT_TRUE(s.world.removeRigidBody(s.box).ok());
  EXPECT_FALSE(s.world.contains(s.anchor));
  EXPECT_EQ(s.world.anchorState(s.anchor).impulse, Vec3::Zero());
  EXPECT_NE(s.world.takeLookupError().message().find("anchor 0 (generation 0) was removed"), std::string::npos);
  for (int i = 0; i < 240; ++i) ASSERT_TRUE(s.world.step(kStep).ok());
  const std::span<const Vec3> nodes = s.world.nodePositions(s.rope);
  EXPECT_NEAR(nodes.back().y(), 1.0, 0.02);  // the rope alone, straight down from its fixed point
  // Its fixed point now carries only the rope's weight (0.1 kg).
  EXPECT_NEAR(s.world.fixedPointImpulse(s.top).y(), 0.1 * 9.81 * kStep, 0.05 * 0.1 * 9.81 * kStep);
}

TEST(Removal, RemovingTheGroundOrAJointLetsBodiesFall) {
  World world;
  RigidBodyDesc groundDesc;
  groundDesc.name = "ground";
  groundDesc.shape = RigidShape::plane({0, 1, 0}, 0);
  groundDesc.motion = MotionType::Static;
  const RigidBodyId ground = *world.addRigidBody(groundDesc);
  const RigidBodyId box = *world.addRigidBody(boxDesc("box", 1.0, {0, 0.1, 0}));
  const RigidBodyId hung = *world.addRigidBody(boxDesc("hung", 1.0, {3, 1, 0}));
  const JointId hinge = *world.addHinge({hung, std::nullopt, {3, 1, 0}, {0, 0, 1}});
  for (int i = 0; i < 30; ++i) ASSERT_TRUE(world.step(kStep).ok());
  ASSERT_GT(world.rigidContactImpulse(box, ground), 0.0);
  ASSERT_NEAR(world.rigidPosition(hung).y(), 1.0, 1e-3);
  ASSERT_TRUE(world.removeRigidBody(ground).ok());
  ASSERT_TRUE(world.removeJoint(hinge).ok());
  EXPECT_TRUE(world.rigidContacts().empty());  // the last step's contacts with it are gone
  EXPECT_EQ(world.lastReport().bulletJoints, 1);  // (the report is the last step's)
  for (int i = 0; i < 30; ++i) ASSERT_TRUE(world.step(kStep).ok());
  EXPECT_NEAR(world.rigidLinearVelocity(box).y(), -9.81 * 0.5, 0.01);
  EXPECT_NEAR(world.rigidLinearVelocity(hung).y(), -9.81 * 0.5, 0.01);
  EXPECT_EQ(world.lastReport().bulletJoints, 0);
  EXPECT_EQ(world.lastReport().bulletContactManifolds, 0);
  EXPECT_TRUE(world.rigidContacts().empty());
  // A body removed with a joint on it takes the joint along.
  const JointId again = *world.addHinge({box, std::nullopt, {0, 0, 0}, {0, 0, 1}});
  ASSERT_TRUE(world.removeRigidBody(box).ok());
  EXPECT_FALSE(world.contains(again));
  ASSERT_TRUE(world.step(kStep).ok());
  EXPECT_EQ(world.lastReport().bulletJoints, 0);
}

TEST(Removal, RemovingAFixedPointDropsTheRope) {
  World world;
  const DeformableId rope = *world.addDeformable(ropeDesc({0, 2, 0}, 1.0, 6));
  const FixedPointId top = *world.addFixedPoint(rope, 0, {0, 2, 0});
  const FixedPointId second = *world.addFixedPoint(rope, 5, {0, 1, 0});
  for (int i = 0; i < 10; ++i) ASSERT_TRUE(world.step(kStep).ok());
  ASSERT_TRUE(world.removeFixedPoint(top).ok());
  EXPECT_EQ(world.setFixedPointTarget(top, Vec3::Zero()).message(),
            "fixed point target: fixed point 0 (generation 0) was removed");
  ASSERT_TRUE(world.setFixedPointTarget(second, Vec3(0, 1, 0)).ok());  // the other keeps its id
  ASSERT_TRUE(world.removeFixedPoint(second).ok());
  const int steps = 30;
  for (int i = 0; i < steps; ++i) ASSERT_TRUE(world.step(kStep).ok());
  for (const Vec3& v : world.nodeVelocities(rope)) EXPECT_NEAR(v.y(), -9.81 * kStep * steps, 1e-6);
}

// A cloth lying on a box: removing the box mid-contact (its contacts and supports go too).
TEST(Removal, RemovingABodyUnderAClothDropsTheCloth) {
  World world;
  RigidBodyDesc table = boxDesc("table", 1.0, {0, 0, 0});
  table.shape = RigidShape::box({1, 0.1, 1});
  table.motion = MotionType::Static;
  const RigidBodyId tableId = *world.addRigidBody(table);
  DeformableDesc cloth;
  cloth.name = "cloth";
  cloth.mesh = *makeClothGrid({-0.5, 0.12, -0.5}, {1, 0, 0}, {0, 0, 1}, 6, 6, 0.2);
  cloth.paradigm.type = ParadigmType::ShapeMatching;  // supports and holds at work
  const DeformableId id = *world.addDeformable(cloth);
  for (int i = 0; i < 60; ++i) ASSERT_TRUE(world.step(kStep).ok());
  ASSERT_FALSE(world.contacts().empty());
  ASSERT_TRUE(world.removeRigidBody(tableId).ok());
  EXPECT_TRUE(world.contacts().empty());
  const int steps = 20;
  for (int i = 0; i < steps; ++i) ASSERT_TRUE(world.step(kStep).ok());
  for (const Vec3& v : world.nodeVelocities(id)) EXPECT_NEAR(v.y(), -9.81 * kStep * steps, 0.05);
}

}  // namespace
}  // namespace tandem
