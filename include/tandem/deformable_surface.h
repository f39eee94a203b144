// Deformable bodies as shaded surfaces, for drawing and exporting them: a surface mesh with
// smooth normals and its open rims as thin tubes (so a strip or cloth seen edge-on still shows),
// a rope (edges only) as a tube round each edge. The vertex count and the triangles depend on
// the mesh only, never on where its nodes are: frames of one body share them (morph targets,
// buffers sized once).
#pragma once

#include <tandem/mesh.h>
#include <tandem/shape_surface.h>

#include <span>
#include <vector>

namespace tandem {

class DeformableSurface {
 public:
  static constexpr int kTubeSides = 8;
  static constexpr double kRopeRadius = 0.01;  // m

  // Finds the rims (edges of one triangle only) of the rest mesh once.
  explicit DeformableSurface(const DeformableMesh& rest);

  // The surface at node positions `x` (as many as the rest mesh has), into `out`.
  void build(std::span<const Vec3> x, ShapeSurface& out) const;
  ShapeSurface build(std::span<const Vec3> x) const;

  // m: of the tubes round a rope's edges, or round a surface's rims (0.12 of its mean edge
  // length, between 1.5 and 6 mm).
  double tubeRadius() const { return m_tubeRadius; }
  bool isRope() const { return m_triangles.empty(); }

 private:
  std::vector<std::array<int32_t, 3>> m_triangles;
  std::vector<std::array<int32_t, 2>> m_tubeEdges;  // every edge of a rope; a surface's rims
  double m_tubeRadius = kRopeRadius;
};

}  // namespace tandem
