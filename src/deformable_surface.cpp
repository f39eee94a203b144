#include <tandem/deformable_surface.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

namespace tandem {

DeformableSurface::DeformableSurface(const DeformableMesh& rest) : m_triangles(rest.triangles) {
  if (m_triangles.empty()) {
    m_tubeEdges = rest.edges;
    return;
  }
  std::map<std::pair<int32_t, int32_t>, int> faces;  // per undirected edge
  double length = 0.0;
  for (const auto& t : m_triangles)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = t[k], b = t[(k + 1) % 3];
      ++faces[{std::min(a, b), std::max(a, b)}];
      length += (rest.positions[a] - rest.positions[b]).norm();
    }
  for (const auto& [edge, count] : faces)
    if (count == 1) m_tubeEdges.push_back({edge.first, edge.second});
  const double meanEdge = length / (3.0 * static_cast<double>(m_triangles.size()));
  m_tubeRadius = std::clamp(0.12 * meanEdge, 0.0015, 0.006);
}

ShapeSurface DeformableSurface::build(std::span<const Vec3> x) const {
  ShapeSurface surface;
  build(x, surface);
  return surface;
}

void DeformableSurface::build(std::span<const Vec3> x, ShapeSurface& out) const {
  out.positions.clear();
  out.normals.clear();
  out.triangles.clear();
  if (!m_triangles.empty()) {  // smooth normals: each node's is the area-weighted sum of its faces'
    out.positions.assign(x.begin(), x.end());
    out.normals.assign(x.size(), Vec3::Zero());
    for (const auto& t : m_triangles) {
      const Vec3 n = (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]);
      for (int k = 0; k < 3; ++k) out.normals[t[k]] += n;
    }
    for (Vec3& n : out.normals) {
      const double length = n.norm();
      n = length > 0 ? Vec3(n / length) : Vec3::UnitY();
    }
    out.triangles = m_triangles;
  }
  for (const auto& e : m_tubeEdges) {  // an open tube of kTubeSides sides round each edge
    const Vec3 a = x[e[0]], b = x[e[1]];
    const Vec3 along = b - a;
    const Vec3 axis = along.norm() > 1e-12 ? Vec3(along.normalized()) : Vec3::UnitX();
    const Vec3 side = (std::abs(axis.y()) < 0.9 ? Vec3::UnitY() : Vec3::UnitX()).cross(axis).normalized();
    const Vec3 other = axis.cross(side);
    const auto first = static_cast<int32_t>(out.positions.size());
    for (int s = 0; s < kTubeSides; ++s) {
      const double angle = 2.0 * std::numbers::pi * s / kTubeSides;
      const Vec3 n = std::cos(angle) * side + std::sin(angle) * other;
      out.positions.push_back(a + m_tubeRadius * n);
      out.normals.push_back(n);
      out.positions.push_back(b + m_tubeRadius * n);
      out.normals.push_back(n);
    }
    for (int32_t s = 0; s < kTubeSides; ++s) {
      const int32_t next = (s + 1) % kTubeSides;
      out.triangles.push_back({first + 2 * s, first + 2 * next, first + 2 * next + 1});
      out.triangles.push_back({first + 2 * s, first + 2 * next + 1, first + 2 * s + 1});
    }
  }
}

}  // namespace tandem
