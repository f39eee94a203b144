// Tandem's collision detection: deformable surfaces against rigid shapes, against each other,
// and against themselves. Produces ContactRow's (src/constraints/contact.h).
//
// Contacts found (each a point, a normal from B to A, a gap, and nodes with weights):
//   node – rigid shape     every surface node against the exact signed distance of each shape
//   rigid feature – face   box corners, cylinder rim points, the sphere centre and the capsule
//                          core segment against each triangle, so a corner cannot poke through
//                          a coarse face between its nodes
//   node – face            between deformables, and within one (self-collision) except for
//                          triangles the node belongs to or was already near at rest
//   edge – edge            the same pairs of surfaces, for edges that cross between their
//                          nodes (two cloths' edges scissoring, ropes against ropes)
// Contacts are speculative: any pair closer than the thickness plus the distance the two
// sides can close in this step is a row, whose bias lets the gap close but not pass.
// Broad phase: bounding spheres for rigid shapes; a sorted spatial hash of padded triangle
// boxes for deformable surfaces, so cost grows linearly with surface size.
#pragma once

#include <tandem/world.h>

#include "collision/geometry.h"
#include "constraints/contact.h"
#include "solver/solver_state.h"

#include <Eigen/Geometry>

#include <span>
#include <vector>

namespace tandem {

struct CollisionSurface {
  int32_t firstNode = 0;
  int32_t nodeCount = 0;
  std::span<const int32_t> nodes;                      // surface nodes, global indices
  std::span<const std::array<int32_t, 3>> triangles;   // global indices
  std::span<const std::array<int32_t, 2>> edges;       // global indices: the triangles' edges, or a rope's
  std::span<const Vec3> restPositions;                 // by local index, for self-collision
  double thickness = 0.0;
  double friction = 0.0;
  bool selfCollision = false;
  uint32_t group = kDefaultCollisionGroup;  // filter (world.h: collisionGroupsMeet)
  uint32_t mask = kAllCollisionGroups;
};

struct CollisionRigid {
  const geometry::CollisionShape* shape = nullptr;
  Vec3 position = Vec3::Zero();  // centre of mass
  Quat orientation = Quat::Identity();
  Vec3 linearVelocity = Vec3::Zero();
  Vec3 angularVelocity = Vec3::Zero();
  double friction = 0.0;
  double mass = 0.0;  // 0 when immovable
  uint32_t group = kDefaultCollisionGroup;  // filter (world.h: collisionGroupsMeet)
  uint32_t mask = kAllCollisionGroups;
};

// A node anchored to a rigid body does not collide with it (nor do faces around the node); the
// world lists its neighbours too (World::Impl::listAnchoredPairs).
uint64_t nodeBodyKey(int32_t node, int32_t body);
// Whether the pair is in `anchored` (sorted nodeBodyKey's): it has no contact.
bool isAnchoredPair(std::span<const uint64_t> anchored, int32_t node, int32_t body);

// Which surfaces may touch which, given a box around each: meets[a * count + b] is set for a
// surface with itself when it self-collides, and for two whose boxes overlap and whose
// collision filters let them meet. (Contact detection passes boxes padded by the step's reach,
// the impact zones the boxes their nodes swept.)
void findMeetingSurfaces(std::span<const CollisionSurface> surfaces, std::span<const Eigen::AlignedBox3d> bounds,
                         std::vector<char>& meets);

// Working memory of detectContacts, kept by the caller between steps so that finding contacts
// with rigid shapes allocates nothing once grown.
struct ContactDetectionScratch {
  std::vector<Vec3> points;          // a shape's points that can poke into faces, in the world
  std::vector<int> contactsPerBody;  // per rigid body
  std::vector<Eigen::AlignedBox3d> bounds;  // per surface, padded
  std::vector<char> meets;           // per pair of surfaces: they may touch
};

// Appends every contact to `contacts`. `anchored` holds nodeBodyKey's of pairs to leave out,
// sorted.
void detectContacts(std::span<const CollisionSurface> surfaces, const NodeArrays& nodes,
                    std::span<const CollisionRigid> rigid, std::span<const uint64_t> anchored, double timeStep,
                    std::vector<ContactRow>& contacts, ContactDetectionScratch& scratch);

}  // namespace tandem
