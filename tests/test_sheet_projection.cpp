// A sheet's limited edges projected together (projectSheetEdgesTogether,
// src/solver/strain_limiting.h): one Newton step of their lengths solved by the swept edges'
// two-level conjugate gradients. Converged, it brings a stretched sheet back within a small part
// of its excess; a few iterations of it among the strain-limiting passes take out what the
// passes alone leave on a wide sheet; it moves a node resting on a still shape only in that
// shape's tangent plane; it opens a moving ball's contacts with the sheet, moving the ball too,
// with momentum kept.
#include "solver/strain_limiting.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace tandem {
namespace {

// A side × side sheet of 1 cm squares, each cut by a diagonal as a cloth's triangles are, bent a
// little across, stretched 5 % along x and 3 % along z (every edge past the 1 % limit), with
// masses varying across it. (Without the diagonals the grid shears freely to first order, and a
// Newton step of its lengths alone moves it along those shears far enough to overshoot.)
struct StretchedSheet {
  int side;
  std::vector<Vec3> position;
  std::vector<double> weight;
  std::vector<LimitedEdge> edges;

  explicit StretchedSheet(int n) : side(n) {
    for (int r = 0; r < side; ++r)
      for (int c = 0; c < side; ++c) {
        position.emplace_back(0.0105 * c, 0.02 * std::sin(0.1 * c), 0.0103 * r);
        weight.push_back(1.0 / (1e-4 * (1.0 + 0.5 * ((r * 7 + c * 3) % 5))));
      }
    auto add = [&](int32_t a, int32_t b, double restLength) {
      InextensibilityRow row;
      row.node = {a, b};
      row.restLength = restLength;
      row.lambdaMin = -INFINITY;
      row.lambdaMax = INFINITY;
      LimitedEdge edge;
      ASSERT_TRUE(makeLimitedEdge(row, weight, edge));
      edge.inSheet = true;
      edges.push_back(edge);
    };
    for (int r = 0; r < side; ++r)
      for (int c = 0; c < side; ++c) {
        const int32_t i = r * side + c;
        if (c + 1 < side) add(i, i + 1, 0.01);
        if (r + 1 < side) add(i, i + side, 0.01);
        if (c + 1 < side && r + 1 < side) add(i, i + side + 1, 0.01 * std::sqrt(2.0));
      }
  }

  double worstExcess() const {
    double worst = 0.0;
    for (const LimitedEdge& edge : edges) {
      const double length = (position[edge.node[1]] - position[edge.node[0]]).norm();
      worst = std::max(worst, (length - edge.longest) / edge.restLength);
    }
    return worst;
  }
};

// What the passes leave once they stop (after kStrainPasses when no edge is corrected by
// kStrainStillTooFar any more), with the sheet projected together among them and without.
double leftAfterThePasses(StretchedSheet sheet, bool together) {
  for (LimitedEdge& edge : sheet.edges) edge.inSheet = together;
  std::vector<Vec3> pushed(sheet.position.size(), Vec3::Zero()), reaction = pushed, heldAlong;
  SweptEdgeSolveScratch scratch;
  limitStrain(sheet.edges, {}, {}, sheet.weight, sheet.position, pushed, reaction, scratch, heldAlong);
  return sheet.worstExcess();
}

TEST(SheetProjection, TakesTheStretchOutOfAWideSheetThatPassesAloneLeave) {
  const StretchedSheet sheet(41);
  const double before = sheet.worstExcess();  // 5 % past the limit
  const double together = leftAfterThePasses(sheet, true), alone = leftAfterThePasses(sheet, false);
  // Measured: 1.4 % of the excess left with it, 34 % without.
  EXPECT_LT(together, 0.05 * before) << together << " of " << before;
  EXPECT_GT(alone, 0.2 * before) << alone << " of " << before;
}

// One projection alone, converged: a Newton step of the lengths, exact for a uniform stretch but
// for the bend.
TEST(SheetProjection, OneConvergedStepTakesMostOfTheStretchOut) {
  StretchedSheet sheet(21);
  const double before = sheet.worstExcess();
  std::vector<Vec3> reaction(sheet.position.size(), Vec3::Zero()), heldAlong = reaction;
  SweptEdgeSolveScratch scratch;
  bool coarseBuilt = false;
  projectSheetEdgesTogether(sheet.edges, sheet.weight, heldAlong, sheet.position, reaction, scratch, coarseBuilt, 400, 1e-6);
  EXPECT_LT(sheet.worstExcess(), 0.02 * before) << sheet.worstExcess() << " of " << before;  // 0.3 % of it left
}

TEST(SheetProjection, MovesANodeOnAStillShapeOnlyInItsTangentPlane) {
  StretchedSheet sheet(21);
  std::vector<Vec3> reaction(sheet.position.size(), Vec3::Zero());
  std::vector<Vec3> heldAlong(sheet.position.size(), Vec3::Zero());
  const auto middle = static_cast<size_t>(10 * sheet.side + 10);
  sheet.position[middle].y() = -0.003;  // a dent: its edges pull it up, out of the plane
  const Vec3 normal = Vec3(1, -1, 0).normalized();  // a shape under it, tilted
  heldAlong[middle] = normal;
  const Vec3 start = sheet.position[middle];
  SweptEdgeSolveScratch scratch;
  bool coarseBuilt = false;
  projectSheetEdgesTogether(sheet.edges, sheet.weight, heldAlong, sheet.position, reaction, scratch, coarseBuilt);
  const Vec3 moved = sheet.position[middle] - start;
  EXPECT_GT(moved.norm(), 1e-5);
  EXPECT_LT(std::abs(moved.dot(normal)), 1e-12);
}

// A ball (0.05 kg) that went through a flat sheet of 0.1 g nodes in one step: found 1 cm above the
// middle node with the normal pointing down from the ball to the sheet, it ends 1 cm below it.
// Its contact row, as a gap linear in the positions along that normal, keeps the side it was
// found on; the projection opens it, moving the node and the ball (one more node after the
// sheet's), and moves nothing else of the sheet's momentum: Σ m Δx = 0 over the nodes and the
// ball.
struct BallThroughSheet {
  StretchedSheet sheet{11};
  int32_t middle = 5 * 11 + 5, ball = 11 * 11;
  double ballMass = 0.05, radius = 0.02, slop = 1e-3;
  std::vector<SheetContact> contacts;

  BallThroughSheet() {
    for (size_t i = 0; i < sheet.position.size(); ++i) {  // flat, at rest length, 0.1 g a node
      const int32_t r = static_cast<int32_t>(i) / sheet.side, c = static_cast<int32_t>(i) % sheet.side;
      sheet.position[i] = Vec3(0.01 * c, 0.0, 0.01 * r);
      sheet.weight[i] = 1e4;
    }
    for (LimitedEdge& edge : sheet.edges) edge.share[0] = edge.share[1] = 0.5;
    const Vec3 middleAtStart = sheet.position[middle], ballAtStart = middleAtStart + Vec3(0, 0.03, 0);
    sheet.position.push_back(middleAtStart - Vec3(0, 0.01, 0));  // where the step left the ball
    sheet.weight.push_back(1.0 / ballMass);
    const Vec3 down(0, -1, 0);
    const double startGap = 0.03 - radius;
    contacts.push_back({{middle, middle, middle}, {1.0, 0.0, 0.0}, ball, down, startGap - down.dot(middleAtStart - ballAtStart)});
  }
  double gap() const { return contacts[0].gap(sheet.position); }
};

TEST(SheetProjection, OpensAContactThatWentThroughAndMovesTheBallWithMomentumKept) {
  BallThroughSheet scene;
  ASSERT_NEAR(scene.gap(), -0.03, 1e-12);  // 2 cm of radius and 1 cm below: 3 cm through
  const std::vector<Vec3> start = scene.sheet.position;
  std::vector<Vec3> reaction(start.size(), Vec3::Zero()), heldAlong = reaction;
  SweptEdgeSolveScratch scratch;
  bool coarseBuilt = false;
  projectSheetEdgesTogether(scene.sheet.edges, scene.sheet.weight, heldAlong, scene.sheet.position, reaction, scratch,
                            coarseBuilt, 400, 1e-10, scene.contacts, scene.slop);
  EXPECT_NEAR(scene.gap(), -scene.slop, 1e-9);  // opened to the slop the contact rows leave
  Vec3 momentum = Vec3::Zero();
  for (size_t i = 0; i < start.size(); ++i) momentum += (scene.sheet.position[i] - start[i]) / scene.sheet.weight[i];
  EXPECT_LT(momentum.norm(), 1e-12);
  EXPECT_GT(scene.sheet.position[scene.ball].y() - start[scene.ball].y(), 0.0);  // the ball went back up
}

// Pinned along its border, the sheet can give only as far as its edges' 1 % allows (7 mm at the
// middle): the passes with the projection among them put a ball pressed 5 mm into the middle node
// back on top of the dent it makes, the node taking the dent and the ball hardly moving. (Pressed
// 1 cm in, past what the dent allows, they leave the edges 2.3 % past their limit and the ball
// 1.4 mm in; from 3 cm through, 1.8 cm: the flat sheet's edges, linearised, let the node go down
// for nothing, and the passes pull it back up through the ball in turn; docs/solver.md,
// twenty-second session.)
TEST(SheetProjection, PutsABallPressedIntoAPinnedSheetBackOnTop) {
  BallThroughSheet scene;
  scene.sheet.position[scene.ball].y() = 0.015;
  const int side = scene.sheet.side;
  for (int i = 0; i < side; ++i)
    for (int node : {i, side * (side - 1) + i, side * i, side * i + side - 1}) scene.sheet.weight[node] = 0.0;
  for (LimitedEdge& edge : scene.sheet.edges) {
    const double wi = scene.sheet.weight[edge.node[0]], wj = scene.sheet.weight[edge.node[1]];
    edge.share[0] = wi + wj > 0 ? wi / (wi + wj) : 0.0;
    edge.share[1] = wi + wj > 0 ? wj / (wi + wj) : 0.0;
  }
  std::vector<Vec3> pushed(scene.sheet.position.size(), Vec3::Zero()), reaction = pushed, heldAlong;
  SweptEdgeSolveScratch scratch;
  const double ballBefore = scene.sheet.position[scene.ball].y();
  limitStrain(scene.sheet.edges, {}, {}, scene.sheet.weight, scene.sheet.position, pushed, reaction, scratch, heldAlong,
              scene.contacts, scene.slop);
  EXPECT_GT(scene.gap(), -2 * scene.slop);  // on top of the middle node again (measured: the slop)
  EXPECT_GE(scene.sheet.position[scene.ball].y(), ballBefore);
  EXPECT_LT(scene.sheet.position[scene.middle].y(), -0.003);  // the dent: 4 mm
  EXPECT_LT(scene.sheet.worstExcess(), 0.001);  // the edges at their limit
}

}  // namespace
}  // namespace tandem
