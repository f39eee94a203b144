// Closest-point queries for collision detection: point–triangle, segment–segment,
// segment–triangle, and signed distances from a point to Tandem's rigid shapes.
#pragma once

#include <tandem/world.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

namespace tandem::geometry {

// Barycentric weights (wa, wb, wc) of the point of triangle abc closest to p
// (Ericson, Real-Time Collision Detection, §5.1.5).
inline std::array<double, 3> closestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denominator = 1.0 / (va + vb + vc);
  const double v = vb * denominator, w = vc * denominator;
  return {1 - v - w, v, w};
}

// Parameters (s, t) in [0, 1] of the closest points p0 + s (p1 − p0) and q0 + t (q1 − q0).
inline std::array<double, 2> closestOnSegments(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0, t = 0;
  if (a <= 1e-24 && e <= 1e-24) return {0, 0};
  if (a <= 1e-24) return {0, std::clamp(f / e, 0.0, 1.0)};
  const double c = d1.dot(r);
  if (e <= 1e-24) return {std::clamp(-c / a, 0.0, 1.0), 0};
  const double b = d1.dot(d2), denominator = a * e - b * b;
  s = denominator > 1e-24 ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
  t = (b * s + f) / e;
  if (t < 0) {
    t = 0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1) {
    t = 1;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  return {s, t};
}

// The closest pair between segment p0p1 and triangle abc: the parameter on the segment and
// the triangle's barycentric weights. Candidates: the segment's ends against the face, the
// segment crossing the face, and the segment against each edge.
struct SegmentTriangle {
  double s;
  std::array<double, 3> weights;
  double distance;
};
inline SegmentTriangle closestSegmentTriangle(const Vec3& p0, const Vec3& p1, const Vec3& a, const Vec3& b,
                                              const Vec3& c) {
  const std::array<Vec3, 3> corner{a, b, c};
  auto point = [&](const std::array<double, 3>& w) { return w[0] * a + w[1] * b + w[2] * c; };
  SegmentTriangle best{0, {1, 0, 0}, 1e300};
  auto consider = [&](double s, const std::array<double, 3>& w) {
    const double distance = (p0 + s * (p1 - p0) - point(w)).norm();
    if (distance < best.distance) best = {s, w, distance};
  };
  consider(0, closestOnTriangle(p0, a, b, c));
  consider(1, closestOnTriangle(p1, a, b, c));
  const Vec3 normal = (b - a).cross(c - a);
  const double h0 = normal.dot(p0 - a), h1 = normal.dot(p1 - a);
  if (h0 * h1 < 0) {  // the segment crosses the triangle's plane
    const double s = h0 / (h0 - h1);
    consider(s, closestOnTriangle(p0 + s * (p1 - p0), a, b, c));
  }
  for (int e = 0; e < 3; ++e) {
    const auto [s, t] = closestOnSegments(p0, p1, corner[e], corner[(e + 1) % 3]);
    std::array<double, 3> w{0, 0, 0};
    w[e] = 1 - t;
    w[(e + 1) % 3] = t;
    consider(s, w);
  }
  return best;
}

// Where the ray o + t d (t ≥ 0) crosses triangle abc, from either side (Möller and Trumbore
// 1997): t and the barycentric weights, or nothing when it misses or runs parallel.
struct RayTriangle {
  double t;
  std::array<double, 3> weights;
};
inline std::optional<RayTriangle> intersectRayTriangle(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b,
                                                       const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a;
  const Vec3 p = d.cross(ac);
  const double determinant = ab.dot(p);
  if (std::abs(determinant) < 1e-14 * ab.norm() * ac.norm() * d.norm()) return std::nullopt;
  const double inverse = 1.0 / determinant;
  const Vec3 ao = o - a;
  const double u = ao.dot(p) * inverse;
  if (u < 0 || u > 1) return std::nullopt;
  const Vec3 q = ao.cross(ab);
  const double v = d.dot(q) * inverse;
  if (v < 0 || u + v > 1) return std::nullopt;
  const double t = ac.dot(q) * inverse;
  if (t < 0) return std::nullopt;
  return RayTriangle{t, {1 - u - v, u, v}};
}

// Distance from a point to a rigid shape's surface (negative inside), the outward unit normal
// there and the surface point, all in the shape's frame.
struct ShapeDistance {
  double distance;
  Vec3 normal;
  Vec3 surfacePoint;
};

inline ShapeDistance distanceToShape(const RigidShape& shape, const Vec3& q);

// A sorted spatial hash: items inserted into every cell their box covers, looked up by point.
//
// Cell coordinates are 64-bit and computed in double before any conversion: a coordinate / cell
// ratio is clamped to ±kCellLimit (where a double still resolves single cells exactly; 2^52 of
// them is 4.5e12 km at 1 mm cells), so positions far from the origin (a cloth at z = 2^31 m)
// hash into distinct cells as they do near it, and nothing converts a value out of int range.
// A non-finite coordinate (NaN, ±inf) goes to one cell of its own (kNonFiniteCell), away from
// every finite position. Boxes covering more than kMaxCellsPerBox cells (only absurd sizes do)
// are kept in a list every lookup visits; a lookup covering more cells than the hash has entries
// visits every entry. Either way every item that could be in reach is visited, in bounded time.
struct SpatialHash {
  using Cell = Eigen::Matrix<int64_t, 3, 1>;
  static constexpr double kCellLimit = 4503599627370496.0;  // 2^52
  static constexpr int64_t kNonFiniteCell = (int64_t{1} << 53) + 1;
  static constexpr int64_t kMaxCellsPerBox = 4096;

  double cell = 1.0;
  std::vector<std::pair<uint64_t, int32_t>> entries;  // (cell hash, item), sorted once filled
  std::vector<int32_t> everywhere;                     // items whose box covers too many cells

  static int64_t cellIndex(double coordinate, double cellSize) {
    const double scaled = std::floor(coordinate / cellSize);
    if (std::isnan(scaled)) return kNonFiniteCell;
    return static_cast<int64_t>(std::clamp(scaled, -kCellLimit, kCellLimit));
  }
  Cell cellOf(const Vec3& p) const { return Cell(cellIndex(p.x(), cell), cellIndex(p.y(), cell), cellIndex(p.z(), cell)); }
  static uint64_t hash(const Cell& c) {
    return static_cast<uint64_t>(c.x()) * 73856093ull ^ static_cast<uint64_t>(c.y()) * 19349663ull ^
           static_cast<uint64_t>(c.z()) * 83492791ull;
  }
  // Cells in the box from..to, or -1 when more than kMaxCellsPerBox (or a side is non-finite).
  static int64_t cellsIn(const Cell& from, const Cell& to) {
    int64_t cells = 1;
    for (int k = 0; k < 3; ++k) {
      if ((from[k] == kNonFiniteCell) != (to[k] == kNonFiniteCell)) return -1;
      const int64_t side = to[k] - from[k] + 1;  // at most 2^53 + 2: no overflow
      if (side <= 0) return 0;
      if (side > kMaxCellsPerBox || cells * side > kMaxCellsPerBox) return -1;
      cells *= side;
    }
    return cells;
  }
  void insert(const Vec3& low, const Vec3& high, int32_t item) {
    const Cell from = cellOf(low), to = cellOf(high);
    if (cellsIn(from, to) < 0) {
      everywhere.push_back(item);
      return;
    }
    for (int64_t x = from.x(); x <= to.x(); ++x)
      for (int64_t y = from.y(); y <= to.y(); ++y)
        for (int64_t z = from.z(); z <= to.z(); ++z) entries.emplace_back(hash(Cell(x, y, z)), item);
  }
  void sort() { std::sort(entries.begin(), entries.end()); }
  // Every item in the cells within `reach` of p (an item may come more than once).
  template <class Visit>
  void visit(const Vec3& p, double reach, Visit&& visitItem) const {
    for (int32_t item : everywhere) visitItem(item);
    const Cell from = cellOf(p - Vec3::Constant(reach)), to = cellOf(p + Vec3::Constant(reach));
    const int64_t cells = cellsIn(from, to);
    if (cells < 0 || cells > static_cast<int64_t>(entries.size())) {
      for (const auto& entry : entries) visitItem(entry.second);
      return;
    }
    for (int64_t x = from.x(); x <= to.x(); ++x)
      for (int64_t y = from.y(); y <= to.y(); ++y)
        for (int64_t z = from.z(); z <= to.z(); ++z) {
          const uint64_t key = hash(Cell(x, y, z));
          for (auto it = std::lower_bound(entries.begin(), entries.end(), std::make_pair(key, INT32_MIN));
               it != entries.end() && it->first == key; ++it)
            visitItem(it->second);
        }
  }
};

// A static triangle mesh's triangles in a spatial hash (body frame), built once, with each
// triangle's plane (unit normal n and n·a; zero for a degenerate triangle): a point's distance to
// the plane is a lower bound on its distance to the triangle, which lets a query skip the
// triangles that cannot be nearer than the nearest found.
struct TriangleGrid : SpatialHash {
  std::vector<Eigen::Vector4d> planes;
  void build(const std::vector<Vec3>& vertices, const std::vector<std::array<int32_t, 3>>& triangles) {
    planes.clear();
    for (const auto& t : triangles) {
      const Vec3 normal = (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]);
      const double length = normal.norm();
      const Vec3 n = length > 0.0 ? Vec3(normal / length) : Vec3::Zero();
      planes.emplace_back(n.x(), n.y(), n.z(), n.dot(vertices[t[0]]));
    }
    double longest = 1e-3;
    for (const auto& t : triangles)
      for (int k = 0; k < 3; ++k) longest = std::max(longest, (vertices[t[(k + 1) % 3]] - vertices[t[k]]).norm());
    cell = longest;
    for (size_t i = 0; i < triangles.size(); ++i) {
      const auto& t = triangles[i];
      insert(vertices[t[0]].cwiseMin(vertices[t[1]]).cwiseMin(vertices[t[2]]),
             vertices[t[0]].cwiseMax(vertices[t[1]]).cwiseMax(vertices[t[2]]), static_cast<int32_t>(i));
    }
    sort();
  }
};

// A rigid shape with what collision detection derives from it once: a convex hull's face
// planes (n, d: n·x = d, n outward), a compound's planes hull after hull (hull h's from
// hullPlanesStart[h]), a triangle mesh's grid.
struct CollisionShape {
  RigidShape shape;
  std::vector<Eigen::Vector4d> planes;
  std::vector<int32_t> hullPlanesStart;
  TriangleGrid grid;
};

// The deepest of the planes [first, last): a convex hull's signed distance. Exact inside and over
// faces; outside near an edge or a corner it is less than the true distance, which only makes
// contacts start a little early.
inline ShapeDistance distanceToHull(const std::vector<Eigen::Vector4d>& planes, size_t first, size_t last, const Vec3& q) {
  double distance = -INFINITY;
  Vec3 normal = Vec3::UnitY();
  for (size_t p = first; p < last; ++p) {
    const Eigen::Vector4d& plane = planes[p];
    const double d = plane.head<3>().dot(q) - plane[3];
    if (d > distance) {
      distance = d;
      normal = plane.head<3>();
    }
  }
  return {distance, normal, q - distance * normal};
}

// `reach`: how far from a triangle mesh to look (other shapes are exact everywhere).
inline ShapeDistance distanceToShape(const CollisionShape& collision, const Vec3& q, double reach) {
  const RigidShape& shape = collision.shape;
  if (shape.type == ShapeType::ConvexHull) return distanceToHull(collision.planes, 0, collision.planes.size(), q);
  if (shape.type == ShapeType::Compound) {
    // The union of the hulls: the nearest hull outside, the one it is in deepest inside.
    ShapeDistance best{INFINITY, Vec3::UnitY(), q};
    const size_t hulls = collision.hullPlanesStart.size();
    for (size_t h = 0; h < hulls; ++h) {
      const size_t last = h + 1 < hulls ? static_cast<size_t>(collision.hullPlanesStart[h + 1]) : collision.planes.size();
      const ShapeDistance d = distanceToHull(collision.planes, collision.hullPlanesStart[h], last, q);
      if (d.distance < best.distance) best = d;
    }
    return best;
  }
  if (shape.type == ShapeType::TriangleMesh) {
    ShapeDistance best{INFINITY, Vec3::UnitY(), q};
    collision.grid.visit(q, reach, [&](int32_t i) {
      const Eigen::Vector4d& plane = collision.grid.planes[static_cast<size_t>(i)];
      if (std::abs(plane.head<3>().dot(q) - plane[3]) >= best.distance) return;  // cannot be nearer
      const auto& t = shape.triangles[i];
      const Vec3 &a = shape.points[t[0]], &b = shape.points[t[1]], &c = shape.points[t[2]];
      const std::array<double, 3> w = closestOnTriangle(q, a, b, c);
      const Vec3 onMesh = w[0] * a + w[1] * b + w[2] * c;
      const double distance = (q - onMesh).norm();
      if (distance >= best.distance) return;
      const Vec3 normal = distance > 1e-12 ? Vec3((q - onMesh) / distance) : (b - a).cross(c - a).normalized();
      best = {distance, normal, onMesh};
    });
    return best;
  }
  return distanceToShape(shape, q);
}

inline ShapeDistance distanceToShape(const RigidShape& shape, const Vec3& q) {
  switch (shape.type) {
    case ShapeType::Sphere: {
      const double length = q.norm();
      const Vec3 n = length > 1e-12 ? Vec3(q / length) : Vec3::UnitY();
      return {length - shape.radius, n, shape.radius * n};
    }
    case ShapeType::Box: {
      const Vec3& e = shape.halfExtents;
      const Vec3 clamped = q.cwiseMax(-e).cwiseMin(e);
      const Vec3 outside = q - clamped;
      if (outside.squaredNorm() > 0) {
        const double length = outside.norm();
        return {length, outside / length, clamped};
      }
      int axis = 0;
      double depth = e[0] - std::abs(q[0]);
      for (int k = 1; k < 3; ++k)
        if (e[k] - std::abs(q[k]) < depth) {
          depth = e[k] - std::abs(q[k]);
          axis = k;
        }
      Vec3 n = Vec3::Zero();
      n[axis] = q[axis] >= 0 ? 1 : -1;
      Vec3 surface = q;
      surface[axis] = n[axis] * e[axis];
      return {-depth, n, surface};
    }
    case ShapeType::Capsule: {
      const Vec3 axisPoint(0, std::clamp(q.y(), -shape.halfHeight, shape.halfHeight), 0);
      const Vec3 d = q - axisPoint;
      const double length = d.norm();
      const Vec3 n = length > 1e-12 ? Vec3(d / length) : Vec3::UnitX();
      return {length - shape.radius, n, axisPoint + shape.radius * n};
    }
    case ShapeType::Cylinder: {
      const double radial = std::hypot(q.x(), q.z());
      const Vec3 radialDirection = radial > 1e-12 ? Vec3(q.x() / radial, 0, q.z() / radial) : Vec3::UnitX();
      const double dr = radial - shape.radius, dy = std::abs(q.y()) - shape.halfHeight;
      const double sign = q.y() >= 0 ? 1 : -1;
      const Vec3 rim = shape.radius * radialDirection + Vec3(0, sign * shape.halfHeight, 0);
      if (dr > 0 && dy > 0) {  // beyond the rim
        const Vec3 d = q - rim;
        return {d.norm(), d.normalized(), rim};
      }
      if (dr > dy) {  // nearest the side
        Vec3 surface = shape.radius * radialDirection;
        surface.y() = q.y();
        return {dr, radialDirection, surface};
      }
      Vec3 surface = q;
      surface.y() = sign * shape.halfHeight;
      return {dy, Vec3(0, sign, 0), surface};
    }
    case ShapeType::Plane: {
      const Vec3 n = shape.planeNormal.normalized();
      const double distance = n.dot(q) - shape.planeOffset;
      return {distance, n, q - distance * n};
    }
    case ShapeType::ConvexHull:
    case ShapeType::Compound:
    case ShapeType::TriangleMesh: break;  // need their CollisionShape
  }
  return {1e300, Vec3::UnitY(), q};
}

}  // namespace tandem::geometry
