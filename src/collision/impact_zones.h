// Impact zones: the last stage of a step, which makes sure no deformable surface passed
// through another or through itself (Provot 1997; Bridson, Fedkiw and Anderson 2002; Harmon
// et al. 2008).
//
// The contact rows keep surfaces a thickness apart, but they are solved iteratively on
// velocities, and the position stages after them (block projection, strain limiting) move
// nodes without looking at other surfaces; a fast fold can leave a node through a face. Once
// through, distance-based contacts push it further the wrong way, and the crossing stays.
//
// So after every position stage, each node is taken to move on a straight line from its
// start-of-step position x⁰ to its end position x¹, and every node–face and edge–edge pair of
// surfaces that may meet is tested for a crossing on the way (collision/continuous.h). The
// nodes of each crossing pair are merged into an impact zone, and every zone is given the
// rigid motion that keeps its nodes' momentum:
//   M = Σ m_i,  x̄ = Σ m_i x⁰_i / M,  v̄ = Σ m_i v_i / M,  r_i = x⁰_i − x̄,
//   L = Σ m_i r_i × (v_i − v̄),  I = Σ m_i (|r_i|² 𝟙 − r_i r_iᵀ),  ω = I⁺ L,
//   x¹_i ← x̄ + h v̄ + R r_i,  R = R(h ω),  v_i ← v̄ + ω¹ × R r_i,  ω¹ = (R I Rᵀ)⁺ L,
// (I⁺ the pseudo-inverse, for zones on a line): the end spin ω¹ is the one with the same
// angular momentum for the turned zone, so L is kept exactly, not only to O(h). A rigid motion
// cannot make a zone cross itself, so the test is repeated only between different zones,
// merging those that still cross, until none do: each repeat merges zones, so it ends, at
// worst with one zone per group of touching surfaces (the passes are capped at 1,000). A zone
// holding an immovable node (fixed point, anchor to a static body) moves as its immovable nodes
// do, by their mean displacement.
//
// With a start free of crossings the end is free of them too. The zones' motion is an
// inelastic collision of the nodes involved: linear and angular momentum are kept.
#pragma once

#include "collision/contact_detection.h"
#include "solver/solver_state.h"

#include <span>
#include <vector>

namespace tandem {

struct ImpactZoneStats {
  int crossings = 0;  // crossing pairs found in the first pass
  int zones = 0;      // zones at the end
  int zoneNodes = 0;  // nodes moved rigidly
  int passes = 0;
};

// Working memory of separateByImpactZones that every call needs, kept by the caller between
// steps (so that surfaces that cannot meet cost no allocation).
struct ImpactZoneScratch {
  std::vector<Eigen::AlignedBox3d> bounds;  // per surface, swept over the step
  std::vector<char> meets;                  // per pair of surfaces: they may cross
};

// Moves nodes (position and velocity) so that no surface crosses another or itself (when
// self-colliding) between `start` and the nodes' positions. `start` holds every node.
ImpactZoneStats separateByImpactZones(std::span<const CollisionSurface> surfaces, std::span<const Vec3> start,
                                      NodeArrays& nodes, double timeStep, ImpactZoneScratch& scratch);
// The same with working memory of its own.
ImpactZoneStats separateByImpactZones(std::span<const CollisionSurface> surfaces, std::span<const Vec3> start,
                                      NodeArrays& nodes, double timeStep);

}  // namespace tandem
