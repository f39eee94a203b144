// For tests: how far a point is outside a rigid body, as Tandem's collision detection measures it.
#pragma once

#include "bullet/bullet_world.h"
#include "collision/geometry.h"

#include <tandem/world.h>

namespace tandem::testing_support {

// The shape as Tandem's collision detection sees it (with a hull's planes, a mesh's grid).
inline geometry::CollisionShape collisionShape(const RigidShape& shape) {
  geometry::CollisionShape collision;
  collision.shape = shape;
  if (shape.type == ShapeType::ConvexHull) collision.planes = bullet::convexHullPlanes(shape.points);
  if (shape.type == ShapeType::TriangleMesh) collision.grid.build(shape.points, shape.triangles);
  if (shape.type == ShapeType::Compound)
    for (const std::vector<Vec3>& hull : shape.hulls) {
      collision.hullPlanesStart.push_back(static_cast<int32_t>(collision.planes.size()));
      for (const Eigen::Vector4d& plane : bullet::convexHullPlanes(hull)) collision.planes.push_back(plane);
    }
  return collision;
}

// Signed distance (m) from `point` to the body's surface: negative inside.
inline double signedDistance(const World& world, RigidBodyId body, const geometry::CollisionShape& shape,
                             const Vec3& point) {
  const Vec3 local = world.rigidOrientation(body).conjugate() * (point - world.rigidPosition(body));
  return geometry::distanceToShape(shape, local, 1.0).distance;
}

}  // namespace tandem::testing_support
