#include <tandem/mesh.h>

#include "format.h"
#include "mesh_internal.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>

namespace tandem {
namespace {

template <size_t N>
Status checkIndices(const std::vector<std::array<int32_t, N>>& elements, int32_t nodeCount, const char* kind) {
  for (size_t e = 0; e < elements.size(); ++e) {
    for (size_t k = 0; k < N; ++k) {
      const int32_t index = elements[e][k];
      if (index < 0 || index >= nodeCount)
        return Error{std::string(kind) + " " + std::to_string(e) + " refers to node " + std::to_string(index) +
                     ", but the mesh has " + std::to_string(nodeCount) + " nodes"};
      for (size_t other = 0; other < k; ++other)
        if (elements[e][other] == index)
          return Error{std::string(kind) + " " + std::to_string(e) + " uses node " + std::to_string(index) + " twice"};
    }
  }
  return {};
}

Status checkCounts(int count, int minimum, const char* what, const char* generator) {
  if (count < minimum)
    return Error{std::string(generator) + ": " + what + " must be >= " + std::to_string(minimum) + ", got " +
                 std::to_string(count)};
  return {};
}

Status checkTotalMass(double totalMass, const char* generator) {
  if (!std::isfinite(totalMass) || totalMass <= 0)
    return Error{std::string(generator) + ": total mass must be a positive number of kilograms, got " + formatNumber(totalMass)};
  return {};
}

Status checkPoint(const Vec3& p, const char* what, const char* generator) {
  if (!p.allFinite()) return Error{std::string(generator) + ": " + what + " is not finite"};
  return {};
}

void spreadMass(DeformableMesh& mesh, double totalMass) {
  mesh.masses.assign(mesh.positions.size(), totalMass / static_cast<double>(mesh.positions.size()));
}

void addUniqueEdges(DeformableMesh& mesh, const std::vector<std::array<int32_t, 2>>& candidates) {
  std::set<std::pair<int32_t, int32_t>> seen;
  for (const auto& e : mesh.edges) seen.insert({std::min(e[0], e[1]), std::max(e[0], e[1])});
  for (const auto& e : candidates) {
    const std::pair<int32_t, int32_t> key{std::min(e[0], e[1]), std::max(e[0], e[1])};
    if (seen.insert(key).second) mesh.edges.push_back({key.first, key.second});
  }
}

}  // namespace

Status checkMeshSize(double nodes, double triangles, double tetrahedra, const Limits& limits, const std::string& who,
                     const std::string& shape) {
  auto over = [&](double count, double limit, const char* what, const char* limitName) -> Status {
    if (count <= limit) return {};
    char numbers[96];
    std::snprintf(numbers, sizeof numbers, "%.0f %s, more than the limit of %.0f", count, what, limit);
    return Error{who + ": " + shape + " is " + numbers + " (" + limitName + "; the API can raise it)"};
  };
  const double maxNodes = static_cast<double>(std::min(limits.maxNodes, kMaxIndexableNodes));
  if (Status s = over(nodes, maxNodes, "nodes", "Limits::maxNodes"); !s) return s;
  if (Status s = over(triangles, static_cast<double>(limits.maxTriangles), "triangles", "Limits::maxTriangles"); !s) return s;
  return over(tetrahedra, static_cast<double>(limits.maxTetrahedra), "tetrahedra", "Limits::maxTetrahedra");
}

void addTetEdgesAndBoundary(DeformableMesh& mesh) {
  // Edges of every tet; boundary faces are those used by exactly one tet, oriented outwards.
  std::vector<std::array<int32_t, 2>> edges;
  std::map<std::array<int32_t, 3>, std::pair<int, std::array<int32_t, 3>>> faces;
  for (const auto& t : mesh.tetrahedra) {
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) edges.push_back({t[a], t[b]});
    // Faces opposite each vertex, wound so the normal points away from that vertex (the tet
    // is positively oriented: (x1 − x0) · ((x2 − x0) × (x3 − x0)) > 0).
    const std::array<std::array<int32_t, 3>, 4> tetFaces{
        {{t[1], t[2], t[3]}, {t[0], t[3], t[2]}, {t[0], t[1], t[3]}, {t[0], t[2], t[1]}}};
    for (const auto& f : tetFaces) {
      std::array<int32_t, 3> key = f;
      std::sort(key.begin(), key.end());
      auto& entry = faces[key];
      ++entry.first;
      entry.second = f;
    }
  }
  addUniqueEdges(mesh, edges);
  if (!mesh.triangles.empty()) return;  // given (a TetGen .face file)
  for (const auto& [key, entry] : faces)
    if (entry.first == 1) mesh.triangles.push_back(entry.second);
}

Status validateMesh(const DeformableMesh& mesh) {
  const int32_t n = mesh.nodeCount();
  if (n == 0) return Error{"mesh has no nodes"};
  if (mesh.masses.size() != mesh.positions.size())
    return Error{"mesh has " + std::to_string(n) + " positions but " + std::to_string(mesh.masses.size()) +
                 " masses"};
  for (int32_t i = 0; i < n; ++i) {
    if (!mesh.positions[i].allFinite()) return Error{"node " + std::to_string(i) + " has a non-finite position"};
    const double m = mesh.masses[i];
    if (!std::isfinite(m) || m <= 0)
      return Error{"node " + std::to_string(i) + " has mass " + formatNumber(m) + " kg; masses must be positive and finite"};
  }
  if (Status s = checkIndices(mesh.edges, n, "edge"); !s) return s;
  if (Status s = checkIndices(mesh.shearEdges, n, "shear edge"); !s) return s;
  if (Status s = checkIndices(mesh.triangles, n, "triangle"); !s) return s;
  if (Status s = checkIndices(mesh.tetrahedra, n, "tetrahedron"); !s) return s;
  const auto& x = mesh.positions;
  for (size_t e = 0; e < mesh.edges.size(); ++e) {
    const double length = (x[mesh.edges[e][1]] - x[mesh.edges[e][0]]).norm();
    if (length < 1e-9) return Error{"edge " + std::to_string(e) + " has zero length"};
  }
  for (size_t e = 0; e < mesh.shearEdges.size(); ++e) {
    const double length = (x[mesh.shearEdges[e][1]] - x[mesh.shearEdges[e][0]]).norm();
    if (length < 1e-9) return Error{"shear edge " + std::to_string(e) + " has zero length"};
  }
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& f = mesh.triangles[t];
    const double twiceArea = (x[f[1]] - x[f[0]]).cross(x[f[2]] - x[f[0]]).norm();
    const double scale = std::max({(x[f[1]] - x[f[0]]).squaredNorm(), (x[f[2]] - x[f[0]]).squaredNorm(), 1e-300});
    if (twiceArea < 1e-9 * scale) return Error{"triangle " + std::to_string(t) + " is degenerate (zero area)"};
  }
  for (size_t t = 0; t < mesh.tetrahedra.size(); ++t) {
    const auto& k = mesh.tetrahedra[t];
    const double sixVolume = (x[k[1]] - x[k[0]]).dot((x[k[2]] - x[k[0]]).cross(x[k[3]] - x[k[0]]));
    const double edge = (x[k[1]] - x[k[0]]).norm();
    if (sixVolume <= 1e-9 * edge * edge * edge)
      return Error{"tetrahedron " + std::to_string(t) +
                   (sixVolume < 0 ? " is inverted (negative volume)" : " is degenerate (zero volume)")};
  }
  return {};
}

Result<DeformableMesh> makeRope(const Vec3& start, const Vec3& end, int nodeCount, double totalMass,
                                const Limits& limits) {
  if (Status s = checkCounts(nodeCount, 2, "node count", "rope"); !s) return Error{s.message()};
  if (Status s = checkMeshSize(nodeCount, 0, 0, limits, "rope", "the node count"); !s) return Error{s.message()};
  if (Status s = checkTotalMass(totalMass, "rope"); !s) return Error{s.message()};
  if (Status s = checkPoint(start, "start", "rope"); !s) return Error{s.message()};
  if (Status s = checkPoint(end, "end", "rope"); !s) return Error{s.message()};
  if ((end - start).norm() < 1e-9) return Error{"rope: start and end coincide (zero length)"};
  DeformableMesh mesh;
  for (int i = 0; i < nodeCount; ++i)
    mesh.positions.push_back(start + (end - start) * (static_cast<double>(i) / (nodeCount - 1)));
  for (int i = 0; i + 1 < nodeCount; ++i) mesh.edges.push_back({i, i + 1});
  spreadMass(mesh, totalMass);
  return mesh;
}

Result<DeformableMesh> makeRopeAlongPath(const std::vector<Vec3>& path, int nodeCount, double totalMass,
                                         const Limits& limits) {
  if (path.size() < 2) return Error{"rope: a path needs at least 2 points, got " + std::to_string(path.size())};
  if (Status s = checkCounts(nodeCount, 2, "node count", "rope"); !s) return Error{s.message()};
  if (Status s = checkMeshSize(nodeCount, 0, 0, limits, "rope", "the node count"); !s) return Error{s.message()};
  if (Status s = checkTotalMass(totalMass, "rope"); !s) return Error{s.message()};
  std::vector<double> along{0.0};  // arc length at each path point
  for (size_t i = 0; i < path.size(); ++i) {
    if (Status s = checkPoint(path[i], ("path point " + std::to_string(i)).c_str(), "rope"); !s)
      return Error{s.message()};
    if (i > 0) along.push_back(along.back() + (path[i] - path[i - 1]).norm());
  }
  if (along.back() < 1e-9) return Error{"rope: the path has zero length"};
  DeformableMesh mesh;
  size_t segment = 0;
  for (int i = 0; i < nodeCount; ++i) {
    const double s = along.back() * (static_cast<double>(i) / (nodeCount - 1));
    while (segment + 2 < path.size() && along[segment + 1] < s) ++segment;
    const double length = along[segment + 1] - along[segment];
    const double t = length > 0 ? std::clamp((s - along[segment]) / length, 0.0, 1.0) : 0.0;
    mesh.positions.push_back(path[segment] + t * (path[segment + 1] - path[segment]));
  }
  for (int i = 0; i + 1 < nodeCount; ++i) mesh.edges.push_back({i, i + 1});
  spreadMass(mesh, totalMass);
  if (Status s = validateMesh(mesh); !s) return Error{"rope: " + s.message()};
  return mesh;
}

Result<DeformableMesh> makeClothGrid(const Vec3& corner, const Vec3& sideU, const Vec3& sideV, int columns, int rows,
                                     double totalMass, const Limits& limits) {
  if (Status s = checkCounts(columns, 2, "columns", "cloth grid"); !s) return Error{s.message()};
  if (Status s = checkCounts(rows, 2, "rows", "cloth grid"); !s) return Error{s.message()};
  if (Status s = checkMeshSize(double(columns) * rows, 2.0 * (columns - 1.0) * (rows - 1.0), 0, limits, "cloth grid",
                               std::to_string(columns) + " x " + std::to_string(rows) + " nodes");
      !s)
    return Error{s.message()};
  if (Status s = checkTotalMass(totalMass, "cloth grid"); !s) return Error{s.message()};
  if (!corner.allFinite() || !sideU.allFinite() || !sideV.allFinite())
    return Error{"cloth grid: corner and sides must be finite"};
  if (sideU.cross(sideV).norm() < 1e-12 * std::max(1.0, sideU.squaredNorm() + sideV.squaredNorm()))
    return Error{"cloth grid: the two sides are parallel or zero (the cloth has no area)"};
  DeformableMesh mesh;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c)
      mesh.positions.push_back(corner + sideU * (static_cast<double>(c) / (columns - 1)) +
                               sideV * (static_cast<double>(r) / (rows - 1)));
  auto id = [columns](int c, int r) { return static_cast<int32_t>(r * columns + c); };
  std::vector<std::array<int32_t, 2>> edges;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) {
      if (c + 1 < columns) edges.push_back({id(c, r), id(c + 1, r)});
      if (r + 1 < rows) edges.push_back({id(c, r), id(c, r + 1)});
      if (c + 1 < columns && r + 1 < rows) {
        // Alternate the diagonal so the cloth has no preferred shear direction.
        if ((c + r) % 2 == 0) {
          mesh.triangles.push_back({id(c, r), id(c + 1, r), id(c + 1, r + 1)});
          mesh.triangles.push_back({id(c, r), id(c + 1, r + 1), id(c, r + 1)});
          mesh.shearEdges.push_back({id(c, r), id(c + 1, r + 1)});
        } else {
          mesh.triangles.push_back({id(c, r), id(c + 1, r), id(c, r + 1)});
          mesh.triangles.push_back({id(c + 1, r), id(c + 1, r + 1), id(c, r + 1)});
          mesh.shearEdges.push_back({id(c + 1, r), id(c, r + 1)});
        }
      }
    }
  mesh.edges = std::move(edges);
  spreadMass(mesh, totalMass);
  return mesh;
}

Result<DeformableMesh> makeTetBox(const Vec3& minCorner, const Vec3& maxCorner, int cellsX, int cellsY, int cellsZ,
                                  double totalMass, const Limits& limits) {
  if (Status s = checkCounts(cellsX, 1, "cells along x", "tet box"); !s) return Error{s.message()};
  if (Status s = checkCounts(cellsY, 1, "cells along y", "tet box"); !s) return Error{s.message()};
  if (Status s = checkCounts(cellsZ, 1, "cells along z", "tet box"); !s) return Error{s.message()};
  const double cells = double(cellsX) * cellsY * cellsZ;
  const double boundaryCells = 2.0 * (double(cellsX) * cellsY + double(cellsY) * cellsZ + double(cellsZ) * cellsX);
  if (Status s = checkMeshSize((cellsX + 1.0) * (cellsY + 1.0) * (cellsZ + 1.0), 2 * boundaryCells, 5 * cells, limits,
                               "tet box",
                               std::to_string(cellsX) + " x " + std::to_string(cellsY) + " x " + std::to_string(cellsZ) +
                                   " cells");
      !s)
    return Error{s.message()};
  if (Status s = checkTotalMass(totalMass, "tet box"); !s) return Error{s.message()};
  if (!minCorner.allFinite() || !maxCorner.allFinite()) return Error{"tet box: corners must be finite"};
  if ((maxCorner - minCorner).minCoeff() <= 0)
    return Error{"tet box: max corner must exceed min corner along every axis"};
  const int nx = cellsX + 1, ny = cellsY + 1, nz = cellsZ + 1;
  DeformableMesh mesh;
  const Vec3 size = maxCorner - minCorner;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        mesh.positions.push_back(minCorner + Vec3(size.x() * i / cellsX, size.y() * j / cellsY, size.z() * k / cellsZ));
  auto id = [&](int i, int j, int k) { return static_cast<int32_t>((k * ny + j) * nx + i); };
  for (int k = 0; k < cellsZ; ++k)
    for (int j = 0; j < cellsY; ++j)
      for (int i = 0; i < cellsX; ++i) {
        // Corners v[abc] = (i+a, j+b, k+c). Mirror the five-tet split in alternate cells so
        // faces shared by neighbouring cells are cut by the same diagonal.
        int32_t v[2][2][2];
        for (int a = 0; a < 2; ++a)
          for (int b = 0; b < 2; ++b)
            for (int c = 0; c < 2; ++c) v[a][b][c] = id(i + a, j + b, k + c);
        const bool flip = (i + j + k) % 2 == 1;
        auto corner = [&](int a, int b, int c) { return flip ? v[1 - a][b][c] : v[a][b][c]; };
        const std::array<std::array<int32_t, 4>, 5> tets{{
            {corner(0, 0, 0), corner(1, 0, 0), corner(0, 1, 0), corner(0, 0, 1)},
            {corner(1, 1, 0), corner(0, 1, 0), corner(1, 0, 0), corner(1, 1, 1)},
            {corner(1, 0, 1), corner(0, 0, 1), corner(1, 1, 1), corner(1, 0, 0)},
            {corner(0, 1, 1), corner(1, 1, 1), corner(0, 0, 1), corner(0, 1, 0)},
            {corner(1, 0, 0), corner(0, 1, 0), corner(0, 0, 1), corner(1, 1, 1)},
        }};
        for (auto tet : tets) {
          const auto& x = mesh.positions;
          if ((x[tet[1]] - x[tet[0]]).dot((x[tet[2]] - x[tet[0]]).cross(x[tet[3]] - x[tet[0]])) < 0)
            std::swap(tet[2], tet[3]);
          mesh.tetrahedra.push_back(tet);
        }
      }
  addTetEdgesAndBoundary(mesh);
  spreadMass(mesh, totalMass);
  return mesh;
}

Result<DeformableMesh> makeTetCylinder(const Vec3& baseCentre, double radius, double height, int rings, int sectors,
                                       int layers, double totalMass, const Limits& limits) {
  if (Status s = checkCounts(rings, 1, "rings", "tet cylinder"); !s) return Error{s.message()};
  if (Status s = checkCounts(sectors, 3, "sectors", "tet cylinder"); !s) return Error{s.message()};
  if (Status s = checkCounts(layers, 1, "layers", "tet cylinder"); !s) return Error{s.message()};
  // Per layer: 3 tets per sector in the core, 6 per outer cell; boundary: both caps and the side.
  const double ringCells = double(rings) * sectors;
  if (Status s = checkMeshSize((layers + 1.0) * (1.0 + ringCells), 2.0 * (2.0 * ringCells - sectors) + 2.0 * sectors * layers,
                               double(layers) * sectors * (3.0 + 6.0 * (rings - 1.0)), limits, "tet cylinder",
                               std::to_string(rings) + " rings x " + std::to_string(sectors) + " sectors x " +
                                   std::to_string(layers) + " layers");
      !s)
    return Error{s.message()};
  if (Status s = checkTotalMass(totalMass, "tet cylinder"); !s) return Error{s.message()};
  if (Status s = checkPoint(baseCentre, "base centre", "tet cylinder"); !s) return Error{s.message()};
  if (!(std::isfinite(radius) && radius > 0 && std::isfinite(height) && height > 0))
    return Error{"tet cylinder: radius and height must be positive, got " + formatNumber(radius) + " and " +
                 formatNumber(height)};
  DeformableMesh mesh;
  const int perLevel = 1 + rings * sectors;
  auto centre = [&](int level) { return static_cast<int32_t>(level * perLevel); };
  auto node = [&](int level, int ring, int sector) {  // ring 1..rings
    return static_cast<int32_t>(level * perLevel + 1 + (ring - 1) * sectors + (sector % sectors));
  };
  for (int level = 0; level <= layers; ++level) {
    const double y = height * level / layers;
    mesh.positions.push_back(baseCentre + Vec3(0, y, 0));
    for (int ring = 1; ring <= rings; ++ring)
      for (int sector = 0; sector < sectors; ++sector) {
        const double angle = 2 * 3.14159265358979323846 * sector / sectors, r = radius * ring / rings;
        mesh.positions.push_back(baseCentre + Vec3(r * std::cos(angle), y, r * std::sin(angle)));
      }
  }
  auto addTet = [&](std::array<int32_t, 4> tet) {
    const auto& x = mesh.positions;
    if ((x[tet[1]] - x[tet[0]]).dot((x[tet[2]] - x[tet[0]]).cross(x[tet[3]] - x[tet[0]])) < 0) std::swap(tet[2], tet[3]);
    mesh.tetrahedra.push_back(tet);
  };
  for (int level = 0; level < layers; ++level)
    for (int sector = 0; sector < sectors; ++sector) {
      // Core prism (centre, ring 1 at this sector and the next): three tets whose face diagonals
      // match its neighbours' (centre bottom to ring top; ring bottom to next-sector top).
      const int32_t c0 = centre(level), c1 = centre(level + 1);
      const int32_t a0 = node(level, 1, sector), a1 = node(level + 1, 1, sector);
      const int32_t b0 = node(level, 1, sector + 1), b1 = node(level + 1, 1, sector + 1);
      addTet({c0, a0, b0, b1});
      addTet({c0, a0, b1, a1});
      addTet({c0, a1, b1, c1});
      // Outer cells: hexahedra in (ring, sector, level), six tets each along the diagonal from
      // their lowest to their highest corner (Kuhn), which conforms between neighbours.
      for (int ring = 1; ring < rings; ++ring) {
        auto corner = [&](int dr, int ds, int dl) { return node(level + dl, ring + dr, sector + ds); };
        const std::array<std::array<int, 3>, 6> orders{{{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
        for (const auto& order : orders) {
          std::array<int, 3> at{0, 0, 0};
          std::array<int32_t, 4> tet;
          tet[0] = corner(0, 0, 0);
          for (int k = 0; k < 3; ++k) {
            at[order[k]] = 1;
            tet[k + 1] = corner(at[0], at[1], at[2]);
          }
          addTet(tet);
        }
      }
    }
  addTetEdgesAndBoundary(mesh);
  // Mass lumped by volume: a quarter of each tet's share to each of its nodes.
  mesh.masses.assign(mesh.positions.size(), 0.0);
  double volume = 0.0;
  for (const auto& t : mesh.tetrahedra) {
    const auto& x = mesh.positions;
    const double v = (x[t[1]] - x[t[0]]).dot((x[t[2]] - x[t[0]]).cross(x[t[3]] - x[t[0]])) / 6.0;
    volume += v;
    for (int32_t n : t) mesh.masses[n] += v / 4.0;
  }
  for (double& m : mesh.masses) m *= totalMass / volume;
  return mesh;
}

std::vector<EdgeHinge> findEdgeHinges(const std::vector<std::array<int32_t, 3>>& triangles) {
  // For each directed edge (a, b) of a triangle, the opposite vertex. The triangle on the other
  // side of the edge holds it as (b, a).
  std::map<std::pair<int32_t, int32_t>, int32_t> opposite;
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) opposite[{t[k], t[(k + 1) % 3]}] = t[(k + 2) % 3];
  std::vector<EdgeHinge> hinges;
  for (const auto& [edge, left] : opposite) {
    if (edge.first > edge.second) continue;  // each undirected edge once
    auto other = opposite.find({edge.second, edge.first});
    if (other == opposite.end()) continue;  // boundary edge
    hinges.push_back({edge.first, edge.second, left, other->second});
  }
  return hinges;
}

}  // namespace tandem
