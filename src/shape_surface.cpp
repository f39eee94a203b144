// Triangle surfaces of rigid shapes: boxes face by face, round shapes by rings of segments,
// convex hulls by Bullet's hull computer, triangle meshes as they are.
#include <tandem/shape_surface.h>

#include <LinearMath/btConvexHullComputer.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace tandem {
namespace {

void addFlatTriangle(ShapeSurface& surface, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 normal = (b - a).cross(c - a).normalized();
  const auto first = static_cast<int32_t>(surface.positions.size());
  for (const Vec3& p : std::array<Vec3, 3>{a, b, c}) {
    surface.positions.push_back(p);
    surface.normals.push_back(normal);
  }
  surface.triangles.push_back({first, first + 1, first + 2});
}

void addBox(ShapeSurface& surface, const Vec3& half) {
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {-1.0, 1.0}) {
      Vec3 n = Vec3::Zero(), u = Vec3::Zero(), v = Vec3::Zero();
      n[axis] = sign;
      u[(axis + 1) % 3] = half[(axis + 1) % 3];
      v[(axis + 2) % 3] = half[(axis + 2) % 3] * sign;  // u × v along n
      const Vec3 centre = n.cwiseProduct(half);
      const auto first = static_cast<int32_t>(surface.positions.size());
      for (const Vec3& corner : std::array<Vec3, 4>{centre - u - v, centre + u - v, centre + u + v, centre - u + v}) {
        surface.positions.push_back(corner);
        surface.normals.push_back(n);
      }
      surface.triangles.push_back({first, first + 1, first + 2});
      surface.triangles.push_back({first, first + 2, first + 3});
    }
}

// A surface of revolution about y: `profile` gives (radius, y, normal's radial part, normal's
// y part) from the bottom pole or rim to the top; the rings are joined into quads.
struct ProfilePoint {
  double radius, y, normalRadial, normalY;
};
void addRevolved(ShapeSurface& surface, const std::vector<ProfilePoint>& profile, int segments) {
  const auto first = static_cast<int32_t>(surface.positions.size());
  for (const ProfilePoint& p : profile)
    for (int s = 0; s <= segments; ++s) {
      const double angle = 2.0 * std::numbers::pi * s / segments;
      const double c = std::cos(angle), si = std::sin(angle);
      surface.positions.emplace_back(p.radius * c, p.y, -p.radius * si);
      surface.normals.push_back(Vec3(p.normalRadial * c, p.normalY, -p.normalRadial * si).normalized());
    }
  const int ring = segments + 1;
  double radiusScale = 0.0;  // a ring this much smaller than the widest is a pole
  for (const ProfilePoint& p : profile) radiusScale = std::max(radiusScale, p.radius);
  for (size_t r = 0; r + 1 < profile.size(); ++r)
    for (int s = 0; s < segments; ++s) {
      const int32_t a = first + static_cast<int32_t>(r) * ring + s, b = a + 1, c = a + ring, d = c + 1;
      if (profile[r].radius > 1e-12 * radiusScale) surface.triangles.push_back({a, b, d});
      if (profile[r + 1].radius > 1e-12 * radiusScale) surface.triangles.push_back({a, d, c});
    }
}

void addSphereLike(ShapeSurface& surface, double radius, double halfHeight, int segments) {
  std::vector<ProfilePoint> profile;
  const int quarter = std::max(2, segments / 4);
  for (int hemisphere = 0; hemisphere < 2; ++hemisphere)
    for (int i = 0; i <= quarter; ++i) {
      if (hemisphere == 1 && i == 0 && halfHeight == 0.0) continue;  // a sphere's equator once
      const double polar = std::numbers::pi / 2 * (hemisphere == 0 ? i : quarter + i) / quarter;  // from the bottom
      const double ny = -std::cos(polar), nr = std::sin(polar);
      const double centre = hemisphere == 0 ? -halfHeight : halfHeight;
      profile.push_back({radius * nr, centre + radius * ny, nr, ny});
    }
  addRevolved(surface, profile, segments);
}

void addCylinder(ShapeSurface& surface, double radius, double halfHeight, int segments) {
  addRevolved(surface, {{0, -halfHeight, 0, -1}, {radius, -halfHeight, 0, -1}}, segments);
  addRevolved(surface, {{radius, -halfHeight, 1, 0}, {radius, halfHeight, 1, 0}}, segments);
  addRevolved(surface, {{radius, halfHeight, 0, 1}, {0, halfHeight, 0, 1}}, segments);
}

void addConvexHull(ShapeSurface& surface, const std::vector<Vec3>& points) {
  std::vector<double> coordinates;
  for (const Vec3& p : points) coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});
  btConvexHullComputer hull;
  hull.compute(coordinates.data(), 3 * sizeof(double), static_cast<int>(points.size()), 0.0, 0.0);
  auto vertex = [&](int i) { return Vec3(hull.vertices[i].x(), hull.vertices[i].y(), hull.vertices[i].z()); };
  for (int f = 0; f < hull.faces.size(); ++f) {
    const btConvexHullComputer::Edge* start = &hull.edges[hull.faces[f]];
    const Vec3 origin = vertex(start->getSourceVertex());
    const btConvexHullComputer::Edge* edge = start->getNextEdgeOfFace();
    while (edge->getTargetVertex() != start->getSourceVertex()) {  // a fan over the face
      addFlatTriangle(surface, origin, vertex(edge->getSourceVertex()), vertex(edge->getTargetVertex()));
      edge = edge->getNextEdgeOfFace();
    }
  }
}

// A visual mesh with smooth normals: each corner's normal is the mean of the normals of the
// faces round its vertex that turn less than kCreaseDegrees from its own face, each weighted by
// its angle at the vertex (so the result does not depend on how a polygon was cut into
// triangles); vertices are split only where the normals differ (a lid's rim, a spout's end cap).
void addVisualMesh(ShapeSurface& surface, const VisualMesh& mesh) {
  constexpr double kCreaseDegrees = 50.0;
  const double creaseCosine = std::cos(kCreaseDegrees * std::numbers::pi / 180.0);
  const auto& x = mesh.positions;
  std::vector<Vec3> faceNormal;
  std::vector<std::vector<std::pair<int32_t, double>>> facesOf(x.size());  // (face, its angle at the vertex)
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& f = mesh.triangles[t];
    const Vec3 normal = (x[f[1]] - x[f[0]]).cross(x[f[2]] - x[f[0]]);
    faceNormal.push_back(normal.norm() > 0 ? Vec3(normal.normalized()) : Vec3::Zero());
    for (int k = 0; k < 3; ++k) {
      const Vec3 u = x[f[(k + 1) % 3]] - x[f[k]], v = x[f[(k + 2) % 3]] - x[f[k]];
      facesOf[f[k]].emplace_back(static_cast<int32_t>(t), std::atan2(u.cross(v).norm(), u.dot(v)));
    }
  }
  // Per vertex, the normals made so far and their output indices: corners with the same normal
  // share one output vertex.
  std::vector<std::vector<std::pair<Vec3, int32_t>>> made(x.size());
  auto next = static_cast<int32_t>(surface.positions.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    std::array<int32_t, 3> corner{};
    const Vec3& own = faceNormal[t];
    for (int k = 0; k < 3; ++k) {
      const int32_t v = mesh.triangles[t][k];
      Vec3 sum = Vec3::Zero();
      for (const auto& [other, angle] : facesOf[v])
        if (faceNormal[other].dot(own) >= creaseCosine) sum += angle * faceNormal[other];
      const Vec3 normal = sum.norm() > 0 ? Vec3(sum.normalized()) : own;
      int32_t index = -1;
      for (const auto& [existing, at] : made[v])
        if (existing == normal) index = at;
      if (index < 0) {
        index = next++;
        made[v].emplace_back(normal, index);
        surface.positions.push_back(x[v]);
        surface.normals.push_back(normal);
      }
      corner[k] = index;
    }
    surface.triangles.push_back(corner);
  }
}

}  // namespace

ShapeSurface shapeSurface(const RigidShape& shape, int segments) {
  segments = std::max(segments, 3);
  ShapeSurface surface;
  if (!shape.visual.empty()) {
    addVisualMesh(surface, shape.visual);
    return surface;
  }
  switch (shape.type) {
    case ShapeType::Box: addBox(surface, shape.halfExtents); break;
    case ShapeType::Sphere: addSphereLike(surface, shape.radius, 0.0, segments); break;
    case ShapeType::Capsule: addSphereLike(surface, shape.radius, shape.halfHeight, segments); break;
    case ShapeType::Cylinder: addCylinder(surface, shape.radius, shape.halfHeight, segments); break;
    case ShapeType::ConvexHull: addConvexHull(surface, shape.points); break;
    case ShapeType::Compound:
      for (const std::vector<Vec3>& hull : shape.hulls) addConvexHull(surface, hull);
      break;
    case ShapeType::TriangleMesh:
      for (const auto& t : shape.triangles)
        addFlatTriangle(surface, shape.points[t[0]], shape.points[t[1]], shape.points[t[2]]);
      break;
    case ShapeType::Plane: break;
  }
  return surface;
}

}  // namespace tandem
