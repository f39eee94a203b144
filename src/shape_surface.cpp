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

}  // namespace

ShapeSurface shapeSurface(const RigidShape& shape, int segments) {
  segments = std::max(segments, 3);
  ShapeSurface surface;
  switch (shape.type) {
    case ShapeType::Box: addBox(surface, shape.halfExtents); break;
    case ShapeType::Sphere: addSphereLike(surface, shape.radius, 0.0, segments); break;
    case ShapeType::Capsule: addSphereLike(surface, shape.radius, shape.halfHeight, segments); break;
    case ShapeType::Cylinder: addCylinder(surface, shape.radius, shape.halfHeight, segments); break;
    case ShapeType::ConvexHull: addConvexHull(surface, shape.points); break;
    case ShapeType::TriangleMesh:
      for (const auto& t : shape.triangles)
        addFlatTriangle(surface, shape.points[t[0]], shape.points[t[1]], shape.points[t[2]]);
      break;
    case ShapeType::Plane: break;
  }
  return surface;
}

}  // namespace tandem
