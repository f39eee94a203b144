// Rigid shapes as triangles: each surface encloses its shape's volume, winds outward, and
// carries outward normals (what the renderer draws must be the shape the solver collides).
#include <tandem/shape_surface.h>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace tandem {
namespace {

// Σ a·(b × c) / 6: the enclosed volume, positive when every triangle winds outward.
double enclosedVolume(const ShapeSurface& s) {
  double volume = 0.0;
  for (const auto& t : s.triangles)
    volume += s.positions[t[0]].dot(s.positions[t[1]].cross(s.positions[t[2]])) / 6.0;
  return volume;
}

// For shapes convex about their origin: every vertex normal and every face points away from it.
void expectOutward(const ShapeSurface& s) {
  ASSERT_EQ(s.positions.size(), s.normals.size());
  for (size_t i = 0; i < s.positions.size(); ++i) {
    EXPECT_NEAR(s.normals[i].norm(), 1.0, 1e-9);
    EXPECT_GT(s.normals[i].dot(s.positions[i]), 0.0) << "vertex " << i;
  }
  for (const auto& t : s.triangles) {
    const Vec3 &a = s.positions[t[0]], &b = s.positions[t[1]], &c = s.positions[t[2]];
    EXPECT_GT((b - a).cross(c - a).dot(a + b + c), 0.0);
  }
}

constexpr double kPi = std::numbers::pi;

TEST(ShapeSurface, BoxIsExact) {
  const ShapeSurface box = shapeSurface(RigidShape::box({0.1, 0.2, 0.3}));
  EXPECT_EQ(box.triangles.size(), 12u);
  EXPECT_NEAR(enclosedVolume(box), 0.2 * 0.4 * 0.6, 1e-12);
  expectOutward(box);
}

TEST(ShapeSurface, RoundShapesApproachTheirVolume) {
  const double r = 0.3, half = 0.4;
  const ShapeSurface sphere = shapeSurface(RigidShape::sphere(r), 64);
  const ShapeSurface cylinder = shapeSurface(RigidShape::cylinder(r, half), 64);
  const ShapeSurface capsule = shapeSurface(RigidShape::capsule(r, half), 64);
  // An inscribed polygon of n sides has area n/(2π) sin(2π/n) of its circle: 0.16% short at 64.
  EXPECT_NEAR(enclosedVolume(sphere) / (4.0 / 3 * kPi * r * r * r), 1.0, 0.01);
  EXPECT_NEAR(enclosedVolume(cylinder) / (kPi * r * r * 2 * half), 1.0, 0.003);
  EXPECT_NEAR(enclosedVolume(capsule) / (kPi * r * r * (2 * half + 4.0 / 3 * r)), 1.0, 0.01);
  for (const ShapeSurface* s : {&sphere, &cylinder, &capsule}) expectOutward(*s);
  double top = -1e9;
  for (const Vec3& p : cylinder.positions) top = std::max(top, p.y());
  EXPECT_DOUBLE_EQ(top, half);  // the axis is the body's y
}

TEST(ShapeSurface, ConvexHullWrapsItsPoints) {
  std::vector<Vec3> points;  // an octahedron, with an interior point the hull must leave out
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {-1.0, 1.0}) points.push_back(sign * Vec3::Unit(axis));
  points.emplace_back(0.1, 0.1, 0.1);
  const ShapeSurface hull = shapeSurface(RigidShape::convexHull(points));
  EXPECT_EQ(hull.triangles.size(), 8u);
  EXPECT_NEAR(enclosedVolume(hull), 4.0 / 3.0, 1e-9);
  expectOutward(hull);
}

TEST(ShapeSurface, TriangleMeshKeepsItsTrianglesAndPlanesHaveNone) {
  const ShapeSurface mesh = shapeSurface(RigidShape::triangleMesh({{0, 0, 0}, {1, 0, 0}, {0, 0, -1}}, {{{0, 1, 2}}}));
  ASSERT_EQ(mesh.triangles.size(), 1u);
  EXPECT_LT((mesh.normals[0] - Vec3::UnitY()).norm(), 1e-12);
  EXPECT_TRUE(shapeSurface(RigidShape::plane({0, 1, 0}, 0)).triangles.empty());
}

}  // namespace
}  // namespace tandem
