// Continuous collision between moving features, and the impact zones that keep surfaces from
// passing through each other over a step.
#include "collision/continuous.h"
#include "collision/impact_zones.h"

#include <gtest/gtest.h>

#include <random>

namespace tandem {
namespace {

using geometry::edgeEdgeImpact;
using geometry::nodeFaceImpact;

const Vec3 kZero = Vec3::Zero();
const Vec3 kA(0, 0, 0), kB(1, 0, 0), kC(0, 1, 0);

TEST(Continuous, NodeThroughAStillFaceAtTheTimeItReachesThePlane) {
  // From z = 0.3 to z = −0.7 through (0.2, 0.2): it meets the face at t = 0.3.
  const auto t = nodeFaceImpact({0.2, 0.2, 0.3}, {0, 0, -1}, kA, kZero, kB, kZero, kC, kZero, 1e-9);
  ASSERT_TRUE(t);
  EXPECT_NEAR(*t, 0.3, 1e-10);
  // Beside the face, stopping short of it, or moving along its plane: no impact.
  EXPECT_FALSE(nodeFaceImpact({0.8, 0.8, 0.3}, {0, 0, -1}, kA, kZero, kB, kZero, kC, kZero, 1e-9));
  EXPECT_FALSE(nodeFaceImpact({0.2, 0.2, 0.3}, {0, 0, -0.2}, kA, kZero, kB, kZero, kC, kZero, 1e-9));
  EXPECT_FALSE(nodeFaceImpact({-0.5, 0.2, 0}, {2, 0, 0}, kA, kZero, kB, kZero, kC, kZero, 1e-9));
}

TEST(Continuous, FaceSweepingOverAStillNodeAndBothMoving) {
  // The face moves up by 1 through a node at height 0.6: t = 0.6; both moving towards each
  // other at 0.5 each from 0.6 apart: t = 0.6.
  const Vec3 up(0, 0, 1);
  auto t = nodeFaceImpact({0.1, 0.1, 0.6}, kZero, kA, up, kB, up, kC, up, 1e-9);
  ASSERT_TRUE(t);
  EXPECT_NEAR(*t, 0.6, 1e-10);
  t = nodeFaceImpact({0.1, 0.1, 0.6}, -0.5 * up, kA, 0.5 * up, kB, 0.5 * up, kC, 0.5 * up, 1e-9);
  ASSERT_TRUE(t);
  EXPECT_NEAR(*t, 0.6, 1e-10);
}

TEST(Continuous, EdgesCrossingAtTheTimeTheyMeet) {
  // Edge along x at z = 0.5 falling by 1 onto an edge along y at z = 0: they meet at t = 0.5.
  const Vec3 down(0, 0, -1);
  const auto t = edgeEdgeImpact({-1, 0, 0.5}, down, {1, 0, 0.5}, down, {0, -1, 0}, kZero, {0, 1, 0}, kZero, 1e-9);
  ASSERT_TRUE(t);
  EXPECT_NEAR(*t, 0.5, 1e-10);
  // Shifted past the second edge's end: the lines cross, the edges do not.
  EXPECT_FALSE(edgeEdgeImpact({-1, 2, 0.5}, down, {1, 2, 0.5}, down, {0, -1, 0}, kZero, {0, 1, 0}, kZero, 1e-9));
}

// Far from the origin a coordinate resolves less: at 2^31 m one unit in the last place is
// 0.48 µm, ten times the touch tolerance the impact zones use for 5 cm features (10^-6 of the
// cell, 50 nm). The tests work relative to one of the features' points, so the distances they
// measure at the coplanar time are as exact there as at the origin: every crossing is found.
class ContinuousFarFromTheOrigin : public testing::TestWithParam<double> {};

TEST_P(ContinuousFarFromTheOrigin, FindsEveryCrossingOfFiveCentimetreFeatures) {
  const Vec3 origin = Vec3::Constant(GetParam());
  constexpr double kSize = 0.05, kTolerance = 1e-6 * kSize;
  std::mt19937 random(13);
  std::uniform_real_distribution<double> unit(0.0, 1.0), move(-0.5 * kSize, 0.5 * kSize);
  auto vector = [&] { return Vec3(move(random), move(random), move(random)); };
  int nodeFaceFound = 0, edgeEdgeFound = 0;
  constexpr int kCases = 200;
  for (int i = 0; i < kCases; ++i) {
    // A face moving a little, and a node that crosses its plane at t0 through a point inside it
    // (or on an edge, one case in four: the shared edge two faces' tests must both see).
    const Vec3 a = vector(), b = a + Vec3(kSize, 0, 0) + 0.2 * vector(), c = a + Vec3(0, kSize, 0) + 0.2 * vector();
    const Vec3 da = 0.1 * vector(), db = da, dc = da;  // a translating face: f is quadratic at most
    double u = unit(random), v = unit(random);
    if (u + v > 1) u = 1 - u, v = 1 - v;
    if (i % 4 == 0) v = 1 - u;  // on edge bc
    const double t0 = 0.1 + 0.8 * unit(random);
    const Vec3 normal = (b - a).cross(c - a).normalized();
    const Vec3 hit = a + t0 * da + u * (b - a) + v * (c - a);  // where the face is at t0
    const Vec3 dp = 0.4 * kSize * (normal + 0.3 * vector() / kSize).normalized() * (i % 2 ? 1 : -1);
    const Vec3 p = hit - t0 * dp;
    const auto t = nodeFaceImpact(origin + p, dp, origin + a, da, origin + b, db, origin + c, dc, kTolerance);
    if (t && std::abs(*t - t0) < 1e-4) ++nodeFaceFound;  // the inputs rounded: t moves by 2.4e-5

    // An edge crossing another at t0, each at an inner point.
    const Vec3 q0 = vector(), q1 = q0 + Vec3(kSize, 0.3 * kSize, 0), dq = 0.1 * vector();
    const Vec3 meet = q0 + t0 * dq + unit(random) * (q1 - q0);
    const Vec3 direction = Vec3(0.2, 1, 0.1).normalized() * kSize, dr = 0.4 * kSize * Vec3(0.1, -0.2, 1).normalized();
    const double s = unit(random);
    const Vec3 r0 = meet - s * direction - t0 * dr, r1 = r0 + direction;
    const auto te = edgeEdgeImpact(origin + r0, dr, origin + r1, dr, origin + q0, dq, origin + q1, dq, kTolerance);
    if (te && std::abs(*te - t0) < 1e-4) ++edgeEdgeFound;
  }
  EXPECT_EQ(nodeFaceFound, kCases);
  EXPECT_EQ(edgeEdgeFound, kCases);
}

// The origin; Limits::maxCoordinate (1e8 m, what validation allows for a scene's positions);
// 2^31 m, which a scene that validates can still reach (10^4 m/s for 10^7 steps).
INSTANTIATE_TEST_SUITE_P(Origins, ContinuousFarFromTheOrigin, testing::Values(0.0, 1e8, 2147483648.0),
                         [](const testing::TestParamInfo<double>& param) {
                           return "At" + std::to_string(static_cast<long long>(param.param)) + "Metres";
                         });

// Brute force: the first time on a fine grid at which the node is on the face's plane side
// change, refined, and on the face. The cubic's roots must agree with it.
std::optional<double> sampledNodeFaceImpact(const std::array<Vec3, 4>& x, const std::array<Vec3, 4>& d) {
  auto at = [&](int k, double t) -> Vec3 { return x[k] + t * d[k]; };
  auto side = [&](double t) {
    return (at(2, t) - at(1, t)).cross(at(3, t) - at(1, t)).dot(at(0, t) - at(1, t));
  };
  constexpr int kSamples = 20000;
  for (int i = 0; i < kSamples; ++i) {
    double low = double(i) / kSamples, high = double(i + 1) / kSamples;
    if ((side(low) < 0) == (side(high) < 0)) continue;
    for (int k = 0; k < 60; ++k) {
      const double middle = 0.5 * (low + high);
      ((side(middle) < 0) == (side(low) < 0) ? low : high) = middle;
    }
    const double t = 0.5 * (low + high);
    const auto w = geometry::closestOnTriangle(at(0, t), at(1, t), at(2, t), at(3, t));
    if ((at(0, t) - (w[0] * at(1, t) + w[1] * at(2, t) + w[2] * at(3, t))).norm() < 1e-7) return t;
  }
  return std::nullopt;
}

TEST(Continuous, CubicRootsAgreeWithSamplingOnRandomTumblingMotions) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto vector = [&] { return Vec3(unit(random), unit(random), unit(random)); };
  int hits = 0, agreed = 0, cases = 400;
  for (int c = 0; c < cases; ++c) {
    std::array<Vec3, 4> x{vector(), vector(), vector(), vector()};
    std::array<Vec3, 4> d{2 * vector(), 2 * vector(), 2 * vector(), 2 * vector()};
    const auto cubic = nodeFaceImpact(x[0], d[0], x[1], d[1], x[2], d[2], x[3], d[3], 1e-7);
    const auto sampled = sampledNodeFaceImpact(x, d);
    hits += cubic.has_value();
    if (cubic.has_value() == sampled.has_value() && (!cubic || std::abs(*cubic - *sampled) < 1e-6)) ++agreed;
  }
  EXPECT_GT(hits, 20);  // the random motions do hit, often enough to mean something
  EXPECT_EQ(agreed, cases);
}

// ---- Impact zones -------------------------------------------------------------------------

// One triangle and one node, as a surface each, with the node's mass and the face nodes'.
struct TwoSurfaces {
  NodeArrays nodes;
  std::vector<int32_t> faceNodes{0, 1, 2}, pointNodes{3};
  std::vector<std::array<int32_t, 3>> triangles{{0, 1, 2}}, noTriangles;
  std::vector<std::array<int32_t, 2>> faceEdges{{0, 1}, {1, 2}, {2, 0}}, noEdges;
  std::vector<Vec3> rest;
  std::vector<CollisionSurface> surfaces;

  TwoSurfaces(const std::array<double, 4>& inverseMass) {
    nodes.position = {kA, kB, kC, Vec3(0.25, 0.25, 0.5)};
    nodes.velocity.assign(4, Vec3::Zero());
    nodes.force.assign(4, Vec3::Zero());
    nodes.inverseMass.assign(inverseMass.begin(), inverseMass.end());
    rest = nodes.position;
    surfaces.push_back({0, 3, faceNodes, triangles, faceEdges, rest, 0.0, 0.0, false});
    surfaces.push_back({3, 1, pointNodes, noTriangles, noEdges, rest, 0.0, 0.0, false});
  }
  Vec3 momentum() const {
    Vec3 total = Vec3::Zero();
    for (size_t n = 0; n < 4; ++n)
      if (nodes.inverseMass[n] > 0) total += nodes.velocity[n] / nodes.inverseMass[n];
    return total;
  }
  Vec3 angularMomentum() const {
    Vec3 total = Vec3::Zero();
    for (size_t n = 0; n < 4; ++n)
      if (nodes.inverseMass[n] > 0) total += nodes.position[n].cross(nodes.velocity[n]) / nodes.inverseMass[n];
    return total;
  }
};

TEST(ImpactZones, ANodeThatWouldPassThroughAFaceMovesWithItAndKeepsMomentum) {
  TwoSurfaces world({1.0, 1.0, 1.0, 0.5});  // face nodes 1 kg each, the node 2 kg
  const double h = 0.1;
  const std::vector<Vec3> start = world.nodes.position;
  world.nodes.velocity[3] = {1.0, 0.5, -10.0};  // through the face in one step
  world.nodes.velocity[0] = {0, 0, 1.0};
  const Vec3 momentumBefore = world.momentum();
  const Vec3 angularBefore = world.angularMomentum();
  for (size_t n = 0; n < 4; ++n) world.nodes.position[n] += h * world.nodes.velocity[n];
  ASSERT_TRUE(nodeFaceImpact(start[3], world.nodes.position[3] - start[3], start[0],
                             world.nodes.position[0] - start[0], start[1], kZero, start[2], kZero, 1e-9));

  const ImpactZoneStats stats = separateByImpactZones(world.surfaces, start, world.nodes, h);
  EXPECT_EQ(stats.crossings, 1);
  EXPECT_EQ(stats.zones, 1);
  EXPECT_EQ(stats.zoneNodes, 4);
  // Momentum is kept, and so is angular momentum about the origin (no external forces).
  EXPECT_LT((world.momentum() - momentumBefore).norm(), 1e-12);
  EXPECT_LT((world.angularMomentum() - angularBefore).norm(), 1e-12);
  // The four moved rigidly: every distance between them is as it was.
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      EXPECT_NEAR((world.nodes.position[i] - world.nodes.position[j]).norm(), (start[i] - start[j]).norm(), 1e-12);
  // And the node is still above the face.
  const Vec3& p = world.nodes.position[3];
  const Vec3 normal = (world.nodes.position[1] - world.nodes.position[0])
                          .cross(world.nodes.position[2] - world.nodes.position[0]);
  EXPECT_GT(normal.dot(p - world.nodes.position[0]), 0.0);
  EXPECT_FALSE(nodeFaceImpact(start[3], p - start[3], start[0], world.nodes.position[0] - start[0], start[1],
                              world.nodes.position[1] - start[1], start[2], world.nodes.position[2] - start[2], 1e-9));
}

TEST(ImpactZones, AZoneWithAPinnedNodeMovesAsThePinDoes) {
  TwoSurfaces world({0.0, 1.0, 1.0, 1.0});  // node 0 pinned
  const double h = 0.1;
  const std::vector<Vec3> start = world.nodes.position;
  world.nodes.velocity[3] = {0, 0, -10.0};
  for (size_t n = 0; n < 4; ++n) world.nodes.position[n] += h * world.nodes.velocity[n];
  const ImpactZoneStats stats = separateByImpactZones(world.surfaces, start, world.nodes, h);
  EXPECT_EQ(stats.zones, 1);
  for (int n = 0; n < 4; ++n) {
    EXPECT_LT((world.nodes.position[n] - start[n]).norm(), 1e-15);
    EXPECT_LT(world.nodes.velocity[n].norm(), 1e-15);
  }
}

TEST(ImpactZones, NothingMovesWhenNothingCrosses) {
  TwoSurfaces world({1.0, 1.0, 1.0, 1.0});
  const double h = 0.1;
  const std::vector<Vec3> start = world.nodes.position;
  world.nodes.velocity[3] = {0, 0, -4.0};  // stops 0.1 above the face
  for (size_t n = 0; n < 4; ++n) world.nodes.position[n] += h * world.nodes.velocity[n];
  const std::vector<Vec3> end = world.nodes.position;
  const ImpactZoneStats stats = separateByImpactZones(world.surfaces, start, world.nodes, h);
  EXPECT_EQ(stats.crossings, 0);
  EXPECT_EQ(stats.zones, 0);
  EXPECT_EQ(world.nodes.position, end);
  EXPECT_EQ(world.nodes.velocity[3], Vec3(0, 0, -4.0));
}

TEST(ImpactZones, ANonFinitePositionIsLeftToTheDivergenceCheck) {
  TwoSurfaces world({1.0, 1.0, 1.0, 1.0});
  const std::vector<Vec3> start = world.nodes.position;
  world.nodes.position[3] = Vec3(NAN, 0.0, -1.0);
  const ImpactZoneStats stats = separateByImpactZones(world.surfaces, start, world.nodes, 0.1);
  EXPECT_EQ(stats.zones, 0);
  EXPECT_TRUE(std::isnan(world.nodes.position[3].x()));
  EXPECT_EQ(world.nodes.position[0], start[0]);
}

}  // namespace
}  // namespace tandem
