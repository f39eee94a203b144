// Contacts and friction: cloth against rigid shapes, against cloth and against itself.
#include "collision/contact_motion.h"
#include "collision/geometry.h"
#include "gauntlet.h"
#include "rigid_distance.h"
#include "short_tests.h"

#include <tandem/world.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace tandem {
namespace {

using testing_support::collisionShape;
using testing_support::signedDistance;

constexpr double kStep = 1.0 / 60.0;
constexpr double kPi = 3.14159265358979323846;
constexpr double kGravity = 9.81;

DeformableDesc clothDesc(std::string name, const Vec3& corner, double size, int nodes, double mass) {
  DeformableDesc desc;
  desc.name = std::move(name);
  desc.mesh = *makeClothGrid(corner, {size, 0, 0}, {0, 0, size}, nodes, nodes, mass);
  desc.inextensibility.enabled = true;
  desc.bending.enabled = true;
  desc.bending.maxForce = 0.05;
  desc.collision.friction = 1.0;  // μ = 0.5 against a rigid body's default 0.5
  return desc;
}

RigidBodyDesc staticBody(std::string name, const RigidShape& shape, const Vec3& position,
                         const Quat& orientation = Quat::Identity()) {
  RigidBodyDesc desc;
  desc.name = std::move(name);
  desc.shape = shape;
  desc.motion = MotionType::Static;
  desc.position = position;
  desc.orientation = orientation;
  return desc;
}

// A square pyramid, 0.6 m wide and 0.4 m tall, about its base centre.
RigidShape pyramid() {
  return RigidShape::convexHull({{-0.3, 0, -0.3}, {0.3, 0, -0.3}, {0.3, 0, 0.3}, {-0.3, 0, 0.3}, {0, 0.4, 0}});
}

// Two boxes as one compound body: a 0.6 m wide block 0.2 m tall and, beside it, a 0.3 m tall
// step 0.3 m wide, about the block's base centre.
RigidShape steps() {
  auto box = [](const Vec3& low, const Vec3& high) {
    std::vector<Vec3> corners;
    for (int c = 0; c < 8; ++c) corners.emplace_back(c & 1 ? high.x() : low.x(), c & 2 ? high.y() : low.y(), c & 4 ? high.z() : low.z());
    return corners;
  };
  return RigidShape::compound({box({-0.3, 0, -0.3}, {0.3, 0.2, 0.3}), box({0.3, 0, -0.3}, {0.6, 0.3, 0.3})});
}

// A roof: a 1.2 m square ridge, 0.3 m high along x = 0, as a static triangle mesh.
RigidShape roof() {
  return RigidShape::triangleMesh({{-0.6, 0, -0.6}, {0, 0.3, -0.6}, {0.6, 0, -0.6}, {-0.6, 0, 0.6}, {0, 0.3, 0.6}, {0.6, 0, 0.6}},
                                  {{0, 3, 1}, {1, 3, 4}, {1, 4, 2}, {2, 4, 5}});
}

double fastestNode(const World& world, DeformableId id) {
  double fastest = 0.0;
  for (const Vec3& v : world.nodeVelocities(id)) fastest = std::max(fastest, v.norm());
  return fastest;
}

double rmsNodeSpeed(const World& world, DeformableId id) {
  double sum = 0.0;
  for (const Vec3& v : world.nodeVelocities(id)) sum += v.squaredNorm();
  return std::sqrt(sum / static_cast<double>(world.nodeVelocities(id).size()));
}

// ---- Cloth dropped on static shapes -------------------------------------------------------

struct DropCase {
  const char* name;
  RigidShape shape;
  Vec3 position;
};

class ClothDrop : public ::testing::TestWithParam<DropCase> {};

TEST_P(ClothDrop, RestsOnTheShapeWithoutPenetrating) {
  const DropCase& drop = GetParam();
  // 34 s under the sanitizers for the sphere, whose contacts the paper's cloth scene runs there.
  if (shortTests() && drop.shape.type == ShapeType::Sphere) GTEST_SKIP() << "long under the sanitizers; the Release suite runs it";
  World world;
  const RigidBodyId body = *world.addRigidBody(staticBody(drop.name, drop.shape, drop.position));
  const geometry::CollisionShape shape = collisionShape(drop.shape);
  if (drop.shape.type != ShapeType::Plane && drop.shape.type != ShapeType::TriangleMesh) {  // on a floor
    ASSERT_TRUE(world.addRigidBody(staticBody("floor", RigidShape::plane({0, 1, 0}, 0.0), Vec3::Zero())).ok());
  }
  DeformableDesc desc = clothDesc("cloth", {-0.5, 0.6, -0.5}, 1.0, 21, 0.2);
  desc.damping = 2.0;  // air and the cloth's own friction: it settles in seconds
  const double thickness = desc.collision.thickness;
  const DeformableId cloth = *world.addDeformable(desc);
  double deepest = 1e9;
  for (int step = 0; step < 180; ++step) {  // 3 s
    ASSERT_TRUE(world.step(kStep).ok()) << "step " << step;
    for (const Vec3& p : world.nodePositions(cloth)) deepest = std::min(deepest, signedDistance(world, body, shape, p));
  }
  // Inextensible once it lies still. (While its corners whip round the shape on impact, edges
  // there stretch by up to a fifth for a few steps: docs/architecture.md, known limits.)
  const DeformableMesh& rest = world.restMesh(cloth);
  const auto x = world.nodePositions(cloth);
  double stretch = 0.0;
  for (const auto& e : rest.edges)
    stretch = std::max(stretch, (x[e[1]] - x[e[0]]).norm() / (rest.positions[e[1]] - rest.positions[e[0]]).norm() - 1);
  EXPECT_LT(stretch, 0.01) << drop.name;
  // No node ever gets inside the shape by more than the thickness (it is kept a thickness out).
  EXPECT_GT(deepest, -thickness) << drop.name;
  for (const Vec3& p : x) ASSERT_TRUE(p.allFinite());
  // At rest, as far as Tandem gets today: the cloth as a whole (RMS node speed) and every node.
  // A residual buzz of about 1 cm/s RMS remains on the sphere (plane and box: well below), a
  // known limit of the contact handling on curved surfaces (docs/architecture.md).
  EXPECT_LT(rmsNodeSpeed(world, cloth), 0.02) << drop.name << ": the cloth should be at rest";
  EXPECT_LT(fastestNode(world, cloth), 0.1) << drop.name;
  EXPECT_GT(world.contacts().size(), 10u);
}

INSTANTIATE_TEST_SUITE_P(
    Shapes, ClothDrop,
    ::testing::Values(DropCase{"plane", RigidShape::plane({0, 1, 0}, 0.0), Vec3::Zero()},
                      DropCase{"box", RigidShape::box({0.3, 0.2, 0.3}), Vec3(0, 0.2, 0)},
                      DropCase{"sphere", RigidShape::sphere(0.3), Vec3(0, 0.3, 0)},
                      DropCase{"hull", pyramid(), Vec3::Zero()}, DropCase{"mesh", roof(), Vec3::Zero()}),
    [](const ::testing::TestParamInfo<DropCase>& param) { return std::string(param.param.name); });

// KNOWN FAILURE, disabled until fixed: on the two-box compound the cloth ends with a node 8.6 cm
// inside the shape (measured: deepest -0.0858 m against -0.005 m allowed; fastest node 0.105 m/s).
// Run it with --gtest_also_run_disabled_tests.
INSTANTIATE_TEST_SUITE_P(
    DISABLED_Compound, ClothDrop, ::testing::Values(DropCase{"compound", steps(), Vec3::Zero()}),
    [](const ::testing::TestParamInfo<DropCase>& param) { return std::string(param.param.name); });

TEST(Contact, RigidHullRestsOnAStaticMeshAtItsHeight) {
  World world;
  const std::vector<Vec3> floor{{-2, 0, -2}, {2, 0, -2}, {2, 0, 2}, {-2, 0, 2}};
  ASSERT_TRUE(world.addRigidBody(staticBody("floor", RigidShape::triangleMesh(floor, {{0, 2, 1}, {0, 3, 2}}), Vec3::Zero())).ok());
  RigidBodyDesc tetra;
  tetra.name = "tetra";
  tetra.shape = RigidShape::convexHull({{0.2, -0.1, 0}, {-0.1, -0.1, 0.17}, {-0.1, -0.1, -0.17}, {0, 0.2, 0}});
  tetra.position = {0, 0.5, 0};
  const RigidBodyId body = *world.addRigidBody(tetra);
  for (int step = 0; step < 180; ++step) ASSERT_TRUE(world.step(kStep).ok());
  // Its base (0.1 m below its frame's origin) on the floor, within Bullet's collision margins.
  EXPECT_NEAR(world.rigidPosition(body).y(), 0.1, 0.02);
  EXPECT_LT(world.rigidLinearVelocity(body).norm(), 0.01);
}

TEST(Contact, BadHullsAndMeshesAreRefused) {
  World world;
  RigidBodyDesc body;
  body.name = "thing";
  body.shape = RigidShape::convexHull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  EXPECT_EQ(world.addRigidBody(body).message(), "rigid body 'thing': a convex hull needs at least 4 points");
  body.shape = RigidShape::convexHull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}});
  EXPECT_EQ(world.addRigidBody(body).message(), "rigid body 'thing': the convex hull's points are flat (no volume)");
  body.shape = RigidShape::convexHull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, std::nan("")}});
  EXPECT_EQ(world.addRigidBody(body).message(), "rigid body 'thing': convex hull point 3 is not finite");
  body.shape = RigidShape::triangleMesh({{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}, {{0, 1, 5}});
  body.motion = MotionType::Static;
  EXPECT_EQ(world.addRigidBody(body).message(),
            "rigid body 'thing': triangle mesh: triangle 0 refers to node 5, but the mesh has 3 nodes");
  body.shape = RigidShape::triangleMesh({{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}, {{0, 1, 2}});
  body.motion = MotionType::Dynamic;
  EXPECT_EQ(world.addRigidBody(body).message(), "rigid body 'thing': a plane or a triangle mesh can only be static");
}

// ---- A box on a hammock -------------------------------------------------------------------

TEST(Contact, BoxRestsOnAHammockAndThePinsCarryItsWeight) {
  // 45 s under the sanitizers; there cli_run_whole_hammock runs the shipped hammock scene.
  if (shortTests()) GTEST_SKIP() << "long under the sanitizers; the Release suite runs it";
  World world;
  const int n = 21;
  DeformableDesc desc = clothDesc("hammock", {-0.5, 1.0, -0.5}, 1.0, n, 0.2);
  desc.damping = 2.0;
  const DeformableId hammock = *world.addDeformable(desc);
  std::vector<FixedPointId> pins;
  for (int node : {0, n - 1, n * (n - 1), n * n - 1})
    pins.push_back(*world.addFixedPoint(hammock, node, world.nodePositions(hammock)[node]));
  RigidBodyDesc crate;
  crate.name = "box";
  crate.shape = RigidShape::box({0.1, 0.1, 0.1});
  crate.mass = 1.0;
  crate.position = {0, 1.3, 0};
  const RigidBodyId box = *world.addRigidBody(crate);
  double lowest = 1e9, pinned = 0.0, force = 0.0, normal = 0.0, speed = 0.0;
  const int steps = 300, averaged = 30;  // 5 s; forces averaged over the last half second
  for (int step = 0; step < steps; ++step) {
    ASSERT_TRUE(world.step(kStep).ok()) << "step " << step;
    lowest = std::min(lowest, world.rigidPosition(box).y());
    if (step < steps - averaged) continue;
    for (FixedPointId pin : pins) pinned += world.fixedPointImpulse(pin).y() / averaged;
    force += world.deformableForceOnRigid(box).y() / averaged;
    speed += world.rigidLinearVelocity(box).norm() / averaged;
    for (const ContactReport& contact : world.contacts())
      if (contact.rigid && *contact.rigid == box)
        normal -= (contact.normalImpulse * contact.normal + contact.frictionImpulse).y() / averaged;
  }
  // It rests on the cloth: the cloth sags, but the box stays above the pins' plane minus a sag
  // an inextensible 1 m cloth pinned at its corners can make (its half diagonal, 0.71 m).
  const double centre = world.nodePositions(hammock)[n * n / 2].y();
  EXPECT_LT(centre, 1.0 - 0.02);
  EXPECT_GT(lowest, 1.0 - 0.71);
  EXPECT_GT(world.rigidPosition(box).y(), centre);  // on top of the cloth, not through it
  // (The box is carried, but not still: a rocking of a few cm/s stays alive; docs/solver.md,
  // rest on cloth. Measured, not asserted.)
  RecordProperty("box_mean_speed_last_half_second", std::to_string(speed));
  // The pins carry box and cloth: (1 + 0.2) kg · g · h per step, within 5 %.
  const double weight = 1.2 * kGravity * kStep;
  EXPECT_NEAR(pinned, weight, 0.05 * weight);
  // And the contacts report the box's weight: the force the cloth puts on it, and the contact
  // impulses on the cloth (downwards; normal and friction: on the sagging cloth the contacts are
  // tilted, and friction that grips carries part of the weight, 5-6 % here).
  EXPECT_NEAR(force, kGravity, 0.05 * kGravity);
  EXPECT_NEAR(normal, kGravity * kStep, 0.05 * kGravity * kStep);
}

// Lifted off the hammock, the box's contacts would pull the cloth up with it: the direct block
// lets them go (solved again without their equations, src/solver/direct_block.cpp), so the box
// rises as if nothing held it, (F − m g) / m, and the cloth stays down.
TEST(Contact, BoxLiftedOffAHammockLeavesTheClothBehind) {
  World world;
  const int n = 21;
  DeformableDesc desc = clothDesc("hammock", {-0.5, 1.0, -0.5}, 1.0, n, 0.2);
  desc.damping = 2.0;
  const DeformableId hammock = *world.addDeformable(desc);
  for (int node : {0, n - 1, n * (n - 1), n * n - 1}) ASSERT_TRUE(world.fixNode(hammock, node).ok());
  RigidBodyDesc crate;
  crate.name = "box";
  crate.shape = RigidShape::box({0.05, 0.05, 0.05});
  crate.mass = 1.0;
  crate.position = {0, 1.1, 0};
  const RigidBodyId box = *world.addRigidBody(crate);
  for (int step = 0; step < 120; ++step) ASSERT_TRUE(world.step(kStep).ok()) << "step " << step;
  ASSERT_FALSE(world.contacts().empty());
  // Pulled up by a grab saturated at four times its weight: it rises at 3 g.
  GrabDesc grab;
  grab.body = box;
  grab.point = world.rigidPosition(box);
  grab.target = grab.point + Vec3(0, 10.0, 0);  // far: the grab pulls at its bound all the way
  grab.maxForce = 4.0 * kGravity;
  ASSERT_TRUE(world.addGrab(grab).ok());
  // The cloth, unloaded, springs up under it and pushes it for a few steps, less each step. How
  // many depends on the trajectory's last bits: the box is still bouncing on the cloth when
  // grabbed (it never comes to rest there: docs/solver.md). From when the push is under a
  // tenth of the 1 % measured below (m · 0.03 g · h):
  auto pushOnBox = [&] {
    double impulse = 0.0;
    for (const ContactReport& contact : world.contacts())
      if (contact.rigid == box) impulse += contact.normalImpulse;
    return impulse;
  };
  double push = INFINITY;
  for (int touching = 0; push > 0.003 * kGravity * kStep; ++touching) {
    ASSERT_LT(touching, 6) << "the cloth still pushes the box up: " << push << " N s";
    ASSERT_TRUE(world.step(kStep).ok());
    ASSERT_LT(pushOnBox(), 0.5 * push) << "the cloth's push on the box does not fade";
    push = pushOnBox();
  }
  const double clothBefore = world.nodePositions(hammock)[n * n / 2].y();
  const double heightBefore = world.rigidPosition(box).y();
  for (int step = 0; step < 15; ++step) {
    const double before = world.rigidLinearVelocity(box).y();
    ASSERT_TRUE(world.step(kStep).ok());
    const double acceleration = (world.rigidLinearVelocity(box).y() - before) / kStep;
    EXPECT_NEAR(acceleration, 3 * kGravity, 0.01 * kGravity) << "step " << step;
  }
  // It went up over a metre; the cloth, unloaded, springs back by about its sag under the box
  // (10–11 cm; the contacts' friction arms decide the last centimetre), no more: dragged along,
  // it would rise with the box.
  EXPECT_GT(world.rigidPosition(box).y() - heightBefore, 1.0);
  EXPECT_LT(world.nodePositions(hammock)[n * n / 2].y() - clothBefore, 0.12);
}

// ---- A small ball onto a pinned cloth --------------------------------------------------------

// A 4 cm, 50 g ball dropped onto a 21 × 21 cloth pinned along its edges (3.3 cm triangles, 5 cm
// cells) at the projectile scenes' step, h = 20 ms. The cloth's rows are one direct block with
// the ball, so the ball is held across the sheet; what let it through on main was the position
// passes after the step: they kept the cloth's nodes out of the ball but not its faces, and the
// edges drew the nodes round the ball's sides until it fell between them
// (src/solver/strain_limiting.h, FaceOnCore). Measured before that: through at 2 and 5 m/s. A
// capsule (a core segment rather than a point) lying across the sheet is kept off the same way.
// Not yet at every speed: 6 and 7 m/s were held since the sheet's projection moves the ball with
// the sheet (strain_limiting.h, twenty-second session), and 3, 4, 8 and 10 m/s since a block's
// projection that would lengthen the sheet's worst edge is undone (direct_block.cpp, thirtieth
// session: the cloth sagging under its own weight before the ball arrives had been projected
// worse); with that, the ball at 7 m/s ends up 6.9 cm under the cloth at step 4 (DISABLED_ below;
// docs/solver.md, thirtieth session).
struct BallDrop {
  bool capsule;
  double speed;
};
void PrintTo(const BallDrop& drop, std::ostream* out) {
  *out << (drop.capsule ? "capsule" : "ball") << " at " << drop.speed << " m/s";
}
class BallOntoPinnedCloth : public ::testing::TestWithParam<BallDrop> {};

TEST_P(BallOntoPinnedCloth, IsHeldAndGainsNoEnergy) {
  const double speed = GetParam().speed;
  World world;
  const int n = 21;
  DeformableDesc desc = clothDesc("cloth", {-0.5, 1.0, -0.5}, 1.0, n, 0.1);
  const DeformableId cloth = *world.addDeformable(desc);
  for (int i = 0; i < n; ++i)
    for (int node : {i, n * (n - 1) + i, n * i, n * i + n - 1}) ASSERT_TRUE(world.fixNode(cloth, node).ok());
  RigidBodyDesc ball;
  ball.name = "ball";
  ball.shape = GetParam().capsule ? RigidShape::capsule(0.02, 0.03) : RigidShape::sphere(0.02);
  ball.orientation = Quat(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitZ()));  // a capsule's axis along x
  ball.mass = 0.05;
  ball.position = {0.013, 1.3, 0.007};
  ball.linearVelocity = {0, -speed, 0};
  ball.canSleep = false;
  const RigidBodyId body = *world.addRigidBody(ball);
  const auto energy = [&] {
    return 0.5 * ball.mass * world.rigidLinearVelocity(body).squaredNorm() + ball.mass * kGravity * world.rigidPosition(body).y();
  };
  const double start = energy();
  const double h = 0.02;
  for (int step = 0; step < 75; ++step) {
    ASSERT_TRUE(world.step(h).ok()) << "step " << step;
    EXPECT_LT(energy(), start + 0.01 * std::abs(start)) << "step " << step;
    // Over the sheet, the ball's centre stays above the cloth node nearest to it across.
    // (Bounced at 5 m/s, it can fly off past the pinned edge.)
    const Vec3 c = world.rigidPosition(body);
    if (std::max(std::abs(c.x()), std::abs(c.z())) > 0.5) continue;
    double nearest = INFINITY, above = 0.0;
    for (const Vec3& x : world.nodePositions(cloth)) {
      const double across = std::hypot(x.x() - c.x(), x.z() - c.z());
      if (across < nearest) {
        nearest = across;
        above = c.y() - x.y();
      }
    }
    ASSERT_GT(above, 0.0) << "step " << step << ": the ball is " << -above << " m under the cloth";
  }
}

INSTANTIATE_TEST_SUITE_P(Speeds, BallOntoPinnedCloth,
                         ::testing::Values(BallDrop{false, 1.0}, BallDrop{false, 2.0}, BallDrop{false, 3.0},
                                           BallDrop{false, 4.0}, BallDrop{false, 5.0}, BallDrop{false, 6.0},
                                           BallDrop{false, 8.0}, BallDrop{false, 10.0}, BallDrop{true, 2.0},
                                           BallDrop{true, 5.0}));
INSTANTIATE_TEST_SUITE_P(DISABLED_SpeedsNotYetHeld, BallOntoPinnedCloth, ::testing::Values(BallDrop{false, 7.0}));

// ---- A corner into a coarse face ----------------------------------------------------------

// ---- Contacts moving on within a step (collision/contact_motion.h) -------------------------

// A node against a sphere is measured again in each substep: carried a quarter turn round it, its
// normal, point and gap are the sphere's there. A face against a turning box keeps its normal;
// its gap moves by the relative displacement, the box's point turned with it.
TEST(Contact, ContactsMoveOnWithTheirTwoSidesWithinAStep) {
  const geometry::CollisionShape sphere = collisionShape(RigidShape::sphere(0.5));
  const geometry::CollisionShape box = collisionShape(RigidShape::box({0.5, 0.5, 0.5}));
  const double thickness = 0.01;
  std::vector<Vec3> start{{0, 0.52, 0}, {-0.1, 0.6, 0}, {0.1, 0.6, 0}, {0, 0.6, 0.1}};
  std::vector<Vec3> now = start;
  now[0] = {0.53, 0, 0};  // a quarter turn round the sphere, 3 cm out
  for (int k = 1; k < 4; ++k) now[k] += Vec3(0, -0.04, 0);  // the face came 4 cm down
  ContactRow onSphere;
  onSphere.node = {0, 0, 0, 0};
  onSphere.coefficient = {1, 0, 0, 0};
  onSphere.body = 0;
  onSphere.normal = Vec3::UnitY();
  onSphere.startGap = onSphere.gap = 0.01;
  ContactRow onBox;  // the box's top corner region under a face
  onBox.node = {1, 2, 3, 1};
  onBox.coefficient = {1.0 / 3, 1.0 / 3, 1.0 / 3, 0};
  onBox.body = 1;
  onBox.normal = Vec3::UnitY();
  onBox.startOffset = onBox.offset = Vec3(0, 0.5, 0);
  onBox.startGap = onBox.gap = 0.09;
  std::vector<ContactRow> contacts{onSphere, onBox};
  const Quat turn(Eigen::AngleAxisd(0.1, Vec3::UnitZ()));
  const std::vector<RigidPose> startPoses{{Vec3::Zero(), Quat::Identity()}, {Vec3(0, 0, 0), Quat::Identity()}};
  const std::vector<CollisionRigid> shapes{{&sphere, Vec3::Zero(), Quat::Identity(), Vec3::Zero(), Vec3::Zero(), 0, 0},
                                           {&box, Vec3(0, 0.01, 0), turn, Vec3::Zero(), Vec3::Zero(), 0, 0}};
  moveContactsOn(std::span<ContactRow>(contacts), now, start, shapes, startPoses, [&](int32_t) { return thickness; });
  EXPECT_NEAR((contacts[0].normal - Vec3::UnitX()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(contacts[0].gap, 0.53 - 0.5 - thickness, 1e-12);
  EXPECT_NEAR((contacts[0].offset - Vec3(0.5 + thickness, 0, 0)).norm(), 0.0, 1e-12);
  // Face: down 4 cm; the box up 1 cm and its point r = (0, 0.5, 0) turned by 0.1 rad about z.
  const Vec3 turned = turn * Vec3(0, 0.5, 0);
  EXPECT_NEAR((contacts[1].offset - turned).norm(), 0.0, 1e-12);
  EXPECT_NEAR(contacts[1].gap, 0.09 - 0.04 - 0.01 - (turned.y() - 0.5), 1e-12);
  EXPECT_EQ(contacts[1].normal, Vec3::UnitY());
}

TEST(Contact, BoxCornerDoesNotPokeThroughACoarseFace) {
  World world;
  DeformableDesc desc = clothDesc("coarse", {-0.6, 1.0, -0.6}, 1.2, 4, 0.2);
  const DeformableId cloth = *world.addDeformable(desc);
  for (int node : {0, 3, 12, 15}) ASSERT_TRUE(world.fixNode(cloth, node).ok());
  RigidBodyDesc crate;
  crate.name = "box";
  crate.shape = RigidShape::box({0.05, 0.05, 0.05});
  crate.mass = 0.5;
  // Corner down: turned 45° about z and 35.26° about x, placed over the middle of a face.
  crate.orientation = Quat(Eigen::AngleAxisd(std::atan(1 / std::sqrt(2.0)), Vec3::UnitX())) *
                      Quat(Eigen::AngleAxisd(kPi / 4, Vec3::UnitZ()));
  crate.position = {0.1, 1.2, -0.07};
  crate.linearVelocity = {0, -1.0, 0};
  const RigidBodyId box = *world.addRigidBody(crate);
  for (int step = 0; step < 120; ++step) {
    ASSERT_TRUE(world.step(kStep).ok());
    // The box's lowest point against the cloth surface right under it.
    const Mat3 rotation = world.rigidOrientation(box).toRotationMatrix();
    Vec3 lowest = world.rigidPosition(box) + rotation * Vec3(0.05, 0.05, 0.05);
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 p = world.rigidPosition(box) +
                     rotation * Vec3(corner & 1 ? 0.05 : -0.05, corner & 2 ? 0.05 : -0.05, corner & 4 ? 0.05 : -0.05);
      if (p.y() < lowest.y()) lowest = p;
    }
    const auto x = world.nodePositions(cloth);
    double surface = -1e9;
    for (const auto& t : world.restMesh(cloth).triangles) {
      // The triangle under the corner, seen from above.
      const Vec3 a(x[t[0]].x(), 0, x[t[0]].z()), b(x[t[1]].x(), 0, x[t[1]].z()), c(x[t[2]].x(), 0, x[t[2]].z());
      const auto w = geometry::closestOnTriangle(Vec3(lowest.x(), 0, lowest.z()), a, b, c);
      const Vec3 onPlan = w[0] * a + w[1] * b + w[2] * c;
      if ((onPlan - Vec3(lowest.x(), 0, lowest.z())).norm() > 1e-9) continue;
      surface = w[0] * x[t[0]].y() + w[1] * x[t[1]].y() + w[2] * x[t[2]].y();
    }
    ASSERT_GT(surface, -1e9) << "the corner left the cloth's footprint";
    EXPECT_GT(lowest.y(), surface - 0.002) << "step " << step;
  }
}

// ---- Friction on a slope ------------------------------------------------------------------

// A small cloth patch resting on a static plane tilted by θ about z; returns its mean velocity
// down the slope after `seconds`.
double slideSpeed(double degrees, double mu, FrictionModel model, double seconds) {
  World world;
  WorldSettings settings = world.settings();
  settings.solver.friction = model;
  EXPECT_TRUE(world.setSettings(settings).ok());
  const double theta = degrees * kPi / 180;
  const Quat tilt(Eigen::AngleAxisd(theta, Vec3::UnitZ()));
  const Vec3 normal = tilt * Vec3::UnitY(), downhill = tilt * -Vec3::UnitX();
  RigidBodyDesc slope = staticBody("slope", RigidShape::plane(normal, 0.0), Vec3::Zero());
  slope.friction = mu;
  EXPECT_TRUE(world.addRigidBody(slope).ok());
  DeformableDesc patch;
  patch.name = "patch";
  patch.mesh = *makeClothGrid(Vec3::Zero(), tilt * Vec3(0.2, 0, 0), tilt * Vec3(0, 0, 0.2), 3, 3, 0.05);
  for (Vec3& x : patch.mesh.positions) x += 0.005 * normal;  // resting at its thickness
  patch.inextensibility.enabled = true;
  patch.collision.friction = 1.0;  // μ = 1 · mu
  const DeformableId id = *world.addDeformable(patch);
  for (int step = 0; step < std::lround(seconds / kStep); ++step) EXPECT_TRUE(world.step(kStep).ok());
  Vec3 mean = Vec3::Zero();
  for (const Vec3& v : world.nodeVelocities(id)) mean += v / 9.0;
  return mean.dot(downhill);
}

TEST(Contact, FrictionHoldsBelowTheFrictionAngleAndSlidesAboveIt) {
  const double mu = 0.5;  // friction angle atan 0.5 = 26.6°
  for (FrictionModel model : {FrictionModel::Coulomb, FrictionModel::Pressure}) {
    EXPECT_LT(std::abs(slideSpeed(20, mu, model, 1.0)), 1e-3) << "20° should hold";
    EXPECT_LT(std::abs(slideSpeed(25, mu, model, 1.0)), 1e-3) << "25° should hold";
  }
  for (double degrees : {30.0, 40.0, 55.0}) {
    const double theta = degrees * kPi / 180;
    const double expected = kGravity * (std::sin(theta) - mu * std::cos(theta)) * 1.0;  // v = a t
    EXPECT_NEAR(slideSpeed(degrees, mu, FrictionModel::Coulomb, 1.0), expected, 0.1 * expected) << degrees << "°";
  }
}

// ---- Cloth on cloth -----------------------------------------------------------------------

TEST(Contact, ClothDroppedOnClothStaysOnTop) {
  World world;
  ASSERT_TRUE(world.addRigidBody(staticBody("ground", RigidShape::plane({0, 1, 0}, 0.0), Vec3::Zero())).ok());
  const DeformableId below = *world.addDeformable(clothDesc("below", {-0.5, 0.005, -0.5}, 1.0, 21, 0.2));
  const DeformableId above = *world.addDeformable(clothDesc("above", {-0.4, 0.3, -0.4}, 0.8, 17, 0.15));
  for (int step = 0; step < 120; ++step) ASSERT_TRUE(world.step(kStep).ok()) << "step " << step;
  // Every node of the upper cloth is above the lower cloth's surface beneath it.
  const auto lower = world.nodePositions(below);
  const auto& triangles = world.restMesh(below).triangles;
  int checked = 0;
  for (const Vec3& p : world.nodePositions(above)) {
    for (const auto& t : triangles) {
      const Vec3 a(lower[t[0]].x(), 0, lower[t[0]].z()), b(lower[t[1]].x(), 0, lower[t[1]].z()),
          c(lower[t[2]].x(), 0, lower[t[2]].z());
      const auto w = geometry::closestOnTriangle(Vec3(p.x(), 0, p.z()), a, b, c);
      if ((w[0] * a + w[1] * b + w[2] * c - Vec3(p.x(), 0, p.z())).norm() > 1e-9) continue;
      const double surface = w[0] * lower[t[0]].y() + w[1] * lower[t[1]].y() + w[2] * lower[t[2]].y();
      EXPECT_GT(p.y(), surface + 0.005) << "a node of the upper cloth is through the lower one";
      ++checked;
      break;
    }
  }
  EXPECT_GT(checked, 200);
  EXPECT_LT(rmsNodeSpeed(world, above), 0.02);  // at rest, but for the residual buzz (see ClothDrop)
}

// ---- Self-collision ------------------------------------------------------------------------

// Whether triangle pq r crosses triangle abc: one of the six edges passes through the other face.
bool edgeCrossesTriangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 normal = (b - a).cross(c - a);
  const double dp = normal.dot(p - a), dq = normal.dot(q - a);
  if (dp * dq > 0 || dp == dq) return false;
  const Vec3 hit = p + (dp / (dp - dq)) * (q - p);
  const auto w = geometry::closestOnTriangle(hit, a, b, c);
  return (w[0] * a + w[1] * b + w[2] * c - hit).norm() < 1e-12 && std::min({w[0], w[1], w[2]}) > 0;
}

int countIntersections(std::span<const Vec3> x, const std::vector<std::array<int32_t, 3>>& triangles) {
  int count = 0;
  for (size_t i = 0; i < triangles.size(); ++i)
    for (size_t j = i + 1; j < triangles.size(); ++j) {
      const auto &s = triangles[i], &t = triangles[j];
      bool shared = false;
      for (int a : s)
        for (int b : t) shared |= a == b;
      if (shared) continue;
      bool crossing = false;
      for (int e = 0; e < 3 && !crossing; ++e) {
        crossing |= edgeCrossesTriangle(x[s[e]], x[s[(e + 1) % 3]], x[t[0]], x[t[1]], x[t[2]]);
        crossing |= edgeCrossesTriangle(x[t[e]], x[t[(e + 1) % 3]], x[s[0]], x[s[1]], x[s[2]]);
      }
      count += crossing;
    }
  return count;
}

// A strip standing on its end folds onto itself without passing through, near the origin and
// `depth` metres along z.
class ClothFoldingOnItself : public testing::TestWithParam<double> {};

TEST_P(ClothFoldingOnItself, DoesNotPassThroughItself) {
  const double depth = GetParam();
  // 40 to 60 s each under the sanitizers: there cli_run_whole_self_collision folds the shipped strip.
  if (shortTests()) GTEST_SKIP() << "long under the sanitizers; the Release suite runs it";
  World world;
  ASSERT_TRUE(world.addRigidBody(staticBody("ground", RigidShape::plane({0, 1, 0}, 0.0), Vec3::Zero())).ok());
  // A strip standing on its end, tilted a little: it collapses and folds over itself.
  DeformableDesc strip;
  strip.name = "strip";
  strip.mesh = *makeClothGrid({-0.15, 0.01, depth}, {0.3, 0, 0}, {0.25, 1.5, 0.02}, 7, 31, 0.1);
  strip.inextensibility.enabled = true;
  strip.bending.enabled = true;
  strip.bending.maxForce = 0.01;
  strip.collision.selfCollision = true;
  strip.collision.thickness = 0.01;
  const DeformableId id = *world.addDeformable(strip);
  for (int step = 0; step < 180; ++step) {
    const Status status = world.step(kStep);
    ASSERT_TRUE(status.ok()) << status.message();
  }
  std::vector<Vec3> x;  // back at the origin: the crossing test's tolerances are absolute
  for (const Vec3& p : world.nodePositions(id)) x.push_back(p - Vec3(0, 0, depth));
  // It did fold: its top end came down near the ground.
  double highest = 0.0;
  for (const Vec3& p : x) highest = std::max(highest, p.y());
  EXPECT_LT(highest, 0.3);
  EXPECT_EQ(countIntersections(x, world.restMesh(id).triangles), 0);
  int self = 0;
  for (const ContactReport& contact : world.contacts()) self += contact.other && *contact.other == id;
  EXPECT_GT(self, 0);  // it does lie on itself
  std::printf("at z = %g m: highest node %.3f m, %d self contacts\n", depth, highest, self);
}

// The shipped strip dropped edge-first so that it folds onto itself (scenes/self_collision.json,
// h = 10 ms, K = 8) lies folded in its last second with its edges within their limit and no
// impact zone. A direct block's position projection does not see contacts among deformables, and
// its step pulled the fold's nodes through the faces they lay on in every step: the impact zones
// then moved up to 43 of its 119 nodes rigidly in each step of the last second, an edge ended
// 21 % long, and 239 steps of 300 reported a torn edge. Such a sheet is left to the
// strain-limiting passes now (solver/direct_block.cpp).
TEST(ClothFoldingOnItself, ShippedStripLiesFoldedWithItsEdgesAndNoImpactZones) {
  if (shortTests()) GTEST_SKIP() << "long under the sanitizers; the Release suite runs it";  // 1.2 s in Release
  gauntlet::Outcome result;
  gauntlet::Run run("self_collision.json", {}, result);
  ASSERT_TRUE(run.ok()) << result.error;
  const World& world = run.world;
  const DeformableId strip = run.deformable("strip");
  int violated = 0, zoneNodes = 0;
  double t = 0.0, worst = 0.0;
  ASSERT_TRUE(run.run(0, [&] {
    t += run.h();
    violated += !world.lastReport().violations.empty();
    if (t <= run.scene.duration - 1.0) return;
    zoneNodes = std::max(zoneNodes, world.lastReport().impactZoneNodes);
    worst = std::max(worst, run.worstStretch(strip));
  })) << result.error;
  EXPECT_EQ(violated, 0) << "steps that reported a violated row";
  EXPECT_EQ(zoneNodes, 0) << "nodes moved rigidly by impact zones in the last second";
  EXPECT_LT(worst, 0.02) << "worst edge stretch in the last second";  // measured 1.05 %
  int self = 0;
  for (const ContactReport& contact : world.contacts()) self += contact.other && *contact.other == strip;
  EXPECT_GT(self, 0);  // it does lie on itself
}

// A flag anchored by one face to a capsule (scenes/anchors.json): the anchor holds a point on the
// capsule's surface, so the hem's nodes beside the face lie within the flag's thickness of it.
// Their contacts with the capsule pushed them out against the anchor's hold on the face, and
// below the scene's K = 4 the hem edge beside the face stretched 15 → 38 % from 4.76 s, with 4–10
// violations reported. Nodes one edge from an anchored node do not collide with its body now.
TEST(AnchoredCloth, FaceAnchoredToACapsuleKeepsItsHemAtAnyIterationCount) {
  if (shortTests()) GTEST_SKIP() << "long under the sanitizers; the Release suite runs it";
  for (const gauntlet::Override& settings : {gauntlet::Override{1, 0}, gauntlet::Override{2, 0}, gauntlet::Override{2, 4}}) {
    gauntlet::Outcome result;
    gauntlet::Run run("anchors.json", settings, result);
    ASSERT_TRUE(run.ok()) << result.error;
    const DeformableId flag = run.deformable("flag");
    int violated = 0;
    double worst = 0.0;
    ASSERT_TRUE(run.run(0, [&] {
      violated += !run.world.lastReport().violations.empty();
      worst = std::max(worst, run.worstStretch(flag));
    })) << result.error;
    std::printf("K = %d, n = %d: worst flag edge %.4f, %d steps with violations\n", settings.iterations,
                settings.substeps, worst, violated);
    EXPECT_EQ(violated, 0) << "K = " << settings.iterations << ", n = " << settings.substeps;
    EXPECT_LT(worst, 0.05) << "K = " << settings.iterations << ", n = " << settings.substeps;
  }
}

// At z = 2^28 m (2.7e8, past Limits::maxCoordinate) a 1 cm cell index is 2.7e10, past int32: it
// was converted to int (undefined behaviour; on x86 every z went to one cell). The fold is the
// same there as at the origin. (At 2^31 m the hash is still exact, see below; positions resolve
// 0.48 µm there, coarser than the continuous test's 50 nm touch tolerance, which the continuous
// tests meet by working relative to a local origin: ContinuousFarFromTheOrigin.)
INSTANTIATE_TEST_SUITE_P(Depths, ClothFoldingOnItself, testing::Values(0.0, 268435456.0),
                         [](const testing::TestParamInfo<double>& param) {
                           return "AtZ" + std::to_string(static_cast<long long>(param.param)) + "Metres";
                         });

// The spatial hash's cells: 64-bit, exact far from the origin, clamped past 2^52 cells, a cell of
// their own for non-finite coordinates; boxes and lookups of absurd size are bounded.
TEST(SpatialHash, CellsStayExactFarFromTheOriginAndNonFiniteValuesHaveTheirOwnCell) {
  geometry::SpatialHash grid;
  grid.cell = 0.01;
  const double far = 2147483648.0;  // 2^31 m
  const geometry::SpatialHash::Cell a = grid.cellOf({0, 0, far}), b = grid.cellOf({0, 0, far + 0.01});
  EXPECT_EQ(a.z(), 214748364800);
  EXPECT_EQ(b.z() - a.z(), 1);
  EXPECT_EQ(grid.cellOf({0, 0, -far}).z(), -214748364800);
  EXPECT_EQ(grid.cellOf({1e300, -1e300, 0}).x(), static_cast<int64_t>(geometry::SpatialHash::kCellLimit));
  EXPECT_EQ(grid.cellOf({1e300, -1e300, 0}).y(), -static_cast<int64_t>(geometry::SpatialHash::kCellLimit));
  EXPECT_EQ(grid.cellOf({NAN, INFINITY, 0}).x(), geometry::SpatialHash::kNonFiniteCell);
  EXPECT_EQ(grid.cellOf({NAN, INFINITY, 0}).y(), static_cast<int64_t>(geometry::SpatialHash::kCellLimit));

  // Items far out are found where they are and not one cell over.
  grid.insert({0, 0, far}, {0.005, 0.005, far + 0.005}, 7);
  grid.insert({0, 0, far + 0.05}, {0.005, 0.005, far + 0.055}, 8);
  // A box of 10^600 cells (a cloth side of 1e308 m), one with a NaN corner: kept everywhere.
  grid.insert({-1e300, -1e300, -1e300}, {1e300, 1e300, 1e300}, 9);
  grid.insert({NAN, 0, 0}, {1, 1, 1}, 10);
  grid.sort();
  std::vector<int32_t> found;
  grid.visit({0.001, 0.001, far + 0.001}, 0.0, [&](int32_t item) { found.push_back(item); });
  std::sort(found.begin(), found.end());
  EXPECT_EQ(found, (std::vector<int32_t>{7, 9, 10}));
  // A lookup over more cells than the hash holds visits every entry once instead.
  found.clear();
  grid.visit({0, 0, 0}, 1e300, [&](int32_t item) { found.push_back(item); });
  std::sort(found.begin(), found.end());
  EXPECT_EQ(found, (std::vector<int32_t>{7, 8, 9, 10}));
}

// A lookup's reach grows with speed × time step: a rope node falling at 50 m/s over a static
// triangle mesh in 1 s steps looks 100 m around it, 460 cells of the mesh's 0.22 m on a side,
// 10^8 cells. The hash walked every one of them (12 s per lookup, 7 s per step of such a scene:
// a fuzz finding); a lookup covering more cells than the hash has entries now visits the entries,
// each once, so its cost is bounded by the hash's size whatever the reach.
TEST(SpatialHash, AWideLookupVisitsTheEntriesOnceInsteadOfEveryCell) {
  // A dish-sized floor: 10 x 10 squares of 0.1 m, 200 triangles, 0.14 m cells.
  std::vector<Vec3> vertices;
  std::vector<std::array<int32_t, 3>> triangles;
  for (int i = 0; i <= 10; ++i)
    for (int k = 0; k <= 10; ++k) vertices.emplace_back(-0.5 + 0.1 * i, 0.0, -0.5 + 0.1 * k);
  for (int i = 0; i < 10; ++i)
    for (int k = 0; k < 10; ++k) {
      const int32_t corner = i * 11 + k;
      triangles.push_back({corner, corner + 1, corner + 12});
      triangles.push_back({corner, corner + 12, corner + 11});
    }
  geometry::TriangleGrid grid;
  grid.build(vertices, triangles);
  ASSERT_NEAR(grid.cell, std::sqrt(0.02), 1e-12);
  const size_t entries = grid.entries.size();
  for (double reach : {10.0, 100.0, 1e4, 1e300}) {
    std::vector<int> visits(triangles.size(), 0);
    int total = 0;
    for (int query = 0; query < 100; ++query)
      grid.visit(Vec3(0.1, 0.3 + query, 0.0), reach, [&](int32_t item) {
        ++visits[item];
        ++total;
      });
    // Every entry once per query: no cell walked twice through a colliding hash, none skipped.
    EXPECT_EQ(total, static_cast<int>(100 * entries)) << "reach " << reach;
    for (size_t t = 0; t < triangles.size(); ++t) ASSERT_GE(visits[t], 100) << "triangle " << t << ", reach " << reach;
  }
}

// A point's distance to a triangle mesh, found through the grid with each triangle's plane as a
// lower bound that skips triangles, is the nearest of every triangle's (brute force): on a bowl
// whose faces tilt every way, at random points in and around it.
TEST(SpatialHash, MeshDistanceThroughTheGridIsTheNearestTriangle) {
  geometry::CollisionShape collision;
  RigidShape& bowl = collision.shape;
  bowl.type = ShapeType::TriangleMesh;
  const int rings = 6, sectors = 12;
  bowl.points.emplace_back(0.0, 0.0, 0.0);
  for (int r = 1; r <= rings; ++r)
    for (int k = 0; k < sectors; ++k) {
      const double radius = 0.08 * r, angle = 2 * std::numbers::pi * k / sectors;
      bowl.points.emplace_back(radius * std::cos(angle), 0.3 * radius * radius, radius * std::sin(angle));
    }
  auto point = [&](int r, int k) { return r == 0 ? 0 : 1 + (r - 1) * sectors + (k % sectors); };
  for (int r = 0; r < rings; ++r)
    for (int k = 0; k < sectors; ++k) {
      if (r > 0) bowl.triangles.push_back({point(r, k), point(r + 1, k), point(r, k + 1)});
      bowl.triangles.push_back({point(r, k + 1), point(r + 1, k), point(r + 1, k + 1)});
    }
  collision.grid.build(bowl.points, bowl.triangles);
  uint64_t state = 12345;
  auto uniform = [&](double low, double high) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return low + (high - low) * static_cast<double>(state >> 11) / static_cast<double>(uint64_t{1} << 53);
  };
  const double reach = 0.05;
  int near = 0;
  for (int query = 0; query < 2000; ++query) {
    const Vec3 q(uniform(-0.55, 0.55), uniform(-0.05, 0.15), uniform(-0.55, 0.55));
    double nearest = INFINITY;
    for (const auto& t : bowl.triangles) {
      const Vec3 &a = bowl.points[t[0]], &b = bowl.points[t[1]], &c = bowl.points[t[2]];
      const auto w = geometry::closestOnTriangle(q, a, b, c);
      nearest = std::min(nearest, (q - (w[0] * a + w[1] * b + w[2] * c)).norm());
    }
    if (nearest >= reach) continue;  // beyond the lookup's reach the answer may be any triangle's or none
    ++near;
    const geometry::ShapeDistance found = geometry::distanceToShape(collision, q, reach);
    ASSERT_NEAR(found.distance, nearest, 1e-12) << "query " << query;
    ASSERT_NEAR((q - found.surfacePoint).norm(), nearest, 1e-12) << "query " << query;
  }
  EXPECT_GT(near, 300);  // enough of them near the bowl to mean something
}

TEST(Contact, ClothsMeetingHeadOnFastDoNotPassAndKeepMomentum) {
  // Two sheets 2 cm apart closing at 40 m/s (0.67 m a step) with one iteration: the rows
  // cannot stop them in time, the impact zones must.
  World world;
  WorldSettings settings = world.settings();
  settings.gravity.setZero();
  settings.solver.iterations = 1;
  ASSERT_TRUE(world.setSettings(settings).ok());
  DeformableDesc lower = clothDesc("lower", {-0.3, 0.0, -0.3}, 0.6, 9, 0.2);
  DeformableDesc upper = clothDesc("upper", {-0.25, 0.02, -0.35}, 0.6, 9, 0.4);
  lower.collision.thickness = upper.collision.thickness = 0.002;
  const DeformableId below = *world.addDeformable(lower), above = *world.addDeformable(upper);
  for (int node = 0; node < 81; ++node) {
    ASSERT_TRUE(world.setNodeVelocity(below, node, {0, 20.0, 1.0}));
    ASSERT_TRUE(world.setNodeVelocity(above, node, {0.5, -20.0, 0}));
  }
  const Vec3 before = world.totalLinearMomentum();
  int zones = 0;
  for (int step = 0; step < 10; ++step) {
    ASSERT_TRUE(world.step(kStep).ok());
    zones += world.lastReport().impactZones;
  }
  std::printf("impact zones over the 10 steps: %d\n", zones);
  EXPECT_LT((world.totalLinearMomentum() - before).norm(), 1e-9 * before.norm() + 1e-12);
  // No face of one crosses a face of the other.
  const auto x = world.nodePositions(below), y = world.nodePositions(above);
  const auto& triangles = world.restMesh(below).triangles;
  int crossings = 0;
  for (const auto& s : triangles)
    for (const auto& t : triangles)
      for (int e = 0; e < 3; ++e) {
        crossings += edgeCrossesTriangle(x[s[e]], x[s[(e + 1) % 3]], y[t[0]], y[t[1]], y[t[2]]);
        crossings += edgeCrossesTriangle(y[t[e]], y[t[(e + 1) % 3]], x[s[0]], x[s[1]], x[s[2]]);
      }
  EXPECT_EQ(crossings, 0);
}

TEST(Contact, JellyDroppedOnJellyRestsOnItWithoutPassingIn) {
  // A 1 kg FEM jelly dropped 10 cm onto an 8 kg one on the floor (E = 50 kPa both).
  World world;
  ASSERT_TRUE(world.addRigidBody(staticBody("floor", RigidShape::plane({0, 1, 0}, 0.0), Vec3::Zero())).ok());
  auto jelly = [](std::string name, const Vec3& low, const Vec3& high, int cells, double mass) {
    DeformableDesc desc;
    desc.name = std::move(name);
    desc.mesh = *makeTetBox(low, high, cells, cells / 2, cells, mass);
    desc.paradigm.type = ParadigmType::CorotationalFem;
    desc.collision.thickness = 0.003;
    return desc;
  };
  const DeformableId lower = *world.addDeformable(jelly("lower", {-0.1, 0.0, -0.1}, {0.1, 0.1, 0.1}, 4, 8.0));
  const DeformableId upper = *world.addDeformable(jelly("upper", {-0.05, 0.2, -0.05}, {0.05, 0.3, 0.05}, 2, 1.0));
  for (int step = 0; step < 150; ++step) ASSERT_TRUE(world.step(0.02).ok()) << "step " << step;
  const auto x = world.nodePositions(lower), y = world.nodePositions(upper);
  // No face of one crosses a face of the other, and no node of the upper is inside a
  // tetrahedron of the lower.
  int crossings = 0;
  for (const auto& s : world.restMesh(lower).triangles)
    for (const auto& t : world.restMesh(upper).triangles)
      for (int e = 0; e < 3; ++e) {
        crossings += edgeCrossesTriangle(x[s[e]], x[s[(e + 1) % 3]], y[t[0]], y[t[1]], y[t[2]]);
        crossings += edgeCrossesTriangle(y[t[e]], y[t[(e + 1) % 3]], x[s[0]], x[s[1]], x[s[2]]);
      }
  EXPECT_EQ(crossings, 0);
  int inside = 0;
  for (const Vec3& p : y)
    for (const auto& tet : world.restMesh(lower).tetrahedra) {
      const Vec3 &a = x[tet[0]], &b = x[tet[1]], &c = x[tet[2]], &d = x[tet[3]];
      const double volume = (b - a).cross(c - a).dot(d - a);
      const double w0 = (b - p).cross(c - p).dot(d - p) / volume, w1 = (p - a).cross(c - a).dot(d - a) / volume,
                   w2 = (b - a).cross(p - a).dot(d - a) / volume, w3 = (b - a).cross(c - a).dot(p - a) / volume;
      inside += std::min({w0, w1, w2, w3}) > 1e-6;
    }
  EXPECT_EQ(inside, 0);
  // It rests on the lower jelly: its bottom within the contact thickness of the lower's top
  // under it (each 3 mm), both still.
  double upperBottom = INFINITY, lowerTopUnder = -INFINITY;
  for (const Vec3& p : y) upperBottom = std::min(upperBottom, p.y());
  for (const Vec3& p : x)
    if (std::abs(p.x()) < 0.05 && std::abs(p.z()) < 0.05) lowerTopUnder = std::max(lowerTopUnder, p.y());
  std::printf("upper jelly's bottom %.4f m, the lower's top under it %.4f m\n", upperBottom, lowerTopUnder);
  EXPECT_GT(upperBottom, lowerTopUnder - 0.001);
  EXPECT_LT(upperBottom, lowerTopUnder + 0.006 + 0.002);
  double fastest = 0.0;
  for (const Vec3& v : world.nodeVelocities(lower)) fastest = std::max(fastest, v.norm());
  for (const Vec3& v : world.nodeVelocities(upper)) fastest = std::max(fastest, v.norm());
  EXPECT_LT(fastest, 0.01);
}

// ---- Momentum at a rigid-deformable contact -----------------------------------------------

TEST(Contact, ImpulsesAtARigidContactAreEqualAndOpposite) {
  World world;
  WorldSettings settings = world.settings();
  settings.gravity.setZero();
  ASSERT_TRUE(world.setSettings(settings).ok());
  RigidBodyDesc crate;
  crate.name = "box";
  crate.shape = RigidShape::box({0.2, 0.2, 0.2});
  crate.mass = 2.0;
  crate.position = {0, 0, 0};
  const RigidBodyId box = *world.addRigidBody(crate);
  const DeformableId cloth = *world.addDeformable(clothDesc("cloth", {-0.3, 0.35, -0.3}, 0.6, 11, 0.3));
  for (int node = 0; node < 121; ++node) ASSERT_TRUE(world.setNodeVelocity(cloth, node, {0.2, -2.0, 0.1}));
  const Vec3 before = world.totalLinearMomentum();
  bool touched = false;
  for (int step = 0; step < 60; ++step) {
    ASSERT_TRUE(world.step(kStep).ok());
    touched |= !world.contacts().empty();
  }
  ASSERT_TRUE(touched);
  EXPECT_GT(world.rigidLinearVelocity(box).norm(), 0.1);  // the cloth pushed the box
  EXPECT_LT((world.totalLinearMomentum() - before).norm(), 1e-4 * before.norm());
}

}  // namespace
}  // namespace tandem
