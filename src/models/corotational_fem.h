// Co-rotational linear FEM on tetrahedra, stepped by a linearised backward Euler velocity solve.
//
// Per tetrahedron (nodes x₀…x₃, rest edge matrix D_m = [X₁−X₀, X₂−X₀, X₃−X₀], rest volume V):
//   F = D_s D_m⁻¹ with D_s = [x₁−x₀, x₂−x₀, x₃−x₀];  R = the rotation of F (polar decomposition)
//   ε = ½ (Rᵀ F + Fᵀ R) − I                        (small strain, measured in the rotated frame)
//   P = R (2μ ε + λ tr(ε) I)                        (Lamé μ = E / 2(1+ν), λ = E ν / (1+ν)(1−2ν))
//   [f₁ f₂ f₃] = −V P D_m⁻ᵀ,  f₀ = −(f₁ + f₂ + f₃)
// Under a rigid motion F = R, ε = 0: no force. The stiffness K = ∂f/∂x is taken with R held
// (the co-rotational approximation), applied matrix-free:
//   δF = δD_s D_m⁻¹,  δP = R (2μ sym(Rᵀ δF) + λ tr(Rᵀ δF) I),  δ[f₁ f₂ f₃] = −V δP D_m⁻ᵀ
//
// Explicit steps of jelly-like stiffness are unstable at h = 1/50 s, so the velocity is solved
// implicitly (linearised backward Euler):
//   (M − h² K) Δv = h (f(x) + f_ext) + h² K v,   v* = v + Δv
// M − h² K is symmetric positive definite (K is negative semi-definite); conjugate gradients,
// matrix-free, warm-started from last step's Δv, with pinned nodes held at Δv = 0.
//
// The coupling solver's contacts come after this solve, which left to itself relieves a resting
// body's stress by driving its bottom nodes into the ground (at 1 m/s per step for a 0.2 m
// jelly; the contacts stop them, the stress stays, the jelly rests 12 % squashed), and at an
// impact lets the upper layers fall on through a step with nothing resisting (the energy they
// store launches the jelly higher than it fell). So the solve holds nodes on the static and
// kinematic surfaces they touched or were about to touch last step: along the surface normal n
// a held node gets the normal velocity the contact will give it, the surface's w·n less the gap
// closed in this step,
//   v*·n = w·n − max(gap, 0) / h,    held only if the free motion would go further,
// by filtered conjugate gradients (Baraff and Witkin 1998). The hold's impulse is
// c = (A Δv − b)·n; a hold that would pull (c < 0) is let go and the solve repeated, so bodies
// still lift off.


#pragma once

#include "solver/solver_state.h"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace tandem {

struct FemTetrahedron {
  std::array<int32_t, 4> node{};  // global indices
  Mat3 restInverse = Mat3::Identity();  // D_m⁻¹
  double volume = 0.0;
};

struct FemBody {
  int32_t firstNode = 0;
  int32_t nodeCount = 0;
  std::vector<FemTetrahedron> tetrahedra;
  double mu = 0.0;      // Pa
  double lambda = 0.0;  // Pa
  std::vector<Vec3> previousStep;  // last step's Δv, the solve's starting guess (local indices)
  // Surfaces the nodes touched or neared last step (local indices): normal (zero for none), the
  // gap at the step's end, and the surface's normal velocity.
  std::vector<Vec3> supportNormal;
  std::vector<double> supportGap, supportSpeed;
  int lastIterations = 0;          // conjugate-gradient iterations of the last step
};

// Builds the tetrahedra's rest data; Young's modulus E (Pa) and Poisson's ratio ν.
FemBody makeFemBody(int32_t firstNode, std::span<const Vec3> restPositions,
                    std::span<const std::array<int32_t, 4>> tetrahedra, double youngsModulus, double poissonRatio);

// Elastic forces added to `nodes.force` (global indices).
void addFemForces(const FemBody& body, NodeArrays& nodes);

// v ← v + Δv for the body's free nodes, from the implicit solve; gravity and the forces already
// in `nodes.force` (springs) are its external forces, taken explicitly.
void solveFemVelocities(FemBody& body, NodeArrays& nodes, const Vec3& gravity, double timeStep);

// −h² K at the current positions, as 3×3 node-pair blocks (global indices), for the direct block
// that solves the body's contacts and attachments with the same implicit response.
void addFemStiffness(const FemBody& body, const NodeArrays& nodes, double timeStep, std::vector<NodePairStiffness>& out);

// Records a static or kinematic surface by a node (global index) for the next solve: its normal,
// the gap at the step's end and its normal velocity. The caller clears the supports each step.
void addSupport(FemBody& body, int32_t node, const Vec3& normal, double gap, double normalSpeed);
void clearSupports(FemBody& body);

}  // namespace tandem
