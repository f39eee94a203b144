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
// So a sheet's edges are also projected all together, in a Newton step of this problem (fast
// projection, below: projectSheetEdgesTogether) before every second of the first 40 passes:
// five steps of the swept edges' conjugate gradients with their coarse level, which carries a
// correction across the sheet at once; the passes then take what it leaves. Measured
// (`GAUNTLET_ONLY=cloth build/bench/gauntlet_study 2:1 4:1`, docs/solver.md, twentieth
// session): worst stretch after contact on the sphere 1.07 % at 51 × 51 (2.6 % without), 1.1 % at
// 101 × 101 (4.4 %), 3.5 % at 201 × 201 (8.2 %), for 6.4 / 47 / 530 ms per step at K = 4 (5.8 /
// 44 / 366). Before every fourth pass with three steps: 1.1 / 2.5 / 4.7 %; with twenty, 1.1 /
// 1.2 / 3.5 % for twice the cost. Converged, the step leaves a few tenths of a percent of a
// uniformly stretched sheet's excess (tests/test_sheet_projection.cpp), on meshes whose
// triangles brace them: a grid of edges without diagonals shears freely to first order, and the
// step overshoots along those shears. Ribbons (a rope strip two nodes wide) are left out: a
// coarse level of membrane stresses needs a sheet's interior, and with rope_wheel's strip in it
// its light teapot crept faster. A free sphere touching nothing rigid that a sheet touches is
// moved with the sheet in the step, its contact rows rows of the same system (twenty-second
// session: a ball dropped onto a swept pinned cloth, which fell through it, is held). Sheets
// touching any other moving body are left out: the step would not hold that body's contacts (its
// rows keep their normals, which a turning box's corners do not, and a body moved by translation
// into another, or off its joint, is put back by Bullet), and on a taut sheet pinned on all sides
// it flattened the dent a dropped capsule made into the capsule, which the passes turned into
// velocity that threw it. Tried before: fast projection of all edges by Jacobi-preconditioned conjugate
// gradients (it overshot on a taut sheet), ordering the edges outward from the held nodes (no
// change), over-relaxation and long-range tethers (docs/architecture.md).
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
// cloth.) Not the pairs that have no contact (a node anchored to the body, or one edge from
// such a node: listAnchoredPairs): kept out by the passes alone, a node the edges drew into the
// body was put back on its surface each step with the edges' pull into it as velocity, which no
// contact row then stopped, so the next step's pull was larger (2, 4, 8 cm of pushes on
// successive steps), until the cloth by the anchors lifted and turned its box
// (tests/test_grab.cpp, DraggingAClothAnchoredToABox...). Faces that a contact found near a
// sphere's centre or a capsule's core are kept off it the same way (FaceOnCore, below), so that
// the edges cannot draw a face's nodes round a body smaller than the face.
#pragma once

#include "collision/contact_detection.h"
#include "constraints/inextensibility.h"
#include "solver/solver_state.h"
#include "solver/swept_edge_solve.h"

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
inline constexpr int kSheetProjectionEvery = 2;        // passes between projecting sheets together (in the first kStrainPasses),
inline constexpr int kSheetProjectionIterations = 5;    // conjugate-gradient steps at most in a sheet's projection,
inline constexpr double kSheetProjectionTolerance = 1e-2;  // fewer once its residual has fallen this far
inline constexpr double kStrainTouching = 1.5;    // a node within this many thicknesses of a still shape is held along its normal

// A node that touched a rigid shape in this step, to be kept out of it.
struct NodeOnShape {
  int32_t node;
  const CollisionRigid* rigid;
  double thickness;
  bool still;  // the shape's body does not move by impulses (static, kinematic or asleep)
  // Its distance to the shape and the shape's outward normal there (world frame), as the list
  // was made, before the passes.
  double startDistance;
  Vec3 startNormal;
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
  bool inSheet = false;  // of a surface body without volume (a cloth): projected together too
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

// A dynamic body that a sheet touches, moved by the sheets' projection as one more node: its index
// in the passes' positions and weights (past the nodes'; its weight is its inverse mass, its
// position its centre of mass, translation only) and its shape, kept where the projection moves it.
struct MovingBody {
  int32_t node;
  CollisionRigid* rigid;
};

// A contact row of this step between a sheet and a moving body, as a gap linear in the positions:
// g = offset + n · (Σ cₖ xₖ − x_b), with the row's normal n and coefficients cₖ (nodes on the
// sheet), x_b the body's position among the passes' (MovingBody::node), and the offset making g
// the row's gap at the step's start plus what the step's motion, the body's turn included, did
// to it. A row keeps the side it was found on: a body that went through the sheet in the step
// has g < 0 however far it went.
struct SheetContact {
  std::array<int32_t, 3> node;
  std::array<double, 3> coefficient;
  int32_t body;
  Vec3 normal;
  double offset;
  double gap(std::span<const Vec3> x) const {
    Vec3 point = -x[static_cast<size_t>(body)];
    for (int k = 0; k < 3; ++k) point += coefficient[k] * x[static_cast<size_t>(node[k])];
    return offset + normal.dot(point);
  }
};

// The sheets' limited edges projected together, once (fast projection's Newton step): each edge
// past a bound is to come back to it and each within its bounds to keep its length, to first
// order in the moves Δx = W Jᵀ δλ,
//
//   (J W Jᵀ) δλ = −(ℓ − clamp(ℓ, L⁻, L⁺)),
//
// solved by `iterations` steps of the swept edges' conjugate gradients with their two-level cycle
// (fewer once the residual has fallen by `tolerance`; solver/swept_edge_solve.h), so that a
// correction crosses the whole sheet at once instead of an edge per pass. A node touching a
// still shape moves only in its tangent plane in this step (W = w (I − s sᵀ) with the shape's
// normal s, `heldAlong`), as the push-outs would put it back there. The step's contacts with
// moving bodies that are closed past their gap (`contacts`, g < −slop, the slop the contact rows
// leave) are rows of the same system, to open to g = −slop, each moving its nodes and the body
// (`bodies`, translation only): a ball dropped on a taut sheet is held by the sheet's edges at
// once, the dent and the ball's place found together (without them the projection flattened the
// dent into the body, or left the body on the far side, and the passes' velocity update threw
// it; docs/solver.md). The coarse level is built again for the edges' directions in the stage's
// first projection (`coarseBuilt` false; it is set) if it no longer fits them
// (sweptEdgeCoarseFits: it is kept from step to step while it does) and kept for the stage's
// other projections (a preconditioner need not be exact), unless the edges have changed; the
// contact rows have no coarse part. Nothing is done unless some edge is past a bound by more
// than the passes' convergence (kStrainConverged of its length), or some contact closed past its
// gap by twice the slop: at rest one pass is all a draped cloth needs, and building the coarse
// level for it was a quarter of the paper's cloth's step.
inline void projectSheetEdgesTogether(std::span<const LimitedEdge> edges, std::span<const double> weight,
                                      std::span<const Vec3> heldAlong, std::span<Vec3> x, std::span<Vec3> reaction,
                                      SweptEdgeSolveScratch& s, bool& coarseBuilt,
                                      int iterations = kSheetProjectionIterations,
                                      double tolerance = kSheetProjectionTolerance,
                                      std::span<const SheetContact> contacts = {}, double contactSlop = 0.0,
                                      std::span<const MovingBody> bodies = {}) {
  const bool violated =
      std::any_of(edges.begin(), edges.end(),
                  [&](const LimitedEdge& edge) {
                    if (!edge.inSheet) return false;
                    const double length = (x[edge.node[1]] - x[edge.node[0]]).norm();
                    return std::abs(std::clamp(length, edge.shortest, edge.longest) - length) > kStrainConverged * edge.restLength;
                  }) ||
      std::any_of(contacts.begin(), contacts.end(), [&](const SheetContact& contact) { return contact.gap(x) < -2 * contactSlop; });
  if (!violated) return;
  s.edges.clear();
  s.stars.clear();
  s.residual.clear();
  auto response = [&](int32_t node, const Vec3& n) -> Vec3 {
    const Vec3& held = heldAlong[static_cast<size_t>(node)];
    return weight[static_cast<size_t>(node)] * (n - held * held.dot(n));
  };
  for (size_t k = 0; k < edges.size(); ++k) {
    const LimitedEdge& edge = edges[k];
    if (!edge.inSheet) continue;
    const Vec3 d = x[edge.node[1]] - x[edge.node[0]];
    const double length = d.norm();
    if (length < 1e-12) continue;
    const Vec3 n = d / length;
    const Vec3 response0 = response(edge.node[0], n), response1 = response(edge.node[1], n);
    const double diagonal = n.dot(response0 + response1);
    if (!(diagonal > 1e-3 * (weight[edge.node[0]] + weight[edge.node[1]]))) continue;  // held along it
    s.edges.push_back({static_cast<int32_t>(k), {edge.node[0], edge.node[1]}, n, {response0, response1}, 1.0 / diagonal});
    s.residual.push_back(std::clamp(length, edge.shortest, edge.longest) - length);
  }
  const size_t sheetRows = s.edges.size();
  for (const SheetContact& contact : contacts) {
    const double gap = contact.gap(x) + contactSlop;
    if (gap >= 0.0) continue;
    SweptEdgeSolveScratch::Star star{{contact.node[0], contact.node[1], contact.node[2], contact.body}, {}, {}, 0.0};
    double diagonal = 0.0;
    for (int k = 0; k < 4; ++k) {
      star.j[k] = k < 3 ? Vec3(contact.coefficient[k] * contact.normal) : Vec3(-contact.normal);
      star.response[k] = response(star.node[k], star.j[k]);
      diagonal += star.j[k].dot(star.response[k]);
    }
    if (!(diagonal > 0.0)) continue;
    star.effectiveMass = 1.0 / diagonal;
    s.stars.push_back(star);
    s.residual.push_back(-gap);  // after the edges', as the stars' rows come after theirs
  }
  const bool sameEdges = sheetRows == s.coarse.edgeNodes.size() &&
                         std::equal(s.edges.begin(), s.edges.end(), s.coarse.edgeNodes.begin(), [](const auto& e, const auto& nodes) {
                           return e.node[0] == nodes[0] && e.node[1] == nodes[1];
                         });
  if (!coarseBuilt || !sameEdges || !s.coarse.factor.ready) {
    prepareSweptEdgeCoarse(s, weight, heldAlong);
    coarseBuilt = true;
  }
  solveSweptEdgeSystem(s, x.size(), iterations, tolerance);
  for (size_t i = 0; i < sheetRows; ++i) {
    const SweptEdgeSolveScratch::Edge& e = s.edges[i];
    x[e.node[0]] -= s.impulse[i] * e.response[0];
    x[e.node[1]] += s.impulse[i] * e.response[1];
    const LimitedEdge& edge = edges[static_cast<size_t>(e.row)];
    if (edge.heldByBody >= 0)  // −m Δx of the other end
      reaction[edge.heldByBody] += (edge.heldByBody == edge.node[0] ? -s.impulse[i] : s.impulse[i]) * e.n;
  }
  for (size_t i = 0; i < s.stars.size(); ++i)
    for (int k = 0; k < 4; ++k) x[s.stars[i].node[k]] += s.impulse[sheetRows + i] * s.stars[i].response[k];
  for (const MovingBody& body : bodies) body.rigid->position = x[static_cast<size_t>(body.node)];
}

// (The projections are not added to the rows' λ: warm started with them, the sweep applied them
// a second time and a draped cloth slid off its sphere.)
// `x` and `weight` may go on past the nodes with `bodies`' centres and inverse masses (above).
inline void limitStrain(std::span<const LimitedEdge> edges, std::span<const NodeOnShape> contacts,
                        std::span<const FaceOnCore> faces, std::span<const double> weight, std::span<Vec3> x,
                        std::span<Vec3> pushed, std::span<Vec3> reaction, SweptEdgeSolveScratch& together,
                        std::vector<Vec3>& heldAlong, std::span<const SheetContact> sheetContacts = {},
                        double contactSlop = 0.0, std::span<const MovingBody> bodies = {}) {
  const bool sheets = std::any_of(edges.begin(), edges.end(), [](const LimitedEdge& edge) { return edge.inSheet; });
  if (sheets) {
    heldAlong.assign(x.size(), Vec3::Zero());
    for (const NodeOnShape& contact : contacts)
      if (contact.still && contact.startDistance < kStrainTouching * contact.thickness)
        heldAlong[contact.node] = contact.startNormal;
  }
  bool coarseBuilt = false;
  for (int pass = 0; pass < kStrainPassesAtMost; ++pass) {
    if (sheets && pass < kStrainPasses && pass % kSheetProjectionEvery == 0)
      projectSheetEdgesTogether(edges, weight, heldAlong, x, reaction, together, coarseBuilt, kSheetProjectionIterations,
                                kSheetProjectionTolerance, sheetContacts, contactSlop, bodies);
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
