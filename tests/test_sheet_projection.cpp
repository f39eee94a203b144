// A sheet's limited edges projected together (projectSheetEdgesTogether,
// src/solver/strain_limiting.h): one Newton step of their lengths solved by the swept edges'
// two-level conjugate gradients. Converged, it brings a stretched sheet back within a small part
// of its excess; a few iterations of it among the strain-limiting passes take out what the
// passes alone leave on a wide sheet; it moves a node resting on a still shape only in that
// shape's tangent plane.
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

}  // namespace
}  // namespace tandem
