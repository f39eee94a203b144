// Deformable meshes: the node set and its topology, plus generators.
//
// A mesh is plain data: node positions and masses, and elements (edges, surface triangles,
// tetrahedra) that refer to nodes by index. It is validated once, when a deformable body is
// made from it (World::addDeformable) or by validateMesh().
#pragma once

#include <tandem/export.h>
#include <tandem/limits.h>
#include <tandem/types.h>

#include <array>
#include <cstdint>
#include <string>
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

// Generators and readers refuse meshes past `limits` (total nodes, triangles, tetrahedra; file
// bytes: include/tandem/limits.h), naming the count and the limit, before allocating anything.

// Checks sizes, finiteness, masses (> 0 and finite), index ranges,
// zero-length edges and degenerate triangles and tetrahedra.
TANDEM_API Status validateMesh(const DeformableMesh& mesh);

// A straight rope of `nodeCount` nodes from `start` to `end`, `totalMass` spread evenly.
TANDEM_API Result<DeformableMesh> makeRope(const Vec3& start, const Vec3& end, int nodeCount, double totalMass,
                                const Limits& limits = {});

// A rope of `nodeCount` nodes laid along the polyline through `path` (two or more points), spaced
// evenly by arc length, `totalMass` spread evenly: a rope over a wheel or round a post.
TANDEM_API Result<DeformableMesh> makeRopeAlongPath(const std::vector<Vec3>& path, int nodeCount, double totalMass,
                                         const Limits& limits = {});

// A rectangular cloth of `columns` x `rows` nodes spanning `corner` to `corner + sideU + sideV`,
// with structural edges along both grid directions, alternating-diagonal triangles, and the
// diagonals as shear edges. Node (column c, row r) has index r * columns + c.
TANDEM_API Result<DeformableMesh> makeClothGrid(const Vec3& corner, const Vec3& sideU, const Vec3& sideV,
                                     int columns, int rows, double totalMass, const Limits& limits = {});

// An axis-aligned box from `minCorner` to `maxCorner` split into cellsX*cellsY*cellsZ cubes of
// five tetrahedra each, with every tet edge and the boundary triangles.
TANDEM_API Result<DeformableMesh> makeTetBox(const Vec3& minCorner, const Vec3& maxCorner, int cellsX, int cellsY,
                                  int cellsZ, double totalMass, const Limits& limits = {});

// A tetrahedral cylinder along +y from `baseCentre`: `rings` cells across the radius,
// `sectors` around, `layers` along the axis; a central prism of each layer is split like the
// outer ones, so every tet is well shaped. Boundary triangles and tet edges included.
TANDEM_API Result<DeformableMesh> makeTetCylinder(const Vec3& baseCentre, double radius, double height, int rings, int sectors,
                                       int layers, double totalMass, const Limits& limits = {});

// A TetGen mesh: `<base>.node` and `<base>.ele`, and `<base>.face` for the boundary when it
// exists (else the boundary is found from the tets). Masses are lumped from `density` (kg/m³):
// a quarter of each tet's mass to each of its nodes. Tets wound the other way round (TetGen's
// own convention among them) are turned round; degenerate tets, and any problem in the files,
// are errors naming the file and the line.
TANDEM_API Result<DeformableMesh> loadTetGen(const std::string& basePath, double density, const Limits& limits = {});

// A surface mesh from a Wavefront OBJ file (polygons are triangulated); its edges are the
// triangles' edges, `totalMass` lumped by area.
TANDEM_API Result<DeformableMesh> loadObj(const std::string& path, double totalMass, const Limits& limits = {});

// For bending: each interior edge (i, j) shared by triangles (i, j, left) and (j, i, right).
struct EdgeHinge {
  int32_t i, j, left, right;
};
TANDEM_API std::vector<EdgeHinge> findEdgeHinges(const std::vector<std::array<int32_t, 3>>& triangles);

}  // namespace tandem
