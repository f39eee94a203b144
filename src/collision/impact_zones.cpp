#include "collision/impact_zones.h"

#include "collision/continuous.h"
#include "collision/geometry.h"

#include <Eigen/Geometry>

#include <numeric>

namespace tandem {
namespace {

constexpr int kMaxPasses = 1000;

struct Feature {
  int32_t surface;
  std::array<int32_t, 3> node;  // a face's three nodes, or an edge's two and -1
};

// Union-find over global node indices: each node's zone.
struct Zones {
  std::vector<int32_t> parent;
  explicit Zones(size_t count) : parent(count) { std::iota(parent.begin(), parent.end(), 0); }
  int32_t find(int32_t n) {
    while (parent[n] != n) n = parent[n] = parent[parent[n]];
    return n;
  }
  void merge(int32_t a, int32_t b) { parent[find(a)] = find(b); }
};

struct Separator {
  std::span<const CollisionSurface> surfaces;
  std::span<const Vec3> start;
  NodeArrays& nodes;
  double timeStep;
  ImpactZoneScratch& scratch;
  std::vector<Vec3> end{};        // positions before any zone moved them
  std::vector<Vec3> velocity{};   // velocities before any zone changed them
  std::vector<char>& meets = scratch.meets;  // meets[a * count + b]: surfaces a and b may cross
  std::vector<Feature> faces{}, edges{};  // of the surfaces that may cross
  Zones zones{0};
  std::vector<char> inZone{};     // node has been merged with another

  Eigen::AlignedBox3d sweptBox(std::span<const int32_t> featureNodes) const {
    Eigen::AlignedBox3d box;
    for (int32_t n : featureNodes) {
      if (n < 0) continue;
      box.extend(start[n]);
      box.extend(nodes.position[n]);
    }
    return box;
  }

  void findMeetingSurfaces() {
    const size_t count = surfaces.size();
    std::vector<Eigen::AlignedBox3d>& bounds = scratch.bounds;
    bounds.resize(count);
    for (size_t s = 0; s < count; ++s) bounds[s] = sweptBox(surfaces[s].nodes);
    tandem::findMeetingSurfaces(surfaces, bounds, meets);
  }

  bool involved(size_t s) const {
    for (size_t b = 0; b < surfaces.size(); ++b)
      if (meets[s * surfaces.size() + b]) return true;
    return false;
  }

  void gatherFeatures() {
    for (size_t s = 0; s < surfaces.size(); ++s) {
      if (!involved(s)) continue;
      const auto surface = static_cast<int32_t>(s);
      for (const auto& t : surfaces[s].triangles) faces.push_back({surface, t});
      for (const auto& e : surfaces[s].edges) edges.push_back({surface, {e[0], e[1], -1}});
    }
  }

  // Whether a node of a surface that may cross is not finite (a diverged step).
  bool anyNotFinite() const {
    for (size_t s = 0; s < surfaces.size(); ++s)
      if (involved(s))
        for (int32_t n : surfaces[s].nodes)
          if (!start[n].allFinite() || !nodes.position[n].allFinite()) return true;
    return false;
  }

  // Pairs of features whose swept boxes overlap, from different zones, that cross on the way.
  // Calls `crossing` with the pair's nodes (up to four; -1 unused).
  template <class OnCrossing>
  int findCrossings(OnCrossing&& crossing) {
    const size_t count = surfaces.size();
    // Cells as large as the largest swept feature, so each feature lies in at most 8.
    std::vector<Eigen::AlignedBox3d> faceBoxes(faces.size()), edgeBoxes(edges.size());
    double cell = 1e-6;
    for (size_t f = 0; f < faces.size(); ++f) {
      faceBoxes[f] = sweptBox(faces[f].node);
      cell = std::max(cell, faceBoxes[f].sizes().maxCoeff());
    }
    for (size_t e = 0; e < edges.size(); ++e) {
      edgeBoxes[e] = sweptBox(edges[e].node);
      cell = std::max(cell, edgeBoxes[e].sizes().maxCoeff());
    }
    const double tolerance = 1e-6 * cell;
    geometry::SpatialHash faceGrid, edgeGrid;
    faceGrid.cell = edgeGrid.cell = cell;
    for (size_t f = 0; f < faces.size(); ++f)
      faceGrid.insert(faceBoxes[f].min(), faceBoxes[f].max(), static_cast<int32_t>(f));
    for (size_t e = 0; e < edges.size(); ++e)
      edgeGrid.insert(edgeBoxes[e].min(), edgeBoxes[e].max(), static_cast<int32_t>(e));
    faceGrid.sort();
    edgeGrid.sort();

    auto sameZone = [&](std::initializer_list<int32_t> pair) {
      const int32_t zone = zones.find(*pair.begin());
      for (int32_t n : pair)
        if (zones.find(n) != zone) return false;
      return true;
    };
    auto d = [&](int32_t n) -> Vec3 { return nodes.position[n] - start[n]; };
    int found = 0;
    std::vector<int32_t> seen;  // last node or edge that visited each face or edge
    // Nodes through faces.
    seen.assign(faces.size(), -1);
    for (size_t s = 0; s < count; ++s) {
      if (!involved(s)) continue;
      for (int32_t n : surfaces[s].nodes) {
        const Eigen::AlignedBox3d box = sweptBox(std::span<const int32_t>(&n, 1));
        faceGrid.visit(box.center(), 0.5 * box.sizes().maxCoeff(), [&](int32_t f) {
          if (seen[f] == n) return;
          seen[f] = n;
          const Feature& face = faces[f];
          const auto [a, b, c] = face.node;
          if (!meets[s * count + face.surface] || n == a || n == b || n == c) return;
          if (!faceBoxes[f].intersects(box) || sameZone({n, a, b, c})) return;
          if (!geometry::nodeFaceImpact(start[n], d(n), start[a], d(a), start[b], d(b), start[c], d(c), tolerance))
            return;
          crossing(std::array<int32_t, 4>{n, a, b, c});
          ++found;
        });
      }
    }
    // Edges through edges, each pair once.
    seen.assign(edges.size(), -1);
    for (size_t e = 0; e < edges.size(); ++e) {
      const Feature& first = edges[e];
      const int32_t i0 = first.node[0], i1 = first.node[1];
      edgeGrid.visit(edgeBoxes[e].center(), 0.5 * edgeBoxes[e].sizes().maxCoeff(), [&](int32_t g) {
        if (g <= static_cast<int32_t>(e) || seen[g] == static_cast<int32_t>(e)) return;
        seen[g] = static_cast<int32_t>(e);
        const Feature& second = edges[g];
        const int32_t j0 = second.node[0], j1 = second.node[1];
        if (!meets[first.surface * count + second.surface] && !meets[second.surface * count + first.surface]) return;
        if (i0 == j0 || i0 == j1 || i1 == j0 || i1 == j1) return;
        if (!edgeBoxes[e].intersects(edgeBoxes[g]) || sameZone({i0, i1, j0, j1})) return;
        if (!geometry::edgeEdgeImpact(start[i0], d(i0), start[i1], d(i1), start[j0], d(j0), start[j1], d(j1),
                                      tolerance))
          return;
        crossing(std::array<int32_t, 4>{i0, i1, j0, j1});
        ++found;
      });
    }
    return found;
  }

  // Every zone given the rigid motion that keeps its nodes' momentum (see the header).
  void moveZonesRigidly(ImpactZoneStats& stats) {
    std::vector<std::vector<int32_t>> members(nodes.size());
    for (size_t n = 0; n < nodes.size(); ++n)
      if (inZone[n]) members[zones.find(static_cast<int32_t>(n))].push_back(static_cast<int32_t>(n));
    stats.zones = stats.zoneNodes = 0;
    const double h = timeStep;
    for (const std::vector<int32_t>& zone : members) {
      if (zone.size() < 2) continue;
      ++stats.zones;
      stats.zoneNodes += static_cast<int>(zone.size());
      Vec3 held = Vec3::Zero();
      int heldCount = 0;
      double mass = 0.0;
      Vec3 centre = Vec3::Zero(), momentum = Vec3::Zero();
      for (int32_t n : zone) {
        if (nodes.inverseMass[n] == 0.0) {
          held += end[n] - start[n];
          ++heldCount;
          continue;
        }
        const double m = 1.0 / nodes.inverseMass[n];
        mass += m;
        centre += m * start[n];
        momentum += m * velocity[n];
      }
      if (heldCount > 0) {
        const Vec3 shift = held / heldCount;
        for (int32_t n : zone) {
          nodes.position[n] = start[n] + shift;
          nodes.velocity[n] = shift / h;
        }
        continue;
      }
      centre /= mass;
      const Vec3 mean = momentum / mass;
      Vec3 angular = Vec3::Zero();
      Mat3 inertia = Mat3::Zero();
      for (int32_t n : zone) {
        const double m = 1.0 / nodes.inverseMass[n];
        const Vec3 r = start[n] - centre;
        angular += m * r.cross(velocity[n] - mean);
        inertia += m * (r.squaredNorm() * Mat3::Identity() - r * r.transpose());
      }
      const Vec3 omega = inertia.completeOrthogonalDecomposition().solve(angular);
      const double angle = omega.norm() * h;
      const Mat3 rotation =
          angle > 1e-15 ? Mat3(Eigen::AngleAxisd(angle, omega.normalized())) : Mat3(Mat3::Identity());
      // The spin at the end is the one the turned inertia gives the same angular momentum.
      const Vec3 spin = (rotation * inertia * rotation.transpose()).completeOrthogonalDecomposition().solve(angular);
      for (int32_t n : zone) {
        const Vec3 r = rotation * (start[n] - centre);
        nodes.position[n] = centre + h * mean + r;
        nodes.velocity[n] = mean + spin.cross(r);
      }
    }
  }
};

}  // namespace

ImpactZoneStats separateByImpactZones(std::span<const CollisionSurface> surfaces, std::span<const Vec3> start,
                                      NodeArrays& nodes, double timeStep) {
  ImpactZoneScratch scratch;
  return separateByImpactZones(surfaces, start, nodes, timeStep, scratch);
}

ImpactZoneStats separateByImpactZones(std::span<const CollisionSurface> surfaces, std::span<const Vec3> start,
                                      NodeArrays& nodes, double timeStep, ImpactZoneScratch& scratch) {
  ImpactZoneStats stats;
  Separator separator{surfaces, start, nodes, timeStep, scratch};
  separator.findMeetingSurfaces();
  separator.gatherFeatures();
  if (separator.faces.empty() && separator.edges.empty()) return stats;
  // A diverged step (non-finite positions) is left to the step's divergence check.
  if (separator.anyNotFinite()) return stats;
  separator.end = nodes.position;
  separator.velocity = nodes.velocity;
  separator.zones = Zones(nodes.size());
  separator.inZone.assign(nodes.size(), 0);
  auto merge = [&](const std::array<int32_t, 4>& pair) {
    for (int32_t n : pair) separator.inZone[n] = 1;
    for (int k = 1; k < 4; ++k) separator.zones.merge(pair[k], pair[0]);
  };
  for (stats.passes = 1; stats.passes <= kMaxPasses; ++stats.passes) {
    const int found = separator.findCrossings(merge);
    if (stats.passes == 1) stats.crossings = found;
    if (found == 0) break;
    separator.moveZonesRigidly(stats);
  }
  return stats;
}

}  // namespace tandem
