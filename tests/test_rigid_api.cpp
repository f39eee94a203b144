// Pushing, moving and reading rigid bodies through World: impulses, forces and torques against
// their analytic effect, poses and velocities, Bullet's contact points, collision filters and
// hinge limits and motors.
#include <tandem/mesh.h>
#include <tandem/world.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace tandem {
namespace {

RigidBodyDesc boxDesc(const std::string& name, const Vec3& halfExtents, double mass, const Vec3& position) {
  RigidBodyDesc desc;
  desc.name = name;
  desc.shape = RigidShape::box(halfExtents);
  desc.mass = mass;
  desc.position = position;
  desc.canSleep = false;
  return desc;
}

RigidBodyDesc groundDesc() {
  RigidBodyDesc desc;
  desc.name = "ground";
  desc.shape = RigidShape::plane({0, 1, 0}, 0);
  desc.motion = MotionType::Static;
  return desc;
}

WorldSettings zeroGravity() {
  WorldSettings settings;
  settings.gravity = Vec3::Zero();
  return settings;
}

// Δv = J/m and Δω = I⁻¹ (r × J), at once, for an impulse off the centre.
TEST(RigidApi, ImpulseAtAPointChangesVelocityByJOverMAndSpinByInverseInertiaTimesRCrossJ) {
  World world;
  ASSERT_TRUE(world.setSettings(zeroGravity()).ok());
  const double m = 2.0;
  const RigidBodyId box = *world.addRigidBody(boxDesc("box", {0.5, 0.25, 0.1}, m, {1, 2, 3}));
  const Vec3 J(0.5, 3.0, -1.0), r(0.4, 0.1, -0.05);
  ASSERT_TRUE(world.applyImpulseAtPoint(box, J, Vec3(1, 2, 3) + r).ok());
  const Mat3 I = world.rigidInertia(box);
  // A box's principal moments: m/12 (b² + c²) with b, c the full side lengths.
  EXPECT_NEAR(I(2, 2), m / 12 * (1.0 * 1.0 + 0.5 * 0.5), 1e-12);
  EXPECT_NEAR(world.rigidMass(box), m, 1e-12);
  EXPECT_LT((world.rigidLinearVelocity(box) - J / m).norm(), 1e-12);
  EXPECT_LT((world.rigidAngularVelocity(box) - I.inverse() * r.cross(J)).norm(), 1e-9);
  // At the centre: no spin; an angular impulse: Δω = I⁻¹ L.
  ASSERT_TRUE(world.setRigidAngularVelocity(box, Vec3::Zero()).ok());
  ASSERT_TRUE(world.applyImpulse(box, J).ok());
  EXPECT_LT((world.rigidLinearVelocity(box) - 2 * J / m).norm(), 1e-12);
  EXPECT_LT(world.rigidAngularVelocity(box).norm(), 1e-15);
  ASSERT_TRUE(world.applyAngularImpulse(box, Vec3(0, 0, 0.3)).ok());
  EXPECT_LT((world.rigidAngularVelocity(box) - I.inverse() * Vec3(0, 0, 0.3)).norm(), 1e-12);
}

// Damping as Bullet applies it, in each (sub)step's prediction: with nothing else acting, a
// sphere's linear and angular velocities fall as (1 − d)^t, whatever the substeps, and it moves
// by the damped velocity of each substep, Σ (h/n) v₀ (1 − d)^{k h/n}.
TEST(RigidApi, DampingTakesTheGivenFractionOfTheVelocityPerSecond) {
  for (int substeps : {1, 4}) {
    World world;
    WorldSettings settings = zeroGravity();
    settings.solver.substeps = substeps;
    ASSERT_TRUE(world.setSettings(settings).ok());
    RigidBodyDesc desc;
    desc.name = "ball";
    desc.shape = RigidShape::sphere(0.1);
    desc.canSleep = false;
    desc.linearVelocity = {2.0, 0.0, -1.0};
    desc.angularVelocity = {0.0, 3.0, 0.0};
    desc.linearDamping = 0.3;
    desc.angularDamping = 0.5;
    const RigidBodyId ball = *world.addRigidBody(desc);
    const double h = 0.02;
    Vec3 travelled = Vec3::Zero();
    for (int k = 1; k <= 50 * substeps; ++k) travelled += (h / substeps) * std::pow(0.7, k * h / substeps) * desc.linearVelocity;
    for (int step = 0; step < 50; ++step) ASSERT_TRUE(world.step(h).ok());
    EXPECT_LT((world.rigidLinearVelocity(ball) - 0.7 * desc.linearVelocity).norm(), 1e-12) << substeps << " substeps";
    EXPECT_LT((world.rigidAngularVelocity(ball) - 0.5 * desc.angularVelocity).norm(), 1e-12) << substeps << " substeps";
    EXPECT_LT((world.rigidPosition(ball) - travelled).norm(), 1e-12) << substeps << " substeps";
    // Changed, it acts from the next step; a snapshot keeps the damping it was taken with.
    const WorldSnapshot snapshot = world.snapshot();
    ASSERT_TRUE(world.setRigidDamping(ball, 0.0, 0.0).ok());
    for (int step = 0; step < 50; ++step) ASSERT_TRUE(world.step(h).ok());
    EXPECT_LT((world.rigidLinearVelocity(ball) - 0.7 * desc.linearVelocity).norm(), 1e-12);
    ASSERT_TRUE(world.restore(snapshot).ok());
    for (int step = 0; step < 50; ++step) ASSERT_TRUE(world.step(h).ok());
    EXPECT_LT((world.rigidLinearVelocity(ball) - 0.49 * desc.linearVelocity).norm(), 1e-12);
    EXPECT_LT((world.rigidAngularVelocity(ball) - 0.25 * desc.angularVelocity).norm(), 1e-12);
    EXPECT_FALSE(world.setRigidDamping(ball, 1.5, 0.0).ok());
    EXPECT_FALSE(world.setRigidDamping(RigidBodyId{7}, 0.1, 0.1).ok());
  }
}

// A force F acting over a step changes the momentum by F h, however many substeps; it acts for
// that step only. A torque τ changes the spin by I⁻¹ τ h; a force at a point is both.
TEST(RigidApi, ForceOverOneStepChangesMomentumByForceTimesStepAndIsThenCleared) {
  for (int substeps : {1, 4}) {
    World world;
    WorldSettings settings = zeroGravity();
    settings.solver.substeps = substeps;
    ASSERT_TRUE(world.setSettings(settings).ok());
    const double m = 3.0, h = 0.01;
    const RigidBodyId box = *world.addRigidBody(boxDesc("box", {0.2, 0.2, 0.2}, m, {0, 0, 0}));
    const Vec3 F(10, -4, 2);
    ASSERT_TRUE(world.applyForce(box, F).ok());
    ASSERT_TRUE(world.applyForce(box, F).ok());  // forces accumulate: 2F
    ASSERT_TRUE(world.step(h).ok());
    EXPECT_LT((m * world.rigidLinearVelocity(box) - 2 * F * h).norm(), 1e-12) << substeps << " substeps";
    ASSERT_TRUE(world.step(h).ok());  // cleared: no further change
    EXPECT_LT((m * world.rigidLinearVelocity(box) - 2 * F * h).norm(), 1e-12);

    ASSERT_TRUE(world.setRigidLinearVelocity(box, Vec3::Zero()).ok());
    const Mat3 I = world.rigidInertia(box);  // a cube: isotropic, so the pose does not matter
    const Vec3 torque(0, 0, 0.5);
    ASSERT_TRUE(world.applyTorque(box, torque).ok());
    ASSERT_TRUE(world.step(h).ok());
    EXPECT_LT((world.rigidAngularVelocity(box) - I.inverse() * torque * h).norm(), 1e-12);

    ASSERT_TRUE(world.setRigidAngularVelocity(box, Vec3::Zero()).ok());
    const Vec3 r(0, 0.2, 0), atPoint(1, 0, 0);
    ASSERT_TRUE(world.applyForceAtPoint(box, atPoint, world.rigidPosition(box) + r).ok());
    ASSERT_TRUE(world.step(h).ok());
    EXPECT_LT((m * world.rigidLinearVelocity(box) - atPoint * h).norm(), 1e-12);
    EXPECT_LT((world.rigidAngularVelocity(box) - I.inverse() * r.cross(atPoint) * h).norm(), 1e-12);
  }
}

// Set pose, then step under zero gravity: it stays; with a velocity set, it moves by v h.
TEST(RigidApi, SetPoseHoldsUnderZeroGravityAndWakesTheBody) {
  World world;
  ASSERT_TRUE(world.setSettings(zeroGravity()).ok());
  RigidBodyDesc desc = boxDesc("box", {0.2, 0.3, 0.4}, 1.0, {0, 0, 0});
  desc.canSleep = true;
  const RigidBodyId box = *world.addRigidBody(desc);
  ASSERT_TRUE(world.putRigidToSleep(box).ok());
  ASSERT_FALSE(world.rigidIsAwake(box));
  const Vec3 position(1.5, -2, 0.25);
  const Quat orientation(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
  ASSERT_TRUE(world.setRigidPose(box, position, orientation).ok());
  EXPECT_TRUE(world.rigidIsAwake(box));
  for (int i = 0; i < 10; ++i) ASSERT_TRUE(world.step(0.01).ok());
  EXPECT_LT((world.rigidPosition(box) - position).norm(), 1e-12);
  EXPECT_LT(world.rigidOrientation(box).angularDistance(orientation), 1e-9);
  ASSERT_TRUE(world.setRigidLinearVelocity(box, Vec3(0.5, 0, -1)).ok());
  ASSERT_TRUE(world.step(0.01).ok());
  EXPECT_LT((world.rigidPosition(box) - (position + 0.01 * Vec3(0.5, 0, -1))).norm(), 1e-12);
}

// A box resting on the ground: four contact points whose normal impulses sum to m g h over a
// step, with normals up, the same total as rigidContactImpulse.
TEST(RigidApi, RestingBoxContactPointsCarryItsWeightOverAStep) {
  World world;
  const RigidBodyId ground = *world.addRigidBody(groundDesc());
  const double m = 2.5, h = 1.0 / 60;
  const RigidBodyId box = *world.addRigidBody(boxDesc("box", {0.3, 0.2, 0.25}, m, {0, 0.2, 0}));
  for (int i = 0; i < 120; ++i) ASSERT_TRUE(world.step(h).ok());
  const std::vector<RigidContact> contacts = world.rigidContacts();
  ASSERT_EQ(contacts.size(), 4u);
  double total = 0.0;
  Vec3 friction = Vec3::Zero();
  for (const RigidContact& c : contacts) {
    const bool boxIsA = c.bodyA == box;
    ASSERT_TRUE(boxIsA ? c.bodyB == ground : (c.bodyA == ground && c.bodyB == box));
    // The normal points from B to A: up when the box is A.
    EXPECT_NEAR(c.normal.y(), boxIsA ? 1.0 : -1.0, 1e-9);
    EXPECT_NEAR(c.pointOnB.y() * (boxIsA ? 1 : 0) + c.pointOnA.y() * (boxIsA ? 0 : 1), 0.0, 2e-3);  // on the ground
    EXPECT_GE(c.normalImpulse, 0.0);
    EXPECT_LT(std::abs(c.frictionImpulse.dot(c.normal)), 1e-12);  // tangential
    friction += c.frictionImpulse;
    total += c.normalImpulse;
  }
  EXPECT_NEAR(total, m * 9.81 * h, 0.01 * m * 9.81 * h);
  EXPECT_LT(friction.norm(), 1e-3 * total);  // nothing pushes sideways: the points' friction cancels
  EXPECT_DOUBLE_EQ(total, world.rigidContactImpulse(box, ground));
}

// A small box on the ground plane rests on its face. Bullet's plane algorithm used to make one
// contact point per step: a 10 cm box rocked from corner to corner and sank 13 mm into the ground
// (at 4 and at 10 iterations); 40 cm boxes hid it. Now the patch comes at once.
TEST(RigidApi, SmallBoxesRestOnTheGroundPlaneWithoutSinkingOrRocking) {
  for (const double half : {0.025, 0.05}) {
    World world;
    (void)*world.addRigidBody(groundDesc());
    const RigidBodyId box = *world.addRigidBody(boxDesc("box", {half, half, half}, 0.5, {0, half + 0.01, 0}));
    double deepest = INFINITY, fastest = 0.0, fastestSpin = 0.0;
    for (int i = 0; i < 120; ++i) {
      ASSERT_TRUE(world.step(1.0 / 60).ok());
      if (i < 60) continue;  // landed and settled in the first second
      deepest = std::min(deepest, world.rigidPosition(box).y());
      fastest = std::max(fastest, world.rigidLinearVelocity(box).norm());
      fastestSpin = std::max(fastestSpin, world.rigidAngularVelocity(box).norm());
    }
    EXPECT_GT(deepest, half - 2e-4) << half;
    EXPECT_LT(fastest, 1e-3) << half;
    EXPECT_LT(fastestSpin, 0.05) << half;  // Bullet alone, 4 iterations: 0.02 rad/s for the 5 cm box
  }
}

// Bodies resting on the ground and on each other stay put: a box alone, and three stacked with
// each 1 cm off the one below, at the paper's h = 20 ms and K = 2, and at the default K = 4. With
// Bullet's default warm start (85 % of last step's impulses) the box slid at 0.3 mm/s with a
// steady spin and the stack came apart (its top box 0.17 m away after 8 s at K = 2, 0.57 m at
// K = 4); src/bullet/bullet_world.cpp.
TEST(RigidApi, BoxesRestingOnTheGroundAndOnEachOtherStayPut) {
  for (const int iterations : {2, 4})
    for (const int stacked : {1, 3}) {
      World world;
      WorldSettings settings;
      settings.solver.iterations = iterations;
      ASSERT_TRUE(world.setSettings(settings).ok());
      (void)*world.addRigidBody(groundDesc());
      std::vector<RigidBodyId> boxes;
      for (int i = 0; i < stacked; ++i) {
        RigidBodyDesc desc = boxDesc("box" + std::to_string(i), {0.08, 0.08, 0.08}, 0.5, {0.01 * i, 0.081 + 0.161 * i, 0});
        desc.friction = 0.8;
        boxes.push_back(*world.addRigidBody(desc));
      }
      const double h = 0.02;
      for (int step = 0; step < 100; ++step) ASSERT_TRUE(world.step(h).ok());  // landed and settled
      std::vector<Vec3> settled;
      for (const RigidBodyId box : boxes) settled.push_back(world.rigidPosition(box));
      double fastest = 0.0, fastestSpin = 0.0;
      for (int step = 0; step < 400; ++step) {
        ASSERT_TRUE(world.step(h).ok());
        for (const RigidBodyId box : boxes) {
          fastest = std::max(fastest, world.rigidLinearVelocity(box).norm());
          fastestSpin = std::max(fastestSpin, world.rigidAngularVelocity(box).norm());
        }
      }
      for (int i = 0; i < stacked; ++i)  // the stay-put bound of tests/test_soak.cpp is 0.8 mm in 8 s
        EXPECT_LT((world.rigidPosition(boxes[i]) - settled[i]).norm(), 1e-4) << "K = " << iterations << ", box " << i << " of " << stacked;
      EXPECT_LT(fastest, 1e-5) << "K = " << iterations << ", " << stacked << " boxes";
      EXPECT_LT(fastestSpin, 1e-4) << "K = " << iterations << ", " << stacked << " boxes";
    }
}

// More touching pairs than Bullet's contact pools hold (256 manifolds, 256 algorithms: set small so
// that making a world is cheap, src/bullet/bullet_world_impl.h): the pairs past the pools come from
// the heap and behave the same. 400 boxes on the ground, 400 manifolds, each at rest carrying m g.
TEST(RigidApi, MorePairsThanBulletsPoolsHoldRestOnTheGroundAndCarryTheirWeight) {
  World world;
  const RigidBodyId ground = *world.addRigidBody(groundDesc());
  const double m = 0.5, h = 1.0 / 60, half = 0.05;
  std::vector<RigidBodyId> boxes;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j)
      boxes.push_back(*world.addRigidBody(boxDesc("box" + std::to_string(boxes.size()), {half, half, half}, m,
                                                  {0.3 * i, half + 0.01, 0.3 * j})));
  for (int i = 0; i < 90; ++i) ASSERT_TRUE(world.step(h).ok());
  EXPECT_EQ(world.lastReport().bulletContactManifolds, 400);
  for (const RigidBodyId box : boxes) {
    EXPECT_NEAR(world.rigidPosition(box).y(), half, 2e-3);
    EXPECT_LT(world.rigidLinearVelocity(box).norm(), 1e-3);
    EXPECT_NEAR(world.rigidContactImpulse(box, ground), m * 9.81 * h, 0.02 * m * 9.81 * h);
  }
}

TEST(RigidApi, PushingStaticOrNonFiniteIsRefusedWithAReason) {
  World world;
  const RigidBodyId ground = *world.addRigidBody(groundDesc());
  const RigidBodyId box = *world.addRigidBody(boxDesc("box", {0.2, 0.2, 0.2}, 1.0, {0, 1, 0}));
  EXPECT_EQ(world.applyForce(ground, Vec3(1, 0, 0)).message(), "apply force: rigid body 'ground' is static or kinematic");
  EXPECT_EQ(world.setRigidLinearVelocity(ground, Vec3(1, 0, 0)).message(),
            "set linear velocity: rigid body 'ground' is static or kinematic");
  EXPECT_EQ(world.applyImpulseAtPoint(box, Vec3(NAN, 0, 0), Vec3::Zero()).message(),
            "apply impulse at point: impulse is not finite");
  EXPECT_EQ(world.applyForceAtPoint(box, Vec3(1, 0, 0), Vec3(0, INFINITY, 0)).message(),
            "apply force at point: point is not finite");
  EXPECT_EQ(world.setRigidPose(box, Vec3::Zero(), Quat(0, 0, 0, 0)).message(),
            "set pose: orientation must be a finite non-zero quaternion");
  EXPECT_EQ(world.applyTorque(RigidBodyId{7}, Vec3(1, 0, 0)).message(),
            "apply torque: rigid body 7: no such rigid body (the world has 2 slots)");
  EXPECT_LT(world.rigidLinearVelocity(box).norm(), 1e-15);  // nothing was applied
}

// ---- Collision filters ----------------------------------------------------------------------

TEST(RigidApi, BoxWhoseMaskExcludesTheGroundFallsThroughIt) {
  World world;
  RigidBodyDesc ground = groundDesc();
  ground.collisionGroup = 2;
  ASSERT_TRUE(world.addRigidBody(ground).ok());
  RigidBodyDesc ghostDesc = boxDesc("ghost", {0.2, 0.2, 0.2}, 1.0, {0, 0.5, 0});
  ghostDesc.collisionMask = kAllCollisionGroups & ~2u;
  const RigidBodyId ghost = *world.addRigidBody(ghostDesc);
  const RigidBodyId solid = *world.addRigidBody(boxDesc("solid", {0.2, 0.2, 0.2}, 1.0, {2, 0.5, 0}));
  const double h = 1.0 / 60;
  const int steps = 60;
  for (int i = 0; i < steps; ++i) ASSERT_TRUE(world.step(h).ok());
  // Free fall by symplectic Euler: y = y₀ − g h² n (n + 1) / 2.
  EXPECT_NEAR(world.rigidPosition(ghost).y(), 0.5 - 9.81 * h * h * steps * (steps + 1) / 2, 1e-9);
  EXPECT_NEAR(world.rigidPosition(solid).y(), 0.2, 0.01);
  EXPECT_EQ(world.rigidCollisionMask(ghost), kAllCollisionGroups & ~2u);

  // Changed on the fly: the resting box drops through too.
  ASSERT_TRUE(world.setRigidCollisionFilter(solid, 1, 1).ok());
  for (int i = 0; i < 30; ++i) ASSERT_TRUE(world.step(h).ok());
  EXPECT_LT(world.rigidPosition(solid).y(), -0.5);
}

DeformableDesc clothDesc(double y) {
  DeformableDesc desc;
  desc.name = "cloth";
  desc.mesh = *makeClothGrid({-0.5, y, -0.5}, {1, 0, 0}, {0, 0, 1}, 9, 9, 0.2);
  desc.inextensibility.enabled = true;
  return desc;
}

double meanY(std::span<const Vec3> nodes) {
  double y = 0.0;
  for (const Vec3& p : nodes) y += p.y();
  return y / static_cast<double>(nodes.size());
}

// A cloth filtered against a sphere falls through it; one that is not rests on it.
TEST(RigidApi, ClothFilteredAgainstASphereFallsThroughIt) {
  for (bool filtered : {false, true}) {
    World world;
    RigidBodyDesc sphere;
    sphere.name = "sphere";
    sphere.shape = RigidShape::sphere(0.3);
    sphere.motion = MotionType::Static;
    sphere.collisionGroup = 4;
    ASSERT_TRUE(world.addRigidBody(sphere).ok());
    DeformableDesc cloth = clothDesc(0.5);
    if (filtered) cloth.collision.mask = ~4u;
    const DeformableId id = *world.addDeformable(cloth);
    for (int i = 0; i < 45; ++i) ASSERT_TRUE(world.step(1.0 / 60).ok());
    const double y = meanY(world.nodePositions(id));
    if (filtered) {
      EXPECT_TRUE(world.contacts().empty());
      EXPECT_LT(y, 0.5 - 0.5 * 9.81 * 0.7 * 0.7);  // fell freely for 0.75 s (less the slack)
    } else {
      EXPECT_FALSE(world.contacts().empty());
      EXPECT_GT(y, 0.0);  // draped over the sphere's top at 0.3
    }
  }
  // The same by setDeformableCollisionFilter, and between two deformables.
  World world;
  RigidBodyDesc ground = groundDesc();
  ground.collisionGroup = 4;
  ASSERT_TRUE(world.addRigidBody(ground).ok());
  const DeformableId lower = *world.addDeformable(clothDesc(0.05));
  const DeformableId upper = *world.addDeformable(clothDesc(0.3));
  ASSERT_TRUE(world.setDeformableCollisionFilter(upper, 2, ~1u).ok());
  ASSERT_TRUE(world.setDeformableCollisionFilter(lower, 1, kAllCollisionGroups).ok());
  for (int i = 0; i < 60; ++i) ASSERT_TRUE(world.step(1.0 / 60).ok());
  for (const ContactReport& c : world.contacts()) EXPECT_FALSE(c.other.has_value());  // no cloth-cloth contact
  EXPECT_NEAR(meanY(world.nodePositions(upper)), meanY(world.nodePositions(lower)), 0.01);  // both on the ground
  EXPECT_EQ(world.setDeformableCollisionFilter(DeformableId{4}, 1, 1).message(),
            "collision filter: deformable 4: no such deformable (the world has 2 slots)");
}

// ---- Hinges ---------------------------------------------------------------------------------

struct HingedBar {
  World world;
  RigidBodyId bar;
  JointId hinge;
  double inertia = 0.0;  // about the hinge axis (z, through the centre)
};

// A 1 kg bar 1 m long along x, hinged to the world about z through its centre, no gravity.
void makeHingedBar(HingedBar& out, const HingeDesc& motion) {
  ASSERT_TRUE(out.world.setSettings(zeroGravity()).ok());
  out.bar = *out.world.addRigidBody(boxDesc("bar", {0.5, 0.05, 0.05}, 1.0, {0, 1, 0}));
  HingeDesc desc = motion;
  desc.bodyA = out.bar;
  desc.pivot = {0, 1, 0};
  desc.axis = {0, 0, 1};
  out.hinge = *out.world.addHinge(desc);
  out.inertia = 1.0 / 12 * (1.0 * 1.0 + 0.1 * 0.1);
}

TEST(RigidApi, HingeMotorReachesItsSpeedOrAcceleratesAtMaxTorqueOverInertia) {
  const double h = 1.0 / 240;
  {
    HingeDesc strong;
    strong.motor = true;
    strong.motorTargetSpeed = 3.0;
    strong.motorMaxTorque = 50.0;
    HingedBar bar;
    makeHingedBar(bar, strong);
    for (int i = 0; i < 60; ++i) ASSERT_TRUE(bar.world.step(h).ok());
    EXPECT_NEAR(bar.world.hingeSpeed(bar.hinge), 3.0, 0.01);
    EXPECT_NEAR(bar.world.rigidAngularVelocity(bar.bar).z(), 3.0, 0.01);  // right-handed about +z
    // Its angle follows the integrated speed, and the body's own rotation about z.
    const Quat q = bar.world.rigidOrientation(bar.bar);
    EXPECT_NEAR(bar.world.hingeAngle(bar.hinge), 2 * std::atan2(q.z(), q.w()), 1e-6);
    EXPECT_GT(bar.world.hingeAngle(bar.hinge), 0.0);
  }
  {
    HingeDesc weak;
    weak.motor = true;
    weak.motorTargetSpeed = 3.0;
    weak.motorMaxTorque = 0.1;
    HingedBar bar;
    makeHingedBar(bar, weak);
    const int steps = 120;  // 0.5 s: τ/I t = 0.577 rad/s, short of the target
    for (int i = 0; i < steps; ++i) ASSERT_TRUE(bar.world.step(h).ok());
    const double expected = 0.1 / bar.inertia * steps * h;
    EXPECT_NEAR(bar.world.hingeSpeed(bar.hinge), expected, 0.01 * expected);
    // Reversed at run time, it decelerates at the same rate.
    ASSERT_TRUE(bar.world.setHingeMotor(bar.hinge, true, -3.0, 0.1).ok());
    for (int i = 0; i < steps / 2; ++i) ASSERT_TRUE(bar.world.step(h).ok());
    EXPECT_NEAR(bar.world.hingeSpeed(bar.hinge), expected / 2, 0.02 * expected);
  }
}

TEST(RigidApi, HingeLimitHoldsTheAngleWithinItsRange) {
  HingeDesc limited;
  limited.lowerLimit = -0.3;
  limited.upperLimit = 0.5;
  HingedBar bar;
  makeHingedBar(bar, limited);
  const double h = 1.0 / 240;
  ASSERT_TRUE(bar.world.setRigidAngularVelocity(bar.bar, Vec3(0, 0, 4.0)).ok());  // swings up
  double highest = -1.0;
  for (int i = 0; i < 240; ++i) {
    ASSERT_TRUE(bar.world.step(h).ok());
    highest = std::max(highest, bar.world.hingeAngle(bar.hinge));
  }
  EXPECT_NEAR(highest, 0.5, 0.03);
  ASSERT_TRUE(bar.world.setRigidAngularVelocity(bar.bar, Vec3(0, 0, -4.0)).ok());  // and down
  double lowest = 1.0;
  for (int i = 0; i < 240; ++i) {
    ASSERT_TRUE(bar.world.step(h).ok());
    lowest = std::min(lowest, bar.world.hingeAngle(bar.hinge));
  }
  EXPECT_NEAR(lowest, -0.3, 0.03);
  // A motor pushing into the limit stalls at it.
  ASSERT_TRUE(bar.world.setHingeMotor(bar.hinge, true, 2.0, 5.0).ok());
  for (int i = 0; i < 480; ++i) ASSERT_TRUE(bar.world.step(h).ok());
  EXPECT_NEAR(bar.world.hingeAngle(bar.hinge), 0.5, 0.03);
  EXPECT_NEAR(bar.world.hingeSpeed(bar.hinge), 0.0, 0.05);

  // Limits removed: free to turn on past.
  ASSERT_TRUE(bar.world.setHingeLimits(bar.hinge, 1, -1).ok());
  for (int i = 0; i < 240; ++i) ASSERT_TRUE(bar.world.step(h).ok());
  EXPECT_NEAR(bar.world.hingeSpeed(bar.hinge), 2.0, 0.02);
}

TEST(RigidApi, BadHingeSettingsAreRefused) {
  World world;
  const RigidBodyId a = *world.addRigidBody(boxDesc("a", {0.1, 0.1, 0.1}, 1.0, {0, 0, 0}));
  HingeDesc desc;
  desc.bodyA = a;
  desc.lowerLimit = -4;
  desc.upperLimit = 0;
  EXPECT_EQ(world.addHinge(desc).message(), "hinge: limits must lie in [-pi, pi] rad, got [-4, 0]");
  desc.lowerLimit = 1;
  desc.upperLimit = -1;
  desc.motor = true;
  desc.motorMaxTorque = -1;
  EXPECT_EQ(world.addHinge(desc).message(), "hinge: motor max torque must be >= 0 and finite, got -1 N·m");
  desc.motorMaxTorque = 1;
  const JointId hinge = *world.addHinge(desc);
  const JointId fixed = *world.addFixedJoint({a, std::nullopt});
  EXPECT_EQ(world.setHingeMotor(fixed, true, 1, 1).message(), "hinge motor: joint 1 is a fixed joint, not a hinge");
  EXPECT_EQ(world.setHingeLimits(hinge, NAN, 1).message(),
            "hinge limits: limits must lie in [-pi, pi] rad (lower > upper for none), got [nan, 1]");
  EXPECT_EQ(world.setHingeMotor(hinge, true, INFINITY, 1).message(), "hinge motor: target speed must be finite");
  EXPECT_EQ(world.hingeAngle(fixed), 0.0);
  EXPECT_EQ(world.takeLookupError().message(), "joint 1 is not a hinge");
}

}  // namespace
}  // namespace tandem
