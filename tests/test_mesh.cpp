// Generators: counts, masses, geometry and orientation of what they make.
#include <tandem/mesh.h>

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

namespace tandem {
namespace {

double totalMass(const DeformableMesh& mesh) { return std::accumulate(mesh.masses.begin(), mesh.masses.end(), 0.0); }

TEST(Mesh, RopeHasEvenlySpacedNodesAndItsMass) {
  Result<DeformableMesh> rope = makeRope({0, 2, 0}, {0, 1, 0}, 20, 0.2);
  ASSERT_TRUE(rope.ok()) << rope.message();
  EXPECT_EQ(rope->nodeCount(), 20);
  EXPECT_EQ(rope->edges.size(), 19u);
  EXPECT_NEAR(totalMass(*rope), 0.2, 1e-12);
  for (const auto& e : rope->edges)
    EXPECT_NEAR((rope->positions[e[1]] - rope->positions[e[0]]).norm(), 1.0 / 19, 1e-12);
  EXPECT_TRUE(validateMesh(*rope).ok());
}

TEST(Mesh, RopeAlongAPathIsEvenlySpacedByArcLength) {
  // An L: 1 m up, 0.5 m across; 31 nodes, 5 cm apart along the path, the corner a node.
  Result<DeformableMesh> rope = makeRopeAlongPath({{0, 0, 0}, {0, 1, 0}, {0.5, 1, 0}}, 31, 0.3);
  ASSERT_TRUE(rope.ok()) << rope.message();
  EXPECT_EQ(rope->edges.size(), 30u);
  EXPECT_NEAR(totalMass(*rope), 0.3, 1e-12);
  EXPECT_NEAR((rope->positions[20] - Vec3(0, 1, 0)).norm(), 0.0, 1e-12);
  for (int i = 0; i < 20; ++i) EXPECT_NEAR(rope->positions[i].y(), 0.05 * i, 1e-12);
  for (int i = 20; i < 31; ++i) EXPECT_NEAR(rope->positions[i].x(), 0.05 * (i - 20), 1e-12);
  // Bad paths are refused with what is wrong.
  EXPECT_EQ(makeRopeAlongPath({{0, 0, 0}}, 5, 1.0).message(), "rope: a path needs at least 2 points, got 1");
  EXPECT_EQ(makeRopeAlongPath({{0, 0, 0}, {0, 0, 0}}, 5, 1.0).message(), "rope: the path has zero length");
  EXPECT_FALSE(makeRopeAlongPath({{0, 0, 0}, {0, NAN, 0}}, 5, 1.0).ok());
  EXPECT_FALSE(makeRopeAlongPath({{0, 0, 0}, {1, 0, 0}}, 1, 1.0).ok());
  EXPECT_FALSE(makeRopeAlongPath({{0, 0, 0}, {1, 0, 0}}, 5, -1.0).ok());
}

TEST(Mesh, ClothGridCountsAndHinges) {
  const int columns = 7, rows = 5;
  Result<DeformableMesh> cloth = makeClothGrid({0, 0, 0}, {1.2, 0, 0}, {0, 0, 0.8}, columns, rows, 0.3);
  ASSERT_TRUE(cloth.ok()) << cloth.message();
  EXPECT_EQ(cloth->nodeCount(), columns * rows);
  const size_t structural = columns * (rows - 1) + rows * (columns - 1);
  const size_t diagonals = (columns - 1) * (rows - 1);
  EXPECT_EQ(cloth->edges.size(), structural);
  EXPECT_EQ(cloth->shearEdges.size(), diagonals);
  EXPECT_EQ(cloth->triangles.size(), 2 * diagonals);
  EXPECT_NEAR(totalMass(*cloth), 0.3, 1e-12);
  // Every edge not on the boundary is shared by two triangles and makes one hinge.
  const size_t boundary = 2 * (columns - 1) + 2 * (rows - 1);
  EXPECT_EQ(findEdgeHinges(cloth->triangles).size(), structural + diagonals - boundary);
  // Triangles are consistently wound: all normals point the same way.
  for (const auto& t : cloth->triangles) {
    const Vec3 normal = (cloth->positions[t[1]] - cloth->positions[t[0]]).cross(cloth->positions[t[2]] - cloth->positions[t[0]]);
    EXPECT_LT(normal.y(), 0.0);  // sideU × sideV = x × z = −y
  }
  EXPECT_TRUE(validateMesh(*cloth).ok());
}

TEST(Mesh, TetBoxFillsItsVolumeWithOutwardBoundary) {
  const Vec3 low{-0.5, 0.0, -0.25}, high{0.5, 0.4, 0.25};
  Result<DeformableMesh> box = makeTetBox(low, high, 3, 2, 2, 1.5);
  ASSERT_TRUE(box.ok()) << box.message();
  EXPECT_EQ(box->nodeCount(), 4 * 3 * 3);
  EXPECT_EQ(box->tetrahedra.size(), 5u * 3 * 2 * 2);
  const auto& x = box->positions;
  double volume = 0.0;
  for (const auto& t : box->tetrahedra) {
    const double v = (x[t[1]] - x[t[0]]).dot((x[t[2]] - x[t[0]]).cross(x[t[3]] - x[t[0]])) / 6.0;
    EXPECT_GT(v, 0.0);
    volume += v;
  }
  const double expected = (high - low).prod();
  EXPECT_NEAR(volume, expected, 1e-12);
  // Boundary: two triangles per boundary cell face, and by the divergence theorem
  // Σ (centroid · n) area / 3 = volume when the normals point outwards.
  EXPECT_EQ(box->triangles.size(), 4u * (3 * 2 + 2 * 2 + 3 * 2));
  double flux = 0.0;
  for (const auto& f : box->triangles) {
    const Vec3 areaNormal = 0.5 * (x[f[1]] - x[f[0]]).cross(x[f[2]] - x[f[0]]);
    flux += ((x[f[0]] + x[f[1]] + x[f[2]]) / 3.0).dot(areaNormal) / 3.0;
  }
  EXPECT_NEAR(flux, expected, 1e-12);
  EXPECT_NEAR(totalMass(*box), 1.5, 1e-12);
  EXPECT_TRUE(validateMesh(*box).ok());
}

}  // namespace
}  // namespace tandem
