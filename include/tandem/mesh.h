// Deformable meshes: the node set and its topology, plus generators.
//
// A mesh is plain data: node positions and masses, and elements (edges, surface triangles,
// tetrahedra) that refer to nodes by index. It is validated once, when a deformable body is
// made from it (World::addDeformable) or by validateMesh().
#pragma once

#include <tandem/types.h>

#include <array>
#include <cstdint>
#include <vector>

namespace tandem {

struct DeformableMesh {
  std::vector<Vec3> positions;           // metres, world frame
  std::vector<double> masses;            // kilograms per node, each > 0 (World::fixNode pins a node)
  std::vector<std::array<int32_t, 2>> edges;
  // Edges that only resist shear, like a cloth grid's diagonals. Springs act on them; rows of
  // inextensibility only when asked for (InextensibilitySettings::shearEdges), because on a
  // flat triangulated sheet they over-determine the in-plane motion.
  std::vector<std::array<int32_t, 2>> shearEdges;
  std::vector<std::array<int32_t, 3>> triangles;  // surface faces, counter-clockwise seen from outside
  std::vector<std::array<int32_t, 4>> tetrahedra;

  int32_t nodeCount() const { return static_cast<int32_t>(positions.size()); }
};

// Checks sizes, finiteness, masses (> 0 and finite), index ranges,
// zero-length edges and degenerate triangles and tetrahedra.
Status validateMesh(const DeformableMesh& mesh);

// A straight rope of `nodeCount` nodes from `start` to `end`, `totalMass` spread evenly.
Result<DeformableMesh> makeRope(const Vec3& start, const Vec3& end, int nodeCount, double totalMass);

// A rectangular cloth of `columns` x `rows` nodes spanning `corner` to `corner + sideU + sideV`,
// with structural edges along both grid directions, alternating-diagonal triangles, and the
// diagonals as shear edges. Node (column c, row r) has index r * columns + c.
Result<DeformableMesh> makeClothGrid(const Vec3& corner, const Vec3& sideU, const Vec3& sideV,
                                     int columns, int rows, double totalMass);

// An axis-aligned box from `minCorner` to `maxCorner` split into cellsX*cellsY*cellsZ cubes of
// five tetrahedra each, with every tet edge and the boundary triangles.
Result<DeformableMesh> makeTetBox(const Vec3& minCorner, const Vec3& maxCorner, int cellsX, int cellsY,
                                  int cellsZ, double totalMass);

// For bending: each interior edge (i, j) shared by triangles (i, j, left) and (j, i, right).
struct EdgeHinge {
  int32_t i, j, left, right;
};
std::vector<EdgeHinge> findEdgeHinges(const std::vector<std::array<int32_t, 3>>& triangles);

}  // namespace tandem
