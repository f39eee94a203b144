// Save and restore: stepping on from a restored snapshot repeats the original run bit for bit,
// on a scene with rigid contacts (a stack on the ground), a rope holding a box, and a cloth
// falling onto a sphere and the ground; and on a swept cloth at rest on a sphere.
#include <tandem/mesh.h>
#include <tandem/world.h>

#include <gtest/gtest.h>

#include <cstring>

namespace tandem {
namespace {

constexpr double kStep = 1.0 / 60;

RigidBodyDesc boxDesc(const std::string& name, const Vec3& half, double mass, const Vec3& position) {
  RigidBodyDesc desc;
  desc.name = name;
  desc.shape = RigidShape::box(half);
  desc.mass = mass;
  desc.position = position;
  return desc;
}

struct Scene {
  World world;
  RigidBodyId top, hanging;
  DeformableId rope, cloth;
  FixedPointId ropeTop;
};

void build(Scene& s, int substeps) {
  WorldSettings settings;
  settings.solver.substeps = substeps;
  ASSERT_TRUE(s.world.setSettings(settings).ok());
  RigidBodyDesc ground;
  ground.name = "ground";
  ground.shape = RigidShape::plane({0, 1, 0}, 0);
  ground.motion = MotionType::Static;
  ASSERT_TRUE(s.world.addRigidBody(ground).ok());
  ASSERT_TRUE(s.world.addRigidBody(boxDesc("bottom", {0.3, 0.1, 0.3}, 2.0, {2, 0.1, 0})).ok());
  s.top = *s.world.addRigidBody(boxDesc("top", {0.15, 0.1, 0.15}, 1.0, {2.05, 0.32, 0.02}));
  RigidBodyDesc sphere;
  sphere.name = "sphere";
  sphere.shape = RigidShape::sphere(0.25);
  sphere.motion = MotionType::Static;
  sphere.position = {0, 0.25, 0};
  ASSERT_TRUE(s.world.addRigidBody(sphere).ok());
  DeformableDesc cloth;
  cloth.name = "cloth";
  cloth.mesh = *makeClothGrid({-0.4, 0.7, -0.4}, {0.8, 0, 0}, {0, 0, 0.8}, 12, 12, 0.2);
  cloth.inextensibility.enabled = true;
  cloth.bending.enabled = true;
  s.cloth = *s.world.addDeformable(cloth);
  DeformableDesc rope;
  rope.name = "rope";
  rope.mesh = *makeRope({-2, 2, 0}, {-1.2, 2, 0}, 12, 0.1);  // horizontal: it swings down
  rope.inextensibility.enabled = true;
  s.rope = *s.world.addDeformable(rope);
  s.ropeTop = *s.world.addFixedPoint(s.rope, 0, {-2, 2, 0});
  s.hanging = *s.world.addRigidBody(boxDesc("hanging", {0.05, 0.05, 0.05}, 0.5, {-1.15, 2, 0}));
  ASSERT_TRUE(s.world.addAnchor(AnchorDesc::node(s.rope, 11, s.hanging)).ok());
  ASSERT_TRUE(s.world.applyImpulseAtPoint(s.top, Vec3(0.3, 0, 0), Vec3(2.05, 0.42, 0.1)).ok());
}

// Every number of the state a user can read, in order.
std::vector<double> record(const World& world) {
  std::vector<double> out;
  auto add = [&](const auto& v) { out.insert(out.end(), v.data(), v.data() + v.size()); };
  for (RigidBodyId b : world.rigidBodies()) {
    add(world.rigidPosition(b));
    add(world.rigidOrientation(b).coeffs());
    add(world.rigidLinearVelocity(b));
    add(world.rigidAngularVelocity(b));
    add(world.deformableImpulseOnRigid(b));
  }
  for (DeformableId d : world.deformableIds()) {
    for (const Vec3& p : world.nodePositions(d)) add(p);
    for (const Vec3& v : world.nodeVelocities(d)) add(v);
  }
  for (const ContactReport& c : world.contacts()) {
    add(c.point);
    out.push_back(c.normalImpulse);
    add(c.frictionImpulse);
  }
  for (const RigidContact& c : world.rigidContacts()) {
    add(c.pointOnA);
    out.push_back(c.normalImpulse);
    add(c.frictionImpulse);
  }
  return out;
}

// Steps `count` times, recording after each.
std::vector<std::vector<double>> run(World& world, int count) {
  std::vector<std::vector<double>> records;
  for (int i = 0; i < count; ++i) {
    EXPECT_TRUE(world.step(kStep).ok());
    records.push_back(record(world));
  }
  return records;
}

void expectBitForBit(const std::vector<std::vector<double>>& a, const std::vector<std::vector<double>>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t step = 0; step < a.size(); ++step) {
    ASSERT_EQ(a[step].size(), b[step].size()) << "step " << step;
    size_t differing = 0;
    double largest = 0.0;
    for (size_t i = 0; i < a[step].size(); ++i)
      if (std::memcmp(&a[step][i], &b[step][i], sizeof(double)) != 0) {
        ++differing;
        largest = std::max(largest, std::abs(a[step][i] - b[step][i]));
      }
    ASSERT_EQ(differing, 0u) << "step " << step << ": " << differing << " numbers differ, by up to " << largest;
  }
}

TEST(Snapshot, SteppingOnFromARestoreRepeatsTheRunBitForBit) {
  for (int substeps : {1, 3}) {
    Scene s;
    build(s, substeps);
    const std::vector<std::vector<double>> before = run(s.world, 45);  // contacts made, rope swinging
    ASSERT_FALSE(s.world.contacts().empty());
    ASSERT_FALSE(s.world.rigidContacts().empty());
    const WorldSnapshot snapshot = s.world.snapshot();
    EXPECT_EQ(snapshot.stepCount(), 45);
    ASSERT_TRUE(s.world.applyForce(s.top, Vec3(2, 0, 0)).ok());  // a push applied before the save...
    const WorldSnapshot pushed = s.world.snapshot();              // ...is in the state
    const std::vector<std::vector<double>> original = run(s.world, 60);
    ASSERT_TRUE(s.world.restore(pushed).ok());
    EXPECT_EQ(s.world.stepCount(), 45);
    EXPECT_EQ(record(s.world), before.back());
    expectBitForBit(original, run(s.world, 60));
    // And again from the first, after more steps and edits in between.
    ASSERT_TRUE(s.world.setFixedPointTarget(s.ropeTop, Vec3(-2, 2.2, 0)).ok());
    run(s.world, 10);
    ASSERT_TRUE(s.world.restore(snapshot).ok());
    const std::vector<std::vector<double>> once = run(s.world, 30);
    ASSERT_TRUE(s.world.restore(snapshot).ok());
    expectBitForBit(once, run(s.world, 30));
  }
}

TEST(Snapshot, RestoreBringsBackRemovedDeformablesAndRefusesWhatItCannot) {
  Scene s;
  build(s, 1);
  run(s.world, 20);
  const WorldSnapshot snapshot = s.world.snapshot();
  const std::vector<double> saved = record(s.world);
  ASSERT_TRUE(s.world.removeDeformable(s.cloth).ok());
  ASSERT_TRUE(s.world.removeFixedPoint(s.ropeTop).ok());
  run(s.world, 5);
  ASSERT_TRUE(s.world.restore(snapshot).ok());
  EXPECT_TRUE(s.world.contains(s.cloth));
  EXPECT_TRUE(s.world.contains(s.ropeTop));
  EXPECT_EQ(record(s.world), saved);

  EXPECT_EQ(s.world.restore(WorldSnapshot{}).message(), "restore: the snapshot is empty");
  World other;
  EXPECT_EQ(other.restore(snapshot).message(), "restore: the snapshot was taken from another world");
  ASSERT_TRUE(s.world.addRigidBody(boxDesc("late", {0.1, 0.1, 0.1}, 1.0, {5, 1, 0})).ok());
  EXPECT_EQ(s.world.restore(snapshot).message(),
            "restore: rigid bodies or joints were added or removed since the snapshot was taken");
}

// A swept cloth draped on a sphere keeps its edges' coarse level (the preconditioner of their
// solve together) from step to step while its edges turn little: that level is state, and a
// restored world goes on with the one the original had.
TEST(Snapshot, ASweptClothAtRestGoesOnBitForBitFromARestore) {
  World world;
  RigidBodyDesc sphere;
  sphere.name = "sphere";
  sphere.shape = RigidShape::sphere(0.3);
  sphere.motion = MotionType::Static;
  ASSERT_TRUE(world.addRigidBody(sphere).ok());
  DeformableDesc cloth;
  cloth.name = "cloth";
  cloth.mesh = *makeClothGrid({-0.5, 0.35, -0.5}, {1, 0, 0}, {0, 0, 1}, 25, 25, 0.3);
  cloth.inextensibility.enabled = true;
  cloth.bending.enabled = true;
  cloth.rowSolver = RowSolverKind::Iterative;
  ASSERT_TRUE(world.addDeformable(cloth).ok());
  run(world, 150);  // draped and nearly still
  const WorldSnapshot snapshot = world.snapshot();
  const std::vector<std::vector<double>> original = run(world, 40);
  ASSERT_TRUE(world.restore(snapshot).ok());
  expectBitForBit(original, run(world, 40));
}

// A world made after another is gone may sit at the same address (the allocator hands the freed
// memory back: an empty world's state is the first thing a new world allocates): the snapshot
// of the first still names the first, and the new world refuses it rather than restoring a
// stranger's state.
TEST(Snapshot, ASnapshotOfAWorldThatIsGoneRestoresIntoNoOther) {
  for (bool withBody : {false, true}) {
    WorldSnapshot snapshot;
    {
      World first;
      if (withBody) {
        ASSERT_TRUE(first.addRigidBody(boxDesc("box", {0.1, 0.1, 0.1}, 1.0, {0, 1, 0})).ok());
        ASSERT_TRUE(first.step(kStep).ok());
      }
      snapshot = first.snapshot();
    }
    for (int i = 0; i < 4; ++i) {
      World next;
      if (withBody) {
        ASSERT_TRUE(next.addRigidBody(boxDesc("box", {0.1, 0.1, 0.1}, 1.0, {0, 1, 0})).ok());
      }
      EXPECT_EQ(next.restore(snapshot).message(), "restore: the snapshot was taken from another world") << withBody;
      EXPECT_EQ(next.stepCount(), 0);
    }
  }
}

}  // namespace
}  // namespace tandem
