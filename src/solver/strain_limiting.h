// Strain limiting: after the nodes move, inextensible edges that no direct block projected
// exactly (those the iterative sweep solved, and those of blocks holding dynamic bodies, which
// a block's projection would have to move) are brought back within a tolerance of their rest
// length by position, Gauss-Seidel over the edges (Provot 1995), interleaved with
// pushing nodes back out of the rigid shapes they touched this step.
//
// Why: projected Gauss-Seidel on the velocity rows of a fine grid converges slowly (a 51×51
// cloth at K = 4 leaves its edges stretched by tens of percent), and a velocity-level row
// never undoes the stretch that drift has already left. By position, each edge is exact in one
// projection; a handful of passes bring a draped cloth within the tolerance. On impact (a
// 51×51 cloth's middle stopped by a sphere while its skirt still falls) a correction has to
// cross the sheet, one edge per pass: 40 passes left 23 % there, so passes go on, up to 400,
// while any edge is still 3 % beyond the limit (2.6 % worst then, for a few costly steps).
// Tried instead: a global projection of all the edges at once (fast projection: J W Jᵀ δλ = −C
// by conjugate gradients; the linearisation overshoots on a taut sheet and made it worse),
// ordering the edges outward from the held nodes (no change), over-relaxation and long-range
// tethers (docs/architecture.md).
//
// For an edge (i, j) with d = x_j − x_i, length ℓ = |d|, n = d / ℓ, and the limit
// L⁺ = (1 + ε) L (stretch) or L⁻ = (1 − ε) L (compression), the projection that moves the
// nodes in proportion to their inverse masses wᵢ, w_j is
//
//   Δ = ℓ − L^±,   x_i ← x_i + wᵢ / (wᵢ + w_j) Δ n,   x_j ← x_j − w_j / (wᵢ + w_j) Δ n
//
// (momentum-preserving: Σ m Δx = 0). Only the sides of each row that have no force bound are
// limited (a row with maxForce may stretch on purpose). Nodes held by a fixed point or an
// anchor count as immovable (an anchor to a dynamic body only without a force bound). For a
// node anchored to a dynamic body the correction the node would have taken goes to the body
// instead, as an impulse: each projection of an edge with one such node adds −m Δx of the
// other node to the held node's `reaction`, and the caller gives
// Σ reaction / h to the body at the anchor (momentum kept, the anchor left closed). Moving the
// anchored node instead, as before, opened the rope-over-wheel scene's anchors by 2.3 cm when
// the slack rope snapped taut (t = 1.16 s at K = 4), for the bias to close over many steps.
// A node moved by the edges also has its velocity changed by Δx / h, as position-based dynamics
// does: left alone, a velocity the sweep could not stop (a cloth's edge falling past the sphere
// its neighbour rests on) keeps growing step after step while the projection keeps undoing it.
//
// Contacts: every node of a limited body near a rigid shape the body touched this step is kept
// out of it (put back on the surface, thickness away, along the normal) every fourth pass and
// after the last, so the edges cannot drag it through them; those pushes move positions only,
// like the contacts' own push-out. (Every pass: the same result, 18 % slower on the paper's
// cloth.) Faces that a contact found near a sphere's centre or a capsule's core are kept off it
// the same way (FaceOnCore, below), so that the edges cannot draw a face's nodes round a body
// smaller than the face.
#pragma once

#include "collision/contact_detection.h"
#include "constraints/inextensibility.h"
#include "solver/solver_state.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <vector>

namespace tandem {

inline constexpr double kStrainTolerance = 0.01;  // ε: 1 % of the rest length
inline constexpr double kStrainConverged = 1e-3;  // done when no edge was corrected by more than 0.1 %
inline constexpr int kStrainPasses = 40;          // else after this many passes,
inline constexpr double kStrainStillTooFar = 0.03;  // unless an edge was still 3 % beyond the limit,
inline constexpr int kStrainPassesAtMost = 400;   // then up to this many
inline constexpr int kStrainPushOutEvery = 4;     // passes between keeping nodes out of shapes

// A node that touched a rigid shape in this step, to be kept out of it.
struct NodeOnShape {
  int32_t node;
  const CollisionRigid* rigid;
  double thickness;
};

// An edge as the passes read it: its nodes, the bounds it is kept within and each node's share
// of a correction, w / (wᵢ + w_j), fixed for the call (a node's weight does not change in it).
struct LimitedEdge {
  int32_t node[2];
  double share[2];
  double restLength;
  double longest;   // (1 + ε) L, or ∞ where the row may stretch (it has a force bound)
  double shortest;  // (1 − ε) L, or −1 where it may compress
  // Squared lengths strictly between these need no correction (a margin of 10⁻⁹ inside the
  // bounds, so that the square root is taken only near or past them, with the same result).
  double clearAbove, clearBelow;
  // An end held by a dynamic body's anchor (share 0), whose reaction the other end's moves add
  // to, and that end's mass; −1 when neither end is.
  int32_t heldByBody = -1;
  double movingMass = 0.0;
};

// The edge of `row` for the passes; false when neither node can move.
inline bool makeLimitedEdge(const InextensibilityRow& row, std::span<const double> weight, LimitedEdge& edge) {
  const double wi = weight[row.node[0]], wj = weight[row.node[1]];
  if (wi + wj == 0.0) return false;
  edge.node[0] = row.node[0];
  edge.node[1] = row.node[1];
  edge.share[0] = wi / (wi + wj);
  edge.share[1] = wj / (wi + wj);
  edge.restLength = row.restLength;
  edge.longest = std::isinf(row.lambdaMin) ? (1 + kStrainTolerance) * row.restLength : INFINITY;
  edge.shortest = std::isinf(row.lambdaMax) ? (1 - kStrainTolerance) * row.restLength : -1.0;
  edge.clearAbove = edge.longest * edge.longest * (1 - 1e-9);
  edge.clearBelow = edge.shortest > 0 ? edge.shortest * edge.shortest * (1 + 1e-9) : -INFINITY;
  return true;
}

// One projection of an edge. Returns the relative excess it removed.
inline double limitEdge(const LimitedEdge& edge, std::span<Vec3> x, std::span<Vec3> reaction) {
  const Vec3 d = x[edge.node[1]] - x[edge.node[0]];
  const double squared = d.squaredNorm();
  if (squared < edge.clearAbove && squared > edge.clearBelow) return 0.0;
  const double length = std::sqrt(squared);
  if (length < 1e-12) return 0.0;
  double excess = 0.0;
  if (length > edge.longest) excess = length - edge.longest;
  if (length < edge.shortest) excess = length - edge.shortest;
  if (excess == 0.0) return 0.0;
  const Vec3 n = d / length;
  x[edge.node[0]] += (edge.share[0] * excess) * n;
  x[edge.node[1]] -= (edge.share[1] * excess) * n;
  if (edge.heldByBody >= 0)  // the other end moved by ±excess n
    reaction[edge.heldByBody] += (edge.heldByBody == edge.node[0] ? excess * edge.movingMass : -excess * edge.movingMass) * n;
  return std::abs(excess) / edge.restLength;
}

inline void keepOutOfShape(const NodeOnShape& contact, std::span<Vec3> x, std::span<Vec3> pushed) {
  const CollisionRigid& body = *contact.rigid;
  const Vec3 local = body.orientation.conjugate() * (x[contact.node] - body.position);
  const geometry::ShapeDistance distance = geometry::distanceToShape(*body.shape, local, 2 * contact.thickness);
  if (!std::isfinite(distance.distance) || distance.distance >= contact.thickness) return;
  const Vec3 push = (contact.thickness - distance.distance) * (body.orientation * distance.normal);
  x[contact.node] += push;
  pushed[contact.node] += push;
}

// A face of a limited body that a contact row found near a round body's core (a sphere's
// centre, a capsule's segment; contact_detection.cpp, pointAgainstFace), kept radius plus
// thickness from it. Measured again at every projection, as a node against a shape is: the
// face's point nearest the core, c = Σ wₖ xₖ, and d = c − q from the core's nearest point q;
// with the deficit δ = r + t − |d|, the face moves along d / |d| as an edge's nodes do,
// Δxₖ = wₖ mₖ⁻¹ δ / Σ wⱼ² mⱼ⁻¹. Where d has turned against the normal the row was found with
// (the core went through the face's plane) it moves back along that normal instead.
// Without it only the faces' nodes were kept out of the shape, and the edges' passes drew them
// round a small ball's sides: a 4 cm ball fell through a pinned cloth of 3.3 cm triangles
// between its nodes, every node outside it.
struct FaceOnCore {
  std::array<int32_t, 3> node;
  const CollisionRigid* rigid;  // where the step left the body
  double clearance;             // r + t
  Vec3 startNormal;             // from the core to the face, when the row was found
};

inline void keepFaceOffCore(const FaceOnCore& face, std::span<const double> weight, std::span<Vec3> x,
                            std::span<Vec3> pushed) {
  const Vec3 &a = x[face.node[0]], &b = x[face.node[1]], &c = x[face.node[2]];
  const CollisionRigid& body = *face.rigid;
  Vec3 core = body.position;
  if (body.shape->shape.type == ShapeType::Capsule) {
    const Vec3 axis = body.orientation * Vec3(0, body.shape->shape.halfHeight, 0);
    core += (2 * geometry::closestSegmentTriangle(core - axis, core + axis, a, b, c).s - 1) * axis;
  }
  const std::array<double, 3> w = geometry::closestOnTriangle(core, a, b, c);
  const Vec3 d = w[0] * a + w[1] * b + w[2] * c - core;
  const double distance = d.norm();
  Vec3 out = face.startNormal;
  double along = d.dot(out);
  if (along > 0.0 && distance > 1e-12) {
    out = d / distance;
    along = distance;
  }
  const double deficit = face.clearance - along;
  if (deficit <= 0.0) return;
  double inverseMass = 0.0;
  for (int k = 0; k < 3; ++k) inverseMass += w[k] * w[k] * weight[face.node[k]];
  if (inverseMass == 0.0) return;
  for (int k = 0; k < 3; ++k) {
    const Vec3 push = (w[k] * weight[face.node[k]] * deficit / inverseMass) * out;
    x[face.node[k]] += push;
    pushed[face.node[k]] += push;
  }
}

// (The projections are not added to the rows' λ: warm started with them, the sweep applied them
// a second time and a draped cloth slid off its sphere.)
inline void limitStrain(std::span<const LimitedEdge> edges, std::span<const NodeOnShape> contacts,
                        std::span<const FaceOnCore> faces, std::span<const double> weight, std::span<Vec3> x,
                        std::span<Vec3> pushed, std::span<Vec3> reaction) {
  for (int pass = 0; pass < kStrainPassesAtMost; ++pass) {
    double worst = 0.0;
    for (const LimitedEdge& edge : edges) worst = std::max(worst, limitEdge(edge, x, reaction));
    const bool last = worst < kStrainConverged || (pass >= kStrainPasses && worst < kStrainStillTooFar) ||
                      pass + 1 == kStrainPassesAtMost;
    if (last || pass % kStrainPushOutEvery == 0) {
      for (const NodeOnShape& contact : contacts) keepOutOfShape(contact, x, pushed);
      for (const FaceOnCore& face : faces) keepFaceOffCore(face, weight, x, pushed);
    }
    if (last) break;
  }
}

}  // namespace tandem
