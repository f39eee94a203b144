// A rope hanging from a fixed point holding a rigid box: stretch, height, rest; warm starting.
#include <tandem/scenes.h>
#include <tandem/world.h>

#include <gtest/gtest.h>

#include <string>

namespace tandem {
namespace {

constexpr double kStep = 1.0 / 60.0;

double ropeLength(std::span<const Vec3> x) {
  double length = 0.0;
  for (size_t k = 1; k < x.size(); ++k) length += (x[k] - x[k - 1]).norm();
  return length;
}

double maxEdgeStretch(std::span<const Vec3> x, double restLength) {
  double worst = 0.0;
  for (size_t k = 1; k < x.size(); ++k) worst = std::max(worst, (x[k] - x[k - 1]).norm() / restLength - 1.0);
  return worst;
}

TEST(HangingRope, HoldsAOneKilogramBoxWithoutStretching) {
  World world;
  ASSERT_TRUE(findBuiltinScene("hanging_rope")->build(world).ok());
  ASSERT_EQ(world.settings().solver.iterations, 4);
  const DeformableId rope = *world.findDeformable("rope");
  const RigidBodyId box = *world.findRigidBody("box");
  double worstStretch = 0.0;
  for (int step = 0; step < 300; ++step) {  // 5 s
    ASSERT_TRUE(world.step(kStep).ok());
    worstStretch = std::max(worstStretch, maxEdgeStretch(world.nodePositions(rope), 1.0 / 19));
  }
  // Never more than 1 % per edge at any step, and the whole rope within 1 % at the end.
  EXPECT_LT(worstStretch, 0.01);
  EXPECT_NEAR(ropeLength(world.nodePositions(rope)), 1.0, 0.01);
  // Fixed point at y = 2, rope 1 m, anchor on the top face of a box of half height 0.1 m.
  EXPECT_NEAR(world.rigidPosition(box).y(), 2.0 - 1.0 - 0.1, 0.02);
  EXPECT_LT(world.rigidLinearVelocity(box).norm(), 0.01);
  // The fixed point carries the weight of rope and box: (0.2 + 1) kg · g · h per step.
  EXPECT_NEAR(world.fixedPointImpulse(FixedPointId{0}).y(), 1.2 * 9.81 * kStep, 0.02 * 1.2 * 9.81 * kStep);
}

TEST(HangingRope, StaysRigidGradeWithOneIteration) {
  World world;
  WorldSettings settings = world.settings();
  settings.solver.iterations = 1;
  ASSERT_TRUE(world.setSettings(settings).ok());
  ASSERT_TRUE(findBuiltinScene("hanging_rope")->build(world).ok());
  const DeformableId rope = *world.findDeformable("rope");
  for (int step = 0; step < 300; ++step) ASSERT_TRUE(world.step(kStep).ok());
  EXPECT_LT(maxEdgeStretch(world.nodePositions(rope), 1.0 / 19), 0.01);
}

// The projected Gauss-Seidel path: a rope swinging from a fixed point, every row iterative.
// Warm starting begins each row at last step's impulse, so two sweeps leave less to correct.
// (The rows get a force bound far above the rope's tension: bounded rows are left to the sweep
// alone, not limited by position afterwards, which would change the velocities the next step
// starts from.)
double meanRmsAfterSecondIteration(bool warmStart) {
  World world;
  WorldSettings settings = world.settings();
  settings.solver.warmStart = warmStart;
  EXPECT_TRUE(world.setSettings(settings).ok());
  DeformableDesc desc;
  desc.name = "rope";
  desc.mesh = *makeRope({0, 2, 0}, {1, 2, 0}, 20, 0.2);  // starts horizontal: it swings down
  desc.inextensibility.enabled = true;
  desc.inextensibility.maxForce = 1e6;
  desc.rowSolver = RowSolverKind::Iterative;
  const DeformableId rope = *world.addDeformable(desc);
  EXPECT_TRUE(world.addFixedPoint(rope, 0, {0, 2, 0}).ok());
  double sum = 0.0;
  int count = 0;
  for (int step = 0; step < 120; ++step) {
    EXPECT_TRUE(world.step(kStep).ok());
    if (step < 30) continue;
    sum += world.lastReport().rmsDeltaLambda.at(1);
    ++count;
  }
  return sum / count;
}

TEST(HangingRope, WarmStartingLowersTheResidualAfterTwoIterations) {
  const double warm = meanRmsAfterSecondIteration(true);
  const double cold = meanRmsAfterSecondIteration(false);
  EXPECT_LT(warm, 0.5 * cold) << "warm " << warm << " cold " << cold;
}

TEST(HangingRope, ReportsStagesRowsAndConvergence) {
  World world;
  ASSERT_TRUE(findBuiltinScene("hanging_rope")->build(world).ok());
  EXPECT_EQ(world.lastTimeStep(), 0.0);
  ASSERT_TRUE(world.step(kStep).ok());
  EXPECT_EQ(world.lastTimeStep(), kStep);
  EXPECT_FALSE(world.step(-1.0).ok());
  EXPECT_EQ(world.lastTimeStep(), kStep);  // a refused step changes nothing
  const StepReport& report = world.lastReport();
  EXPECT_EQ(report.rows(RowType::FixedPoint), 3);
  EXPECT_EQ(report.rows(RowType::Anchor), 3);
  EXPECT_EQ(report.rows(RowType::Inextensibility), 19);
  EXPECT_EQ(report.rows(RowType::Bending), 0);
  ASSERT_EQ(report.rmsDeltaLambda.size(), 4u);
  // The direct block solves the rope in the first sweep up to its small regularisation, which
  // each later sweep refines away: Δλ falls steadily, by over a thousand in four sweeps.
  EXPECT_GT(report.rmsDeltaLambda[0], 0.1);
  for (int k = 1; k < 4; ++k) EXPECT_LT(report.rmsDeltaLambda[k], 0.2 * report.rmsDeltaLambda[k - 1]);
  EXPECT_LT(report.rmsDeltaLambda[3], 1e-3 * report.rmsDeltaLambda[0]);
  double sum = 0.0;
  for (double seconds : report.stageSeconds) {
    EXPECT_GE(seconds, 0.0);
    sum += seconds;
  }
  EXPECT_NEAR(report.totalSeconds, sum, 1e-12);
  EXPECT_EQ(world.stepCount(), 1);
  EXPECT_NEAR(world.time(), kStep, 1e-15);
}

}  // namespace
}  // namespace tandem

namespace tandem {
namespace {

// A 1 m, 11-node rope pinned at its top, a 10 kg box anchored to its lower end; `edgeForce` and
// `anchorForce` bound its edges and the anchor (N).
struct RopeAndBox {
  DeformableId rope;
  RigidBodyId box;
};
RopeAndBox hangBoxOnRope(World& world, const std::string& ropeName, const std::string& boxName, double edgeForce,
                         double anchorForce, RowSolverKind rowSolver = RowSolverKind::Auto) {
  DeformableDesc rope;
  rope.name = ropeName;
  rope.mesh = *makeRope({0, 2, 0}, {0, 1, 0}, 11, 0.1);
  rope.inextensibility.enabled = true;
  rope.inextensibility.maxForce = edgeForce;
  rope.rowSolver = rowSolver;
  const DeformableId ropeId = *world.addDeformable(rope);
  RigidBodyDesc box;
  box.name = boxName;
  box.shape = RigidShape::box({0.1, 0.1, 0.1});
  box.mass = 10.0;
  box.position = {0, 0.9, 0};
  const RigidBodyId boxId = *world.addRigidBody(box);
  EXPECT_TRUE(world.addFixedPoint(ropeId, 0, {0, 2, 0}).ok());
  AnchorDesc anchor = AnchorDesc::node(ropeId, 10, boxId);
  anchor.maxForce = anchorForce;
  EXPECT_TRUE(world.addAnchor(anchor).ok());
  return {ropeId, boxId};
}

// A rope whose rows are too weak for its load is torn on purpose: the step still succeeds, and
// the report names the violated row (anchor gap or edge stretch) with its deformable and body.
std::vector<RowViolation> violationsOfWeakRope(double edgeForce, double anchorForce) {
  World world;
  hangBoxOnRope(world, "weak rope", "heavy box", edgeForce, anchorForce);
  std::vector<RowViolation> seen;
  for (int step = 0; step < 60; ++step) {
    EXPECT_TRUE(world.step(kStep).ok());
    for (const RowViolation& v : world.lastReport().violations) seen.push_back(v);
  }
  return seen;
}

TEST(HangingRope, ATornRopeIsReportedNamingItsRows) {
  // Edges bounded at 2 N under a 98 N load: they stretch past 10 %.
  const std::vector<RowViolation> edges = violationsOfWeakRope(2.0, kUnbounded);
  ASSERT_FALSE(edges.empty());
  for (const RowViolation& v : edges) {
    EXPECT_EQ(v.kind, RowViolation::Kind::EdgeStretch) << v.message;
    EXPECT_GT(v.value, kEdgeStretchWarning);
    EXPECT_NE(v.message.find("'weak rope'"), std::string::npos) << v.message;
  }
  // An anchor bounded at 20 N lets the box fall away from the rope's end.
  const std::vector<RowViolation> anchors = violationsOfWeakRope(kUnbounded, 20.0);
  ASSERT_FALSE(anchors.empty());
  for (const RowViolation& v : anchors) {
    EXPECT_EQ(v.kind, RowViolation::Kind::AnchorGap) << v.message;
    EXPECT_GT(v.value, kAnchorGapWarning);
    EXPECT_NE(v.message.find("'weak rope'"), std::string::npos) << v.message;
    EXPECT_NE(v.message.find("'heavy box'"), std::string::npos) << v.message;
  }
}

// An anchor's force bound holds for everything the rope puts on the body, the position passes
// included: they hold only unbounded anchors' nodes (whose reaction the body then takes).
TEST(HangingRope, ABoundedAnchorNeverPullsHarderThanItsBound) {
  World world;
  // Swept, so that its edges are limited by position.
  const auto [ropeId, boxId] = hangBoxOnRope(world, "rope", "box", kUnbounded, 20.0, RowSolverKind::Iterative);
  for (int node = 1; node < 11; ++node) ASSERT_TRUE(world.setNodeVelocity(ropeId, node, {3.0, 0, 0}).ok());
  for (int step = 0; step < 60; ++step) {
    ASSERT_TRUE(world.step(kStep).ok());
    EXPECT_LE(world.deformableImpulseOnRigid(boxId).norm(), 20.0 * kStep * (1 + 1e-9)) << "step " << step;
  }
}

// A rope that holds its load reports nothing.
TEST(HangingRope, ARopeThatHoldsReportsNoViolation) {
  World world;
  ASSERT_TRUE(findBuiltinScene("hanging_rope")->build(world).ok());
  for (int step = 0; step < 120; ++step) {
    ASSERT_TRUE(world.step(kStep).ok());
    EXPECT_TRUE(world.lastReport().violations.empty()) << world.lastReport().violations.front().message;
  }
}

}  // namespace
}  // namespace tandem
