// Dynamic bodies resting on elastic bodies, carried by the elastic models' implicit solve with the
// body moving in it (models/supports.h): momentum kept exactly, and the load shared with the
// body's other supports as statics says.
#include <tandem/world.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace tandem {
namespace {

constexpr double kStep = 1.0 / 50.0;  // the paper's

DeformableDesc femJelly(const Vec3& baseCentre, double mass) {
  DeformableDesc jelly;
  jelly.name = "jelly";
  jelly.mesh = *makeTetCylinder(baseCentre, 0.1, 0.2, 2, 8, 3, mass);
  jelly.paradigm.type = ParadigmType::CorotationalFem;
  jelly.paradigm.youngsModulus = 50e3;
  jelly.paradigm.poissonRatio = 0.0;
  return jelly;
}

// Without gravity, a 2 kg plate pushed at 0.5 m/s onto a free 0.5 kg jelly: the holds' impulses
// on the jelly's nodes and their reactions on the plate are equal and opposite, so the momentum
// of the whole stays the plate's first momentum, every step, while the jelly takes at least its
// share of a plastic impact, m / (m + M) = 20 % (pushed whole, not only its top layer). Kept to 10⁻⁵ of it: what the models' conjugate
// gradients leave (their tolerance, 10⁻⁴ of the right-hand side: the unsolved residual's sum is
// momentum lost, 3·10⁻⁷ with the scalar Jacobi preconditioner, 3.8·10⁻⁶ with the 3 × 3 blocks
// since the twenty-sixth session) and the first contact's position stages; a reaction given
// wrongly would be off by its whole size.
TEST(MovingSupports, KeepMomentumWhenAPlatePushesAFreeJelly) {
  World world;
  WorldSettings settings = world.settings();
  settings.gravity = Vec3::Zero();
  ASSERT_TRUE(world.setSettings(settings).ok());
  const DeformableId jelly = *world.addDeformable(femJelly({0, 0, 0}, 0.5));
  RigidBodyDesc plate;
  plate.name = "plate";
  plate.shape = RigidShape::box({0.15, 0.02, 0.15});
  plate.mass = 2.0;
  plate.position = Vec3(0, 0.2 + 0.005 + 0.02 + 0.002, 0);
  plate.linearVelocity = Vec3(0, -0.5, 0);
  plate.canSleep = false;
  const RigidBodyId plateId = *world.addRigidBody(plate);
  const Vec3 start = world.totalLinearMomentum();
  double held = 0.0;
  for (int step = 0; step < 50; ++step) {
    ASSERT_TRUE(world.step(kStep).ok()) << "step " << step;
    EXPECT_LT((world.totalLinearMomentum() - start).norm(), 1e-5 * start.norm()) << "step " << step;
    for (const ContactReport& contact : world.contacts())
      if (contact.rigid && *contact.rigid == plateId) held += contact.normalImpulse;
  }
  Vec3 jellyMomentum = Vec3::Zero();
  const auto v = world.nodeVelocities(jelly);
  const auto inverseMass = world.nodeInverseMasses(jelly);
  for (size_t n = 0; n < v.size(); ++n) jellyMomentum += v[n] / inverseMass[n];
  EXPECT_LT(jellyMomentum.y(), 0.2 * start.y());
  EXPECT_NEAR(held, -jellyMomentum.y(), 0.01 * std::abs(start.y()));  // and the contacts report what it got
}

// A 1 kg plank on a jelly at one end and on a thin rigid post at the other, its centre of mass
// midway: at rest each carries half its weight (the jelly's solve moves the plank with what the
// post gave it last step), and that solve converges in a few dozen iterations.
TEST(MovingSupports, APlankOnAJellyAndAPostRestsWithHalfItsWeightOnEach) {
  World world;
  RigidBodyDesc ground;
  ground.name = "ground";
  ground.shape = RigidShape::plane({0, 1, 0}, 0.0);
  ground.motion = MotionType::Static;
  const RigidBodyId groundId = *world.addRigidBody(ground);
  const double jellyMass = 0.5, plankMass = 1.0, top = 0.005 + 0.2 + 0.005;
  const DeformableId jelly = *world.addDeformable(femJelly({-0.3, 0.005, 0}, jellyMass));
  RigidBodyDesc post;
  post.name = "post";
  post.shape = RigidShape::box({0.01, 0.5 * top, 0.1});
  post.motion = MotionType::Static;
  post.position = Vec3(0.3, 0.5 * top, 0);
  ASSERT_TRUE(world.addRigidBody(post).ok());
  RigidBodyDesc plank;
  plank.name = "plank";
  plank.shape = RigidShape::box({0.45, 0.02, 0.15});
  plank.mass = plankMass;
  plank.position = Vec3(0, top + 0.02 + 0.001, 0);
  plank.canSleep = false;
  const RigidBodyId plankId = *world.addRigidBody(plank);
  int slowest = 0;  // conjugate-gradient iterations of the jelly's solve, the most in a step at rest
  for (int step = 0; step < 150; ++step) {  // 3 s
    ASSERT_TRUE(world.step(kStep).ok()) << "step " << step;
    if (step >= 50) {
      EXPECT_TRUE(world.lastReport().modelsConverged) << "step " << step;
      slowest = std::max(slowest, world.lastReport().modelIterations);
    }
  }
  EXPECT_LT(slowest, 40);

  double onPlank = 0.0, onGround = 0.0, speed = 0.0;
  for (const ContactReport& contact : world.contacts()) {
    if (contact.rigid && *contact.rigid == plankId) onPlank += contact.normalImpulse;
    if (contact.rigid && *contact.rigid == groundId && contact.deformable == jelly) onGround += contact.normalImpulse;
  }
  for (const Vec3& v : world.nodeVelocities(jelly)) speed = std::max(speed, v.norm());
  const double weight = 9.81 * kStep;  // N·s per kg over a step
  EXPECT_NEAR(onPlank, 0.5 * plankMass * weight, 0.05 * 0.5 * plankMass * weight);
  EXPECT_NEAR(onGround, (0.5 * plankMass + jellyMass) * weight, 0.05 * (0.5 * plankMass + jellyMass) * weight);
  EXPECT_LT(world.rigidLinearVelocity(plankId).norm(), 1e-3);
  EXPECT_LT(world.rigidAngularVelocity(plankId).norm(), 1e-2);
  EXPECT_LT(speed, 1e-3);
  EXPECT_GT(world.rigidPosition(plankId).y(), top + 0.02 - 0.01);  // on the jelly and the post, not in them
}

}  // namespace
}  // namespace tandem
