// Rigid shapes as triangle surfaces, for drawing them (and for anything else that wants a
// shape's outside as triangles). Planes are infinite and have no surface here.
#pragma once

#include <tandem/export.h>
#include <tandem/world.h>

#include <array>
#include <cstdint>
#include <vector>

namespace tandem {

// Vertices in the shape's frame with one normal each (sharp edges repeat their vertices, one
// per face), triangles counter-clockwise seen from outside.
struct ShapeSurface {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;
  std::vector<std::array<int32_t, 3>> triangles;
};

// `segments`: around a sphere, cylinder or capsule (at least 3). A shape with a visual mesh
// (RigidShape::visual) gives that mesh, with smooth normals split at creases sharper than 50°.
TANDEM_API ShapeSurface shapeSurface(const RigidShape& shape, int segments = 32);

}  // namespace tandem
