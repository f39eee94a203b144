// Conservation and integration: internal rows keep momentum; free fall is symplectic Euler.
#include <tandem/world.h>

#include <gtest/gtest.h>

#include <random>

namespace tandem {
namespace {

constexpr double kStep = 1.0 / 60.0;

class FreeCloth : public ::testing::TestWithParam<RowSolverKind> {};

TEST_P(FreeCloth, InternalRowsKeepLinearMomentum) {
  World world;
  WorldSettings settings = world.settings();
  settings.gravity.setZero();
  ASSERT_TRUE(world.setSettings(settings).ok());
  DeformableDesc desc;
  desc.name = "cloth";
  desc.mesh = *makeClothGrid({0, 0, 0}, {1, 0, 0}, {0, 0, 1}, 9, 9, 0.4);
  desc.inextensibility.enabled = true;
  desc.bending.enabled = true;
  desc.bending.maxForce = 2.0;
  desc.rowSolver = GetParam();
  const DeformableId cloth = *world.addDeformable(desc);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int node = 0; node < 81; ++node)
    ASSERT_TRUE(world.setNodeVelocity(cloth, node, {0.5 + u(rng), u(rng), u(rng)}));
  const Vec3 initial = world.totalLinearMomentum();
  for (int step = 0; step < 120; ++step) ASSERT_TRUE(world.step(kStep).ok());
  // The rows did work: the velocity field changed.
  EXPECT_GT(world.lastReport().rmsDeltaLambda[0], 0.0);
  EXPECT_LT((world.totalLinearMomentum() - initial).norm(), 1e-6 * initial.norm());
}

INSTANTIATE_TEST_SUITE_P(BothRowSolvers, FreeCloth,
                         ::testing::Values(RowSolverKind::Iterative, RowSolverKind::Direct));

TEST(FreeFall, DropsExactlyWhatSymplecticEulerPredicts) {
  World world;
  DeformableDesc desc;
  desc.name = "cloth";
  desc.mesh = *makeClothGrid({0, 10, 0}, {1, 0, 0}, {0, 0, 1}, 5, 5, 0.2);
  desc.inextensibility.enabled = true;  // rows present but idle: uniform motion does not strain
  const DeformableId cloth = *world.addDeformable(desc);
  const RigidBodyId box = *world.addRigidBody([] {
    RigidBodyDesc b;
    b.name = "box";
    b.shape = RigidShape::box({0.1, 0.1, 0.1});
    b.position = {3, 10, 0};
    return b;
  }());
  const int n = 90;
  for (int step = 0; step < n; ++step) ASSERT_TRUE(world.step(kStep).ok());
  const double predicted = 9.81 * kStep * kStep * n * (n + 1) / 2.0;  // Σₖ g h² k
  for (const Vec3& x : world.nodePositions(cloth)) EXPECT_NEAR(10.0 - x.y(), predicted, 1e-6 * predicted);
  EXPECT_NEAR(10.0 - world.rigidPosition(box).y(), predicted, 1e-6 * predicted);
  // And to first order in h that is g t² / 2.
  const double t = n * kStep;
  EXPECT_NEAR(predicted, 9.81 * t * t / 2.0, 9.81 * t * kStep);
}

}  // namespace
}  // namespace tandem
