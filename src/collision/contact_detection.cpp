#include "collision/contact_detection.h"

#include "collision/geometry.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <unordered_set>

namespace tandem {
namespace {

using geometry::closestOnTriangle;

// Metres: far above the rounding of a position, far below any contact's distances. Tests that
// only skip work are widened by it, so they never skip what the full test would keep.
constexpr double kSideTolerance = 1e-9;

// Feature keys for warm starting: what touches what, packed in 64 bits.
enum class Feature : uint64_t { NodeRigid = 1, FaceRigid = 2, NodeFace = 3, EdgeEdge = 4 };
uint64_t featureKey(Feature kind, uint64_t a, uint64_t b, uint64_t c = 0) {
  return (static_cast<uint64_t>(kind) << 60) ^ (a * 0x9E3779B97F4A7C15ull) ^ (b * 0xC2B2AE3D27D4EB4Full) ^
         (c * 0x165667B19E3779F9ull);
}

double boundingRadius(const RigidShape& shape) {
  switch (shape.type) {
    case ShapeType::Box: return shape.halfExtents.norm();
    case ShapeType::Sphere: return shape.radius;
    case ShapeType::Capsule: return shape.radius + shape.halfHeight;
    case ShapeType::Cylinder: return std::hypot(shape.radius, shape.halfHeight);
    case ShapeType::ConvexHull: {
      double radius = 0.0;
      for (const Vec3& p : shape.points) radius = std::max(radius, p.norm());
      return radius;
    }
    case ShapeType::Compound: {
      double radius = 0.0;
      for (const std::vector<Vec3>& hull : shape.hulls)
        for (const Vec3& p : hull) radius = std::max(radius, p.norm());
      return radius;
    }
    case ShapeType::Plane:
    case ShapeType::TriangleMesh: return INFINITY;
  }
  return INFINITY;
}

// Points of a shape's surface that can poke into a face between its nodes: box corners and
// cylinder rims (sampled), in the shape's frame, moved by `toWorld` and appended to `points`.
template <class ToWorld>
void addPokingPoints(const RigidShape& shape, ToWorld toWorld, std::vector<Vec3>& points) {
  if (shape.type == ShapeType::ConvexHull) {
    for (const Vec3& p : shape.points) points.push_back(toWorld(p));
  } else if (shape.type == ShapeType::Compound) {
    for (const std::vector<Vec3>& hull : shape.hulls)
      for (const Vec3& p : hull) points.push_back(toWorld(p));
  } else if (shape.type == ShapeType::Box) {
    for (int corner = 0; corner < 8; ++corner)
      points.push_back(toWorld(shape.halfExtents.cwiseProduct(
          Vec3(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1, corner & 4 ? 1 : -1))));
  } else if (shape.type == ShapeType::Cylinder) {
    constexpr int kRimSamples = 16;
    for (int k = 0; k < kRimSamples; ++k) {
      const double angle = 2 * 3.14159265358979323846 * k / kRimSamples;
      for (double y : {-shape.halfHeight, shape.halfHeight})
        points.push_back(toWorld(Vec3(shape.radius * std::cos(angle), y, shape.radius * std::sin(angle))));
    }
  }
}

struct Detector {
  std::span<const CollisionSurface> surfaces;
  const NodeArrays& nodes;
  std::span<const CollisionRigid> rigid;
  std::span<const uint64_t> anchored;  // sorted
  double timeStep;
  std::vector<ContactRow>& contacts;
  ContactDetectionScratch& scratch;
  std::unordered_set<uint64_t> edgeContacts;  // an edge point is found from both its triangles

  // How far two sides may close in this step: twice what their starting speeds give, since the
  // solve can speed a node up (a cloth whipping round an edge). Callers add a thickness.
  double closing(const Vec3& a, const Vec3& b) const { return 2.0 * (a - b).norm() * timeStep; }

  bool isAnchored(int32_t node, int32_t body) const { return isAnchoredPair(anchored, node, body); }

  void addRigidContact(const CollisionSurface& surface, const std::array<int32_t, 3>& node,
                       const std::array<double, 3>& weight, int count, int32_t body, const Vec3& rigidPoint,
                       const Vec3& normal, double gap, uint64_t key) {
    ContactRow row;
    for (int k = 0; k < 4; ++k) {
      row.node[k] = k < count ? node[k] : node[0];
      row.coefficient[k] = k < count ? weight[k] : 0.0;
    }
    row.body = body;
    row.offset = rigidPoint - rigid[body].position;
    row.normal = normal;
    row.gap = gap;
    row.friction = surface.friction * rigid[body].friction;
    row.key = key;
    contacts.push_back(row);
  }

  void nodesAgainstRigid(const CollisionSurface& surface, int32_t body) {
    const CollisionRigid& shape = rigid[body];
    const double reach = boundingRadius(shape.shape->shape) + surface.thickness;
    const Mat3 rotation = shape.orientation.toRotationMatrix();
    for (int32_t n : surface.nodes) {
      const Vec3& x = nodes.position[n];
      const Vec3 rigidVelocity = shape.linearVelocity + shape.angularVelocity.cross(x - shape.position);
      const double margin = closing(nodes.velocity[n], rigidVelocity) + surface.thickness;
      if ((x - shape.position).norm() > reach + margin || isAnchored(n, body)) continue;
      const geometry::ShapeDistance d =
          geometry::distanceToShape(*shape.shape, rotation.transpose() * (x - shape.position), surface.thickness + margin);
      const double gap = d.distance - surface.thickness;
      if (gap > margin) continue;
      // The body's point is where the node's centre rests when touching (the surface moved out by
      // the thickness): friction holds the node to that point's velocity, so a rope of thickness
      // t wound on a wheel of radius r rolls at (r + t) ω, as its centre line does.
      addRigidContact(surface, {n, n, n}, {1, 0, 0}, 1, body,
                      shape.position + rotation * (d.surfacePoint + surface.thickness * d.normal), rotation * d.normal,
                      gap, featureKey(Feature::NodeRigid, n, body));
    }
  }

  // A point of the rigid surface (or of its core, for spheres and capsules, with `radius`)
  // against one triangle. Vertices are left to the node contacts; an edge point is taken once.
  void pointAgainstFace(const CollisionSurface& surface, const std::array<int32_t, 3>& face, int32_t body,
                        const Vec3& point, double radius, int32_t feature) {
    const Vec3 &a = nodes.position[face[0]], &b = nodes.position[face[1]], &c = nodes.position[face[2]];
    const std::array<double, 3> w = closestOnTriangle(point, a, b, c);
    if (std::max({w[0], w[1], w[2]}) > 1.0 - 1e-9) return;  // at a vertex
    const Vec3 onFace = w[0] * a + w[1] * b + w[2] * c;
    const CollisionRigid& shape = rigid[body];
    Vec3 normal;
    double gap;
    if (radius > 0) {  // sphere or capsule core: along the line to the core
      const Vec3 d = onFace - point;
      const double distance = d.norm();
      if (distance < 1e-12) return;
      normal = d / distance;
      gap = distance - radius - surface.thickness;
      // Only where the face reaches clearly deeper than its vertices (a coarse face across a
      // round shape); where the nodes hug the shape their own contacts hold it, and near copies
      // of them would only make the solve ill-conditioned.
      const double vertices = std::min({(a - point).norm(), (b - point).norm(), (c - point).norm()});
      if (distance > vertices - 0.5 * surface.thickness) return;
    } else {  // a corner: along the face normal, on the side away from the body
      normal = (b - a).cross(c - a).normalized();
      if (normal.dot(onFace - shape.position) < 0) normal = -normal;
      gap = normal.dot(onFace - point) - surface.thickness;
      if ((onFace - point - normal.dot(onFace - point) * normal).norm() > 1e-9 * (b - a).norm()) return;  // off the face
      if (gap < -4 * surface.thickness - boundingRadius(shape.shape->shape)) return;  // far behind: not this face
      // A corner through a face leaves the face cutting the shape: the face's point nearest the
      // corner is inside it. Where it is outside, the corner is behind the face, not through it
      // (a long bar's far end "behind" a jelly's side face read as 26 cm deep and kicked the
      // face's nodes away at 3 m/s). A corner still in front (gap ≥ 0) is an approach.
      const Vec3 local = shape.orientation.conjugate() * (onFace - shape.position);
      if (gap < 0 && geometry::distanceToShape(*shape.shape, local, surface.thickness).distance > surface.thickness)
        return;
    }
    Vec3 faceVelocity = w[0] * nodes.velocity[face[0]] + w[1] * nodes.velocity[face[1]] + w[2] * nodes.velocity[face[2]];
    const Vec3 rigidPoint = point + radius * normal;
    const Vec3 rigidVelocity = shape.linearVelocity + shape.angularVelocity.cross(rigidPoint - shape.position);
    if (gap > closing(faceVelocity, rigidVelocity) + surface.thickness) return;
    uint64_t key;
    const int zero = w[0] == 0 ? 0 : w[1] == 0 ? 1 : w[2] == 0 ? 2 : -1;
    if (zero >= 0) {  // on an edge, shared with the neighbouring triangle
      const int32_t i = face[(zero + 1) % 3], j = face[(zero + 2) % 3];
      key = featureKey(Feature::FaceRigid, std::min(i, j), std::max(i, j), (static_cast<uint64_t>(body) << 20) ^ feature);
      if (!edgeContacts.insert(key).second) return;
    } else {
      key = featureKey(Feature::FaceRigid, face[0], face[1] ^ (static_cast<uint64_t>(face[2]) << 32),
                       (static_cast<uint64_t>(body) << 20) ^ feature);
    }
    addRigidContact(surface, face, w, 3, body, rigidPoint, normal, gap, key);
  }

  void facesAgainstRigid(const CollisionSurface& surface, int32_t body) {
    const CollisionRigid& shape = rigid[body];
    const RigidShape& form = shape.shape->shape;
    // A plane cannot reach between a face's nodes; a mesh's vertices are left out (meshes are
    // scenery: terrain, bowls), its faces meet the cloth's nodes.
    if (form.type == ShapeType::Plane || form.type == ShapeType::TriangleMesh || surface.triangles.empty()) return;
    const Mat3 rotation = shape.orientation.toRotationMatrix();
    const double reach = boundingRadius(form) + surface.thickness;
    std::vector<Vec3>& points = scratch.points;
    points.clear();
    addPokingPoints(form, [&](const Vec3& local) -> Vec3 { return shape.position + rotation * local; }, points);
    const Vec3 axis = rotation * Vec3(0, form.halfHeight, 0);
    const double bodySpeed = shape.linearVelocity.norm() + shape.angularVelocity.norm() * boundingRadius(form);
    for (const auto& face : surface.triangles) {
      const Vec3 &a = nodes.position[face[0]], &b = nodes.position[face[1]], &c = nodes.position[face[2]];
      const Vec3 centre = (a + b + c) / 3.0;
      const double size = std::max({(a - centre).norm(), (b - centre).norm(), (c - centre).norm()});
      const double margin = closing(nodes.velocity[face[0]], shape.linearVelocity) + size;
      if ((centre - shape.position).norm() > reach + margin) continue;
      if (isAnchored(face[0], body) || isAnchored(face[1], body) || isAnchored(face[2], body))
        continue;
      if (form.type == ShapeType::Sphere) {
        pointAgainstFace(surface, face, body, shape.position, form.radius, 0);
      } else if (form.type == ShapeType::Capsule) {
        const geometry::SegmentTriangle closest =
            geometry::closestSegmentTriangle(shape.position - axis, shape.position + axis, a, b, c);
        pointAgainstFace(surface, face, body, shape.position - axis + 2 * closest.s * axis, form.radius, 0);
      }
      // A corner counts only between −(4 t + R) and the closing distance plus t from the face,
      // along its normal turned away from the body (pointAgainstFace), so most of a shape's
      // corners are out by one dot product: with the face's fastest node and the body's fastest
      // point, the closing distance here is at least the one tested there. Where the face's
      // plane passes through the body's origin the normal's side is left to pointAgainstFace.
      Vec3 normal = (b - a).cross(c - a).normalized();
      const double side = normal.dot(centre - shape.position);
      if (side < 0) normal = -normal;
      const bool sided = std::abs(side) > kSideTolerance;
      const double fastestNode = std::max({nodes.velocity[face[0]].norm(), nodes.velocity[face[1]].norm(),
                                           nodes.velocity[face[2]].norm()});
      const double farthest = 2.0 * (fastestNode + bodySpeed) * timeStep + surface.thickness + kSideTolerance;
      const double deepest = -4 * surface.thickness - reach - kSideTolerance;
      for (size_t p = 0; p < points.size(); ++p) {
        const double gap = normal.dot(a - points[p]) - surface.thickness;
        if (sided && (gap > farthest || gap < deepest)) continue;
        pointAgainstFace(surface, face, body, points[p], 0.0, static_cast<int32_t>(p) + 1);
      }
    }
  }

  // Which surfaces can touch which: themselves when self-colliding, others when their padded
  // bounding boxes overlap. meets[a * count + b].
  std::vector<char>& meets = scratch.meets;
  double largestPad = 0.0;
  void findMeetingSurfaces() {
    const size_t count = surfaces.size();
    std::vector<Eigen::AlignedBox3d>& bounds = scratch.bounds;
    bounds.assign(count, Eigen::AlignedBox3d());
    for (size_t s = 0; s < count; ++s) {
      double fastest = 0.0;
      for (int32_t n : surfaces[s].nodes) {
        bounds[s].extend(nodes.position[n]);
        fastest = std::max(fastest, nodes.velocity[n].norm());
      }
      const double pad = 2 * surfaces[s].thickness + 2 * fastest * timeStep;
      largestPad = std::max(largestPad, pad);
      bounds[s].min().array() -= pad;
      bounds[s].max().array() += pad;
    }
    tandem::findMeetingSurfaces(surfaces, bounds, meets);
  }

  // Whether any surface can touch the features (faces, edges) of surface s.
  bool featuresNeeded(size_t s) const {
    const size_t count = surfaces.size();
    for (size_t a = 0; a < count; ++a)
      if (meets[a * count + s]) return true;
    return false;
  }

  // Node against face, between surfaces and within one, over a spatial hash of the faces.
  void nodesAgainstFaces() {
    const size_t count = surfaces.size();
    struct Face {
      int32_t surface;
      std::array<int32_t, 3> node;
    };
    std::vector<Face> faces;
    geometry::SpatialHash grid;
    grid.cell = largestPad;
    for (size_t s = 0; s < count; ++s) {
      if (!featuresNeeded(s)) continue;
      for (const auto& face : surfaces[s].triangles) {
        faces.push_back({static_cast<int32_t>(s), face});
        grid.cell = std::max(grid.cell, (nodes.position[face[1]] - nodes.position[face[0]]).norm());
      }
    }
    if (faces.empty()) return;
    for (size_t f = 0; f < faces.size(); ++f) {
      const auto& node = faces[f].node;
      Vec3 low = nodes.position[node[0]], high = low;
      for (int k = 1; k < 3; ++k) {
        low = low.cwiseMin(nodes.position[node[k]]);
        high = high.cwiseMax(nodes.position[node[k]]);
      }
      grid.insert(low - Vec3::Constant(largestPad), high + Vec3::Constant(largestPad), static_cast<int32_t>(f));
    }
    grid.sort();

    for (size_t s = 0; s < count; ++s) {
      const CollisionSurface& surface = surfaces[s];
      for (int32_t n : surface.nodes) {
        const Vec3& x = nodes.position[n];
        grid.visit(x, 0.0, [&](int32_t f) {
          const Face& face = faces[f];
          const CollisionSurface& other = surfaces[face.surface];
          if (!meets[s * count + face.surface]) return;
          if (face.node[0] == n || face.node[1] == n || face.node[2] == n) return;
          const double thickness = surface.thickness + other.thickness;
          const Vec3 &a = nodes.position[face.node[0]], &b = nodes.position[face.node[1]], &c = nodes.position[face.node[2]];
          const std::array<double, 3> w = closestOnTriangle(x, a, b, c);
          const Vec3 onFace = w[0] * a + w[1] * b + w[2] * c;
          const double distance = (x - onFace).norm();
          const Vec3 faceVelocity = w[0] * nodes.velocity[face.node[0]] + w[1] * nodes.velocity[face.node[1]] +
                                    w[2] * nodes.velocity[face.node[2]];
          if (distance - thickness > closing(nodes.velocity[n], faceVelocity) + thickness) return;
          if (face.surface == static_cast<int32_t>(s) && nearAtRest(surface, n, face.node)) return;
          const Vec3 normal = distance > 1e-9 ? Vec3((x - onFace) / distance) : (b - a).cross(c - a).normalized();
          ContactRow row;
          row.node = {n, face.node[0], face.node[1], face.node[2]};
          row.coefficient = {1.0, -w[0], -w[1], -w[2]};
          row.normal = normal;
          row.gap = distance - thickness;
          row.friction = surface.friction * other.friction;
          row.key = featureKey(Feature::NodeFace, n, face.node[0] ^ (static_cast<uint64_t>(face.node[1]) << 21),
                               face.node[2]);
          contacts.push_back(row);
        });
      }
    }
  }

  // Edge against edge, for the same pairs of surfaces: the crossing that node–face contacts
  // miss when two edges scissor between their nodes.
  void edgesAgainstEdges() {
    const size_t count = surfaces.size();
    struct Edge {
      int32_t surface;
      std::array<int32_t, 2> node;
    };
    std::vector<Edge> edges;
    geometry::SpatialHash grid;
    grid.cell = largestPad;
    for (size_t s = 0; s < count; ++s) {
      if (!featuresNeeded(s)) continue;
      for (const auto& edge : surfaces[s].edges) {
        edges.push_back({static_cast<int32_t>(s), edge});
        grid.cell = std::max(grid.cell, (nodes.position[edge[1]] - nodes.position[edge[0]]).norm());
      }
    }
    if (edges.empty()) return;
    for (size_t e = 0; e < edges.size(); ++e) {
      const Vec3 &a = nodes.position[edges[e].node[0]], &b = nodes.position[edges[e].node[1]];
      grid.insert(a.cwiseMin(b) - Vec3::Constant(largestPad), a.cwiseMax(b) + Vec3::Constant(largestPad),
                  static_cast<int32_t>(e));
    }
    grid.sort();
    std::unordered_set<uint64_t> seen;
    for (size_t e = 0; e < edges.size(); ++e) {
      const Edge& first = edges[e];
      const Vec3 &p0 = nodes.position[first.node[0]], &p1 = nodes.position[first.node[1]];
      grid.visit(0.5 * (p0 + p1), 0.0, [&](int32_t f) {
        if (f <= static_cast<int32_t>(e)) return;  // each pair once
        const Edge& second = edges[f];
        if (!meets[first.surface * count + second.surface] && !meets[second.surface * count + first.surface]) return;
        const auto [i0, i1] = first.node;
        const auto [j0, j1] = second.node;
        if (i0 == j0 || i0 == j1 || i1 == j0 || i1 == j1) return;
        const Vec3 &q0 = nodes.position[j0], &q1 = nodes.position[j1];
        const auto [s, t] = geometry::closestOnSegments(p0, p1, q0, q1);
        // End points are the node–face contacts' business.
        if (s <= 1e-6 || s >= 1 - 1e-6 || t <= 1e-6 || t >= 1 - 1e-6) return;
        const CollisionSurface &a = surfaces[first.surface], &b = surfaces[second.surface];
        const double thickness = a.thickness + b.thickness;
        const Vec3 onFirst = p0 + s * (p1 - p0), onSecond = q0 + t * (q1 - q0);
        const double distance = (onFirst - onSecond).norm();
        if (distance < 1e-9) return;
        const Vec3 firstVelocity = (1 - s) * nodes.velocity[i0] + s * nodes.velocity[i1];
        const Vec3 secondVelocity = (1 - t) * nodes.velocity[j0] + t * nodes.velocity[j1];
        if (distance - thickness > closing(firstVelocity, secondVelocity) + thickness) return;
        if (first.surface == second.surface && nearAtRest(a, first.node, second.node)) return;
        const uint64_t key = featureKey(Feature::EdgeEdge, std::min(i0, i1) ^ (static_cast<uint64_t>(std::max(i0, i1)) << 32),
                                        std::min(j0, j1) ^ (static_cast<uint64_t>(std::max(j0, j1)) << 32));
        if (!seen.insert(key).second) return;
        ContactRow row;
        row.node = {i0, i1, j0, j1};
        row.coefficient = {1 - s, s, -(1 - t), -t};
        row.normal = (onFirst - onSecond) / distance;
        row.gap = distance - thickness;
        row.friction = a.friction * b.friction;
        row.key = key;
        contacts.push_back(row);
      });
    }
  }

  // Features of the same surface that were close at rest (within kNeighbourhood edge lengths)
  // are neighbours, not a collision: a node and a face, or two edges.
  static constexpr double kNeighbourhood = 1.0;
  static Vec3 rest(const CollisionSurface& surface, int32_t n) { return surface.restPositions[n - surface.firstNode]; }

  static bool nearAtRest(const CollisionSurface& surface, int32_t node, const std::array<int32_t, 3>& face) {
    const Vec3 a = rest(surface, face[0]), b = rest(surface, face[1]), c = rest(surface, face[2]), x = rest(surface, node);
    const double edge = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const std::array<double, 3> w = closestOnTriangle(x, a, b, c);
    return (x - (w[0] * a + w[1] * b + w[2] * c)).norm() < kNeighbourhood * edge;
  }

  static bool nearAtRest(const CollisionSurface& surface, const std::array<int32_t, 2>& first,
                         const std::array<int32_t, 2>& second) {
    const Vec3 p0 = rest(surface, first[0]), p1 = rest(surface, first[1]);
    const Vec3 q0 = rest(surface, second[0]), q1 = rest(surface, second[1]);
    const auto [s, t] = geometry::closestOnSegments(p0, p1, q0, q1);
    const double edge = std::max((p1 - p0).norm(), (q1 - q0).norm());
    return ((p0 + s * (p1 - p0)) - (q0 + t * (q1 - q0))).norm() < kNeighbourhood * edge;
  }
};

}  // namespace

void findMeetingSurfaces(std::span<const CollisionSurface> surfaces, std::span<const Eigen::AlignedBox3d> bounds,
                         std::vector<char>& meets) {
  const size_t count = surfaces.size();
  meets.assign(count * count, 0);
  for (size_t a = 0; a < count; ++a)
    for (size_t b = 0; b < count; ++b)
      meets[a * count + b] = a == b ? surfaces[a].selfCollision
                                    : bounds[a].intersects(bounds[b]) &&
                                          collisionGroupsMeet(surfaces[a].group, surfaces[a].mask, surfaces[b].group,
                                                              surfaces[b].mask);
}

uint64_t nodeBodyKey(int32_t node, int32_t body) {
  return (static_cast<uint64_t>(static_cast<uint32_t>(node)) << 32) | static_cast<uint32_t>(body);
}

bool isAnchoredPair(std::span<const uint64_t> anchored, int32_t node, int32_t body) {
  return std::binary_search(anchored.begin(), anchored.end(), nodeBodyKey(node, body));
}

void detectContacts(std::span<const CollisionSurface> surfaces, const NodeArrays& nodes,
                    std::span<const CollisionRigid> rigid, std::span<const uint64_t> anchored, double timeStep,
                    std::vector<ContactRow>& contacts, ContactDetectionScratch& scratch) {
  Detector detector{surfaces, nodes, rigid, anchored, timeStep, contacts, scratch, {}};
  for (const CollisionSurface& surface : surfaces)
    for (int32_t body = 0; body < static_cast<int32_t>(rigid.size()); ++body) {
      if (!collisionGroupsMeet(surface.group, surface.mask, rigid[body].group, rigid[body].mask)) continue;
      detector.nodesAgainstRigid(surface, body);
      detector.facesAgainstRigid(surface, body);
    }
  detector.findMeetingSurfaces();
  detector.nodesAgainstFaces();
  detector.edgesAgainstEdges();

  // The mass a contact moves, for the pressure friction model (paper eq. 32): the nodes' share,
  // plus the rigid body's mass spread over its contacts.
  std::vector<int>& contactsPerBody = scratch.contactsPerBody;
  contactsPerBody.assign(rigid.size(), 0);
  for (const ContactRow& row : contacts)
    if (row.body >= 0) ++contactsPerBody[row.body];
  for (ContactRow& row : contacts) {
    double mass = 0.0;
    for (int k = 0; k < 4; ++k)
      if (row.coefficient[k] != 0.0 && nodes.inverseMass[row.node[k]] > 0)
        mass += std::abs(row.coefficient[k]) / nodes.inverseMass[row.node[k]];
    if (row.body >= 0) mass += rigid[row.body].mass / contactsPerBody[row.body];
    row.contactMass = mass;
  }
}

}  // namespace tandem
