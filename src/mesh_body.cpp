// Rigid bodies from closed meshes: closure and winding checks, volume integrals, principal
// frames and convex hulls (include/tandem/mesh_body.h).
//
// Mass properties by the divergence theorem: each triangle (a, b, c), wound outwards, spans a
// tetrahedron with the reference point r; summed with their signs these tile the solid (what is
// outside cancels). For the tetrahedron with corners 0, a, b, c (coordinates relative to r):
//   V = det[a b c] / 6,   ∫ x dV = V (a + b + c) / 4,
//   C = ∫ x xᵀ dV = det[a b c] / 120 · (a aᵀ + b bᵀ + c cᵀ + s sᵀ),  s = a + b + c
// (the canonical tetrahedron's second moments, 1/120 · (I + 1 1ᵀ), mapped by A = [a b c]).
// About the centre of mass m: C_m = C − V d dᵀ with d = m − r, and the inertia tensor is
// J = tr(C_m) I − C_m. Its eigenvectors are the principal axes.
#include <tandem/mesh_body.h>

#include "bullet/bullet_world.h"
#include "format.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <numeric>

namespace tandem {
namespace {

std::string vertexName(int32_t index) { return "vertex " + std::to_string(index + 1); }

// For each vertex, the first vertex at exactly the same position (so split seams stay closed).
std::vector<int32_t> weldedVertices(const std::vector<Vec3>& positions) {
  std::vector<int32_t> order(positions.size());
  std::iota(order.begin(), order.end(), 0);
  auto less = [&](int32_t a, int32_t b) {
    const Vec3 &p = positions[a], &q = positions[b];
    if (p.x() != q.x()) return p.x() < q.x();
    if (p.y() != q.y()) return p.y() < q.y();
    if (p.z() != q.z()) return p.z() < q.z();
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<int32_t> welded(positions.size());
  for (size_t i = 0; i < order.size(); ++i)
    welded[order[i]] = i > 0 && positions[order[i]] == positions[order[i - 1]] ? welded[order[i - 1]] : order[i];
  return welded;
}

double signedVolume(const std::vector<Vec3>& x, const std::vector<std::array<int32_t, 3>>& triangles, const Vec3& r) {
  double sixVolume = 0.0;
  for (const auto& t : triangles) sixVolume += (x[t[0]] - r).dot((x[t[1]] - r).cross(x[t[2]] - r));
  return sixVolume / 6.0;
}

Vec3 boundsCentre(const std::vector<Vec3>& x, const std::vector<std::array<int32_t, 3>>& triangles, double& diagonal) {
  Eigen::AlignedBox3d box;
  for (const auto& t : triangles)
    for (int32_t v : t) box.extend(x[v]);
  diagonal = box.diagonal().norm();
  return box.center();
}

// The rotation whose columns are the eigenvectors (signs and order free), chosen nearest the
// identity: the body's axes stay as close to the mesh's as its inertia allows.
Mat3 nearestPrincipalAxes(const Mat3& eigenvectors, Vec3& moments) {
  Mat3 best = eigenvectors;
  Vec3 bestMoments = moments;
  double bestTrace = -INFINITY;
  std::array<int, 3> order{0, 1, 2};
  do {
    for (int signs = 0; signs < 8; ++signs) {
      Mat3 axes;
      for (int k = 0; k < 3; ++k) axes.col(k) = eigenvectors.col(order[k]) * ((signs >> k) & 1 ? -1.0 : 1.0);
      if (axes.determinant() < 0) continue;
      if (axes.trace() > bestTrace + 1e-12) {
        bestTrace = axes.trace();
        best = axes;
        bestMoments = Vec3(moments[order[0]], moments[order[1]], moments[order[2]]);
      }
    }
  } while (std::next_permutation(order.begin(), order.end()));
  moments = bestMoments;
  return best;
}

// Evenly spread unit directions (a Fibonacci lattice on the sphere).
Vec3 spreadDirection(int i, int count) {
  const double y = 1.0 - 2.0 * (i + 0.5) / count;
  const double radius = std::sqrt(std::max(0.0, 1.0 - y * y));
  const double angle = i * std::numbers::pi * (3.0 - std::sqrt(5.0));
  return {radius * std::cos(angle), y, radius * std::sin(angle)};
}

// At most `maxPoints` of the hull's vertices: those furthest out along spread directions, with
// as many directions as keep the count within the bound.
std::vector<Vec3> simplifiedHull(const std::vector<Vec3>& vertices, int maxPoints) {
  if (static_cast<int>(vertices.size()) <= maxPoints) return vertices;
  auto supports = [&](int directions) {
    std::vector<int32_t> chosen;
    for (int i = 0; i < directions; ++i) {
      const Vec3 d = spreadDirection(i, directions);
      int32_t best = 0;
      for (int32_t v = 1; v < static_cast<int32_t>(vertices.size()); ++v)
        if (vertices[v].dot(d) > vertices[best].dot(d)) best = v;
      chosen.push_back(best);
    }
    std::sort(chosen.begin(), chosen.end());
    chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
    return chosen;
  };
  std::vector<int32_t> kept = supports(maxPoints);
  for (int directions = maxPoints + maxPoints / 4 + 1; directions <= 16 * maxPoints; directions += directions / 4 + 1) {
    std::vector<int32_t> more = supports(directions);
    if (static_cast<int>(more.size()) > maxPoints) break;
    kept = std::move(more);
  }
  std::vector<Vec3> points;
  for (int32_t v : kept) points.push_back(vertices[v]);
  return points;
}

// The points of `points` that are corners of their convex hull, exactly as given. Bullet's hull
// computer works in quantised coordinates: the corners it returns are off by up to about 3e-4 of
// the points' extent (measured on a sphere's points), so each is traced to the nearest point.
std::vector<Vec3> hullCorners(const std::vector<Vec3>& points) {
  const std::vector<Vec3> approximate = bullet::convexHullVertices(points);
  std::vector<int32_t> byX(points.size());
  std::iota(byX.begin(), byX.end(), 0);
  std::sort(byX.begin(), byX.end(), [&](int32_t a, int32_t b) { return points[a].x() < points[b].x(); });
  Eigen::AlignedBox3d box;
  for (const Vec3& p : points) box.extend(p);
  const double window = 1e-2 * box.diagonal().norm();
  std::vector<int32_t> chosen;
  for (const Vec3& corner : approximate) {
    auto first = std::lower_bound(byX.begin(), byX.end(), corner.x() - window,
                                  [&](int32_t i, double x) { return points[i].x() < x; });
    auto last = std::upper_bound(byX.begin(), byX.end(), corner.x() + window,
                                 [&](double x, int32_t i) { return x < points[i].x(); });
    if (first == last) first = byX.begin(), last = byX.end();
    int32_t nearest = *first;
    for (auto it = first; it != last; ++it)
      if ((points[*it] - corner).squaredNorm() < (points[nearest] - corner).squaredNorm()) nearest = *it;
    chosen.push_back(nearest);
  }
  std::sort(chosen.begin(), chosen.end());
  chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
  std::vector<Vec3> corners;
  for (int32_t i : chosen) corners.push_back(points[i]);
  return corners;
}

bool spansVolume(const std::vector<Vec3>& points) {
  if (points.size() < 4) return false;
  Eigen::AlignedBox3d box;
  for (const Vec3& p : points) box.extend(p);
  const double scale = box.diagonal().norm();
  for (size_t i = 2; i < points.size(); ++i)
    for (size_t j = i + 1; j < points.size(); ++j)
      if (std::abs((points[1] - points[0]).dot((points[i] - points[0]).cross(points[j] - points[0]))) >
          1e-9 * scale * scale * scale)
        return true;
  return false;
}

}  // namespace

Status checkClosedSurface(const std::vector<Vec3>& positions, const std::vector<std::array<int32_t, 3>>& triangles,
                          const std::string& who) {
  if (triangles.empty()) return Error{who + ": the surface has no triangles"};
  const auto count = static_cast<int32_t>(positions.size());
  for (size_t t = 0; t < triangles.size(); ++t)
    for (int32_t v : triangles[t]) {
      if (v < 0 || v >= count)
        return Error{who + ": triangle " + std::to_string(t + 1) + " refers to vertex " + std::to_string(v + 1) +
                     ", which does not exist (there are " + std::to_string(count) + ")"};
      if (!positions[v].allFinite()) return Error{who + ": " + vertexName(v) + " is not a finite point"};
    }
  const std::vector<int32_t> welded = weldedVertices(positions);
  struct DirectedEdge {
    int32_t from, to, triangle;
    bool operator<(const DirectedEdge& o) const {
      return from != o.from ? from < o.from : to != o.to ? to < o.to : triangle < o.triangle;
    }
  };
  std::vector<DirectedEdge> edges;
  edges.reserve(3 * triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t) {
    const std::array<int32_t, 3> v{welded[triangles[t][0]], welded[triangles[t][1]], welded[triangles[t][2]]};
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0])
      return Error{who + ": triangle " + std::to_string(t + 1) + " has two corners at the same point"};
    for (int k = 0; k < 3; ++k) edges.push_back({v[k], v[(k + 1) % 3], static_cast<int32_t>(t)});
  }
  std::sort(edges.begin(), edges.end());
  for (size_t e = 0; e < edges.size(); ++e) {
    const DirectedEdge& edge = edges[e];
    const std::string between = "the edge from " + vertexName(edge.from) + " to " + vertexName(edge.to);
    if (e + 1 < edges.size() && edges[e + 1].from == edge.from && edges[e + 1].to == edge.to)
      return Error{who + ": " + between + " is used the same way round by triangles " +
                   std::to_string(edge.triangle + 1) + " and " + std::to_string(edges[e + 1].triangle + 1) +
                   ": the faces disagree on which side is outside, or more than two faces meet there (the "
                   "surface must be closed and wound counter-clockwise seen from outside)"};
    const auto reverse = std::lower_bound(edges.begin(), edges.end(), DirectedEdge{edge.to, edge.from, -1});
    if (reverse == edges.end() || reverse->from != edge.to || reverse->to != edge.from)
      return Error{who + ": the surface is open: " + between + " belongs to triangle " +
                   std::to_string(edge.triangle + 1) + " only (every edge must be shared by two triangles)"};
  }
  double diagonal = 0.0;
  const Vec3 reference = boundsCentre(positions, triangles, diagonal);
  const double volume = signedVolume(positions, triangles, reference);
  if (!(std::abs(volume) > 1e-12 * diagonal * diagonal * diagonal))
    return Error{who + ": the surface encloses no volume (" + formatNumber(volume) + " m³): it is flat"};
  if (volume < 0)
    return Error{who + ": the surface is wound inwards (clockwise seen from outside): its volume comes out as " +
                 formatNumber(volume) + " m³; turn its faces round"};
  return {};
}

Result<MassProperties> solidMassProperties(const std::vector<Vec3>& positions,
                                           const std::vector<std::array<int32_t, 3>>& triangles, const std::string& who) {
  if (Status s = checkClosedSurface(positions, triangles, who); !s) return Error{s.message()};
  double diagonal = 0.0;
  const Vec3 r = boundsCentre(positions, triangles, diagonal);
  double volume = 0.0;
  Vec3 first = Vec3::Zero();
  Mat3 second = Mat3::Zero();
  for (const auto& t : triangles) {
    const Vec3 a = positions[t[0]] - r, b = positions[t[1]] - r, c = positions[t[2]] - r;
    const double determinant = a.dot(b.cross(c));
    const Vec3 s = a + b + c;
    volume += determinant / 6.0;
    first += determinant / 24.0 * s;
    second += determinant / 120.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  MassProperties out;
  out.volume = volume;
  const Vec3 d = first / volume;
  out.centre = r + d;
  const Mat3 aboutCentre = second - volume * d * d.transpose();
  out.inertia = aboutCentre.trace() * Mat3::Identity() - aboutCentre;
  out.inertia = 0.5 * (out.inertia + out.inertia.transpose());
  const Eigen::SelfAdjointEigenSolver<Mat3> solver(out.inertia);
  Vec3 moments = solver.eigenvalues();
  const Mat3 axes = nearestPrincipalAxes(solver.eigenvectors(), moments);
  out.principalMoments = moments;
  out.axes = Quat(axes).normalized();
  if (!(moments.minCoeff() > 0) || !out.centre.allFinite())
    return Error{who + ": the solid's inertia is not positive (principal moments " + formatNumber(moments[0]) + ", " +
                 formatNumber(moments[1]) + ", " + formatNumber(moments[2]) + " m⁵)"};
  return out;
}

Result<MeshBody> makeMeshBody(const SurfaceMesh& mesh, const MeshBodyOptions& options, const std::string& who) {
  if (options.maxHullVertices < 4 || options.maxHullVertices > 4096)
    return Error{who + ": max hull vertices must be in [4, 4096], got " + std::to_string(options.maxHullVertices)};
  if (!(std::isfinite(options.scale) && options.scale > 0))
    return Error{who + ": scale must be a positive number, got " + formatNumber(options.scale)};
  if (mesh.triangleGroup.size() != mesh.triangles.size() && !mesh.triangleGroup.empty())
    return Error{who + ": triangleGroup must give a group for every triangle (or be empty)"};
  std::vector<Vec3> positions = mesh.positions;
  for (Vec3& p : positions) p *= options.scale;
  Result<MassProperties> properties = solidMassProperties(positions, mesh.triangles, who);
  if (!properties) return Error{properties.message()};

  // The triangles of each part that gets a hull.
  std::vector<std::vector<std::array<int32_t, 3>>> parts;
  std::vector<std::string> partNames;
  switch (options.collision) {
    case MeshCollision::ConvexHull:
      parts.push_back(mesh.triangles);
      partNames.push_back("");
      break;
    case MeshCollision::HullPerGroup: {
      const size_t groups = mesh.groupNames.empty() ? 1 : mesh.groupNames.size();
      parts.resize(groups);
      for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const int32_t group = mesh.triangleGroup.empty() ? 0 : mesh.triangleGroup[t];
        if (group < 0 || static_cast<size_t>(group) >= groups)
          return Error{who + ": triangle " + std::to_string(t + 1) + " is in group " + std::to_string(group) +
                       ", which does not exist"};
        parts[group].push_back(mesh.triangles[t]);
      }
      for (size_t g = 0; g < groups; ++g)
        partNames.push_back(mesh.groupNames.empty() ? std::string("") : mesh.groupNames[g]);
      break;
    }
    case MeshCollision::HullPerPiece: {
      const std::vector<int32_t> welded = weldedVertices(positions);
      std::vector<int32_t> parent(positions.size());
      std::iota(parent.begin(), parent.end(), 0);
      auto root = [&](int32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
      };
      for (const auto& t : mesh.triangles)
        for (int k = 1; k < 3; ++k) parent[root(welded[t[k]])] = root(welded[t[0]]);
      std::vector<int32_t> pieceOfRoot(positions.size(), -1);
      for (const auto& t : mesh.triangles) {
        int32_t& piece = pieceOfRoot[root(welded[t[0]])];
        if (piece < 0) {
          piece = static_cast<int32_t>(parts.size());
          parts.emplace_back();
          partNames.push_back("piece " + std::to_string(piece + 1));
        }
        parts[piece].push_back(t);
      }
      break;
    }
  }

  const Mat3 toBody = properties->axes.conjugate().toRotationMatrix();
  MeshBody body;
  body.massProperties = *properties;
  std::vector<std::vector<Vec3>> hulls;
  for (size_t p = 0; p < parts.size(); ++p) {
    if (parts[p].empty()) continue;  // a group named but given no faces
    const std::string part = partNames[p].empty() ? who : who + ": part '" + partNames[p] + "'";
    if (options.collision != MeshCollision::ConvexHull)
      if (Status s = checkClosedSurface(positions, parts[p], part); !s) return Error{s.message()};
    std::vector<char> used(positions.size(), 0);
    std::vector<Vec3> points;
    for (const auto& t : parts[p])
      for (int32_t v : t)
        if (!used[v]) {
          used[v] = 1;
          points.push_back(toBody * (positions[v] - properties->centre));
        }
    std::vector<Vec3> hull = simplifiedHull(hullCorners(points), options.maxHullVertices);
    if (!spansVolume(hull)) return Error{part + ": its convex hull is flat (no volume)"};
    hulls.push_back(std::move(hull));
  }
  body.hullCount = static_cast<int>(hulls.size());
  body.shape = hulls.size() == 1 ? RigidShape::convexHull(std::move(hulls[0])) : RigidShape::compound(std::move(hulls));
  for (const Vec3& p : positions) body.shape.visual.positions.push_back(toBody * (p - properties->centre));
  body.shape.visual.triangles = mesh.triangles;
  return body;
}

}  // namespace tandem
