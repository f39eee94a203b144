// Position-based paradigms: shape matching and position-based dynamics (paper §3, eq. 1–3).
//
// Both turn goal positions into the unconstrained velocities the row solver starts from, so
// the solver never learns which paradigm a body uses. With v* = v + h m⁻¹ f (forces and
// gravity, as every paradigm gets) and the predicted positions x* = x + h v* (eq. 1):
//
//   shape matching (eq. 2):  v ← (1 − γ) (v* + k (g − x*) / h)
//     g = R (x⁰ − c⁰) + c*, the rest shape moved rigidly onto x*: c* and c⁰ the mass centres,
//     R the rotation of A = Σ m (x* − c*)(x⁰ − c⁰)ᵀ (polar decomposition, by SVD, reflections
//     removed). Linear shape matching, one cluster per body.
//   PBD (eq. 3):             v ← γ v* + (1 − γ) (g − x) / h
//     g = x* projected `iterations` times onto the body's distance (every edge) and volume
//     (every tetrahedron) constraints, each correction scaled by k' = 1 − (1 − k)^(1/iterations)
//     so that the stiffness k does not depend on the iteration count (Müller et al. 2007).
//
// Reading the paper's ṽ in eq. 2 as v*: with ṽ = v a body at rest would lose the velocity
// gravity gives it in the step. Under any rigid motion g = x* exactly: no internal force.
//
// The goals are weighted by the nodes' masses, or by `weightInverseMass` when given: the world
// weighs nodes held on a support (models/supports.h) 1000× heavier in shape matching, so the
// shape is fitted to where the support holds them rather than sinking with the rest of the
// body. PBD instead projects each supported node onto its support's plane (n·x ≥ n·x_now +
// h v_target) in every iteration, among its own constraints: the rest of the body then rests on
// the held nodes within the same projections. (A PBD jelly on the ground jittered at 1 m/s and
// settled short without; with, it rests within 5 % at k = 1, 20 iterations. Below k = 1, PBD
// softens a mesh far more than k says: k = 0.5 rests 40 % short.)
#pragma once

#include "solver/solver_state.h"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace tandem {

// A node that must not go below a plane this step: n·x ≥ minimum (PBD's contacts, from the
// supports its nodes rested on last step; models/supports.h).
struct SupportPlane {
  int32_t node = 0;  // local index
  Vec3 normal = Vec3::UnitY();
  double minimum = 0.0;
};

// What PBD's constraints hold, computed once when the body is made: each edge with its rest
// length and each tetrahedron with its rest volume times six (the signed triple product), in the
// order the projections take them, by colour (solver/graph_colouring.h): edges, and tetrahedra,
// next to each other in it share no node, so the processor can overlap their projections where
// in the mesh's order each waited on the last one's square root and division (the PBD jelly was a
// third of the paper's jelly scene). Kept in that order, so the projections read them in turn.
struct PositionBasedRest {
  struct Edge {
    std::array<int32_t, 2> node;  // local indices
    double length;
  };
  struct Tetrahedron {
    std::array<int32_t, 4> node;  // local indices
    double sixVolume;
  };
  std::vector<Edge> edges;
  std::vector<Tetrahedron> tetrahedra;
};
PositionBasedRest positionBasedRest(std::span<const Vec3> restPositions, std::span<const std::array<int32_t, 2>> edges,
                                    std::span<const std::array<int32_t, 4>> tetrahedra);

// Working memory of the step's paradigms, kept between steps so that the step allocates nothing
// once its sizes have been reached.
struct PositionBasedScratch {
  std::vector<Vec3> predicted, goals;
  std::vector<double> weightInverseMass, supportPush;
  std::vector<SupportPlane> supports;
};

struct PositionBasedBody {
  int32_t firstNode = 0;
  int32_t nodeCount = 0;
  std::span<const Vec3> restPositions;                      // local indices
  std::span<const std::array<int32_t, 2>> edges;           // local indices
  std::span<const std::array<int32_t, 4>> tetrahedra;      // local indices
  const PositionBasedRest* rest = nullptr;                 // PBD: of these edges and tetrahedra
  double stiffness = 1.0;  // k
  double damping = 0.0;    // γ
  int iterations = 4;      // PBD
  // The goals' weights as inverse masses (local indices); the nodes' own when empty. Nodes held
  // on a support count heavier, so the shape is fitted to where the support holds them.
  std::span<const double> weightInverseMass;
  // PBD: planes projected with the other constraints in every iteration; `supportPush` (per
  // node, when given) receives how far along its normal each node was pushed in all.
  std::span<const SupportPlane> supports;
  std::span<double> supportPush;
};

// Shape matching's goals g for predicted positions `predicted` (local indices), into `goals`.
void shapeMatchingGoals(const PositionBasedBody& body, std::span<const Vec3> predicted,
                        std::span<const double> inverseMass, std::span<Vec3> goals);

// PBD's goals: `predicted` projected onto the distance and volume constraints, into `goals`.
void positionBasedGoals(const PositionBasedBody& body, std::span<const Vec3> predicted,
                        std::span<const double> inverseMass, std::span<Vec3> goals);

// Applies eq. 2 or eq. 3 to the body's nodes; `nodes.velocity` holds v* on entry. `scratch`
// holds the predicted positions and goals.
void applyShapeMatching(const PositionBasedBody& body, NodeArrays& nodes, double timeStep,
                        PositionBasedScratch& scratch);
void applyPositionBasedDynamics(const PositionBasedBody& body, NodeArrays& nodes, double timeStep,
                                PositionBasedScratch& scratch);

}  // namespace tandem
