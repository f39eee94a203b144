// Rigid bodies from closed triangle meshes: a teapot, a mug, a part from a CAD program.
//
// The mesh is read (loadObjSurface), checked to be a closed, consistently outward-wound surface,
// and integrated (divergence theorem over its triangles) for the volume, centre of mass and
// inertia tensor of the uniform solid it bounds. The body's frame is the principal frame at the
// centre of mass, as Bullet wants it; the body collides as the convex hull of the mesh or as one
// convex hull per part (OBJ object or group, or connected piece), and is drawn as the mesh itself
// (RigidShape::visual), placed in that frame.
#pragma once

#include <tandem/export.h>
#include <tandem/limits.h>
#include <tandem/world.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tandem {

// A triangle surface with the part each triangle belongs to.
struct SurfaceMesh {
  std::vector<Vec3> positions;                    // m, the mesh's own frame
  std::vector<std::array<int32_t, 3>> triangles;  // counter-clockwise seen from outside
  std::vector<int32_t> triangleGroup;             // per triangle: an index into groupNames
  std::vector<std::string> groupNames;            // OBJ objects and groups ("o", "g"), in file order
};

// An OBJ surface with its objects and groups as parts (polygons are triangulated; one part,
// named "", when the file names none). A coordinate that is not a finite number, a face that
// refers to no vertex and a file past `limits` are errors naming the file (and the line).
TANDEM_API Result<SurfaceMesh> loadObjSurface(const std::string& path, const Limits& limits = {});

// What a closed surface bounds, for a solid of density 1 (kg/m³): multiply by a density.
struct MassProperties {
  double volume = 0.0;           // m³
  Vec3 centre = Vec3::Zero();    // centre of mass, m, in the mesh's frame
  Mat3 inertia = Mat3::Zero();   // m⁵ (kg·m² per kg/m³): about the centre, along the mesh's axes
  Vec3 principalMoments = Vec3::Zero();  // m⁵: inertia's eigenvalues, ascending
  // The principal axes as a rotation (columns: axes in the mesh's frame, right-handed) taking
  // the body's frame to the mesh's: inertia = axes · diag(principalMoments) · axesᵀ.
  Quat axes = Quat::Identity();
};

// Refuses a surface that does not bound a solid, naming `who` (the file) and what is wrong:
// a vertex that is not finite, an index out of range, an edge not shared by exactly two
// triangles or used twice the same way round (an open or badly wound surface), a volume that is
// not positive (wound inwards, or flat). Vertices at exactly the same position are taken as one
// (files split at texture seams stay closed).
TANDEM_API Status checkClosedSurface(const std::vector<Vec3>& positions,
                                     const std::vector<std::array<int32_t, 3>>& triangles, const std::string& who);

// The volume integrals of a closed surface (checkClosedSurface first: a surface it refuses is
// an error here too). Parts that overlap count twice, as separate solids would.
TANDEM_API Result<MassProperties> solidMassProperties(const std::vector<Vec3>& positions,
                                                      const std::vector<std::array<int32_t, 3>>& triangles,
                                                      const std::string& who);

// How a mesh body collides.
enum class MeshCollision {
  ConvexHull,    // one convex hull of every vertex
  HullPerGroup,  // a hull per OBJ object or group (each must be a closed surface itself)
  HullPerPiece,  // a hull per connected piece of the surface (each closed)
};

struct MeshBodyOptions {
  MeshCollision collision = MeshCollision::ConvexHull;
  // At most this many points per hull: a hull with more is simplified to the points furthest
  // out along evenly spread directions (a subset of its vertices, so it lies inside the full
  // hull). Fewer points make contacts cheaper, Bullet's and Tandem's. In [4, 4096].
  int maxHullVertices = 64;
  double scale = 1.0;  // the mesh is scaled by this (about its own origin) before anything else
};

// A rigid shape made from a closed mesh, and where its body sits in the mesh's frame.
struct MeshBody {
  RigidShape shape;  // convex hull or compound in the body's (principal) frame; visual: the mesh
  MassProperties massProperties;  // of the scaled mesh, per unit density, in the mesh's frame
  int hullCount = 0;              // convex hulls made (1 for MeshCollision::ConvexHull)

  // The body's frame: origin at the centre of mass, axes the principal axes, in the mesh's frame.
  Vec3 centre() const { return massProperties.centre; }
  Quat axes() const { return massProperties.axes; }
  // kg·m² principal moments for a body of this mass (uniform density).
  Vec3 inertia(double mass) const { return mass / massProperties.volume * massProperties.principalMoments; }
  // A point given in the mesh's frame, in the body's frame (anchors, grabs).
  Vec3 toBodyFrame(const Vec3& meshPoint) const { return axes().conjugate() * (meshPoint - centre()); }
  // A dynamic body of this mass whose mesh frame is placed at `position` and `orientation`:
  // shape, mass, inertia and the pose of its centre of mass filled in.
  RigidBodyDesc desc(const std::string& name, double mass, const Vec3& position,
                     const Quat& orientation = Quat::Identity()) const {
    RigidBodyDesc d;
    d.name = name;
    d.shape = shape;
    d.mass = mass;
    d.inertia = inertia(mass);
    d.position = position + orientation * centre();
    d.orientation = (orientation * axes()).normalized();
    return d;
  }
};

// Checks the mesh (each part that gets a hull must be closed on its own; the whole must be
// closed), integrates it and makes its hulls. `who` names the mesh (its file) in errors.
TANDEM_API Result<MeshBody> makeMeshBody(const SurfaceMesh& mesh, const MeshBodyOptions& options,
                                         const std::string& who);

}  // namespace tandem
