// Co-rotational linear FEM on tetrahedra: forces and the stiffness the implicit step needs.
//
// Per tetrahedron (nodes x₀…x₃, rest edge matrix D_m = [X₁−X₀, X₂−X₀, X₃−X₀], rest volume V):
//   F = D_s D_m⁻¹ with D_s = [x₁−x₀, x₂−x₀, x₃−x₀];  R = the rotation of F (polar decomposition)
//   ε = ½ (Rᵀ F + Fᵀ R) − I                        (small strain, measured in the rotated frame)
//   P = R (2μ ε + λ tr(ε) I)                        (Lamé μ = E / 2(1+ν), λ = E ν / (1+ν)(1−2ν))
//   [f₁ f₂ f₃] = −V P D_m⁻ᵀ,  f₀ = −(f₁ + f₂ + f₃)
// P is the exact gradient of the energy V (μ |S − I|² + ½ λ tr(S − I)²), S = Rᵀ F, so the
// forces are conservative. Under a rigid motion F = R, ε = 0: no force. The stiffness
// K = ∂f/∂x is taken with R held (the co-rotational approximation):
//   δF = δD_s D_m⁻¹,  δP = R (2μ sym(Rᵀ δF) + λ tr(Rᵀ δF) I),  δ[f₁ f₂ f₃] = −V δP D_m⁻ᵀ
// K is symmetric negative semi-definite and zero on rigid translations. Written with the
// gradients g_a of the barycentric coordinates (F = Σ x_a g_aᵀ: g₁…g₃ the rows of D_m⁻¹,
// g₀ = −(g₁ + g₂ + g₃)), f_a = −V P g_a, and each 3×3 block is
//   K_ab = ∂f_a / ∂x_b = −V (μ (g_a · g_b) I + μ R g_b (R g_a)ᵀ + λ R g_a (R g_b)ᵀ).
// The step that uses it is in models/implicit_solve.h.
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

struct FemElements {
  std::vector<FemTetrahedron> tetrahedra;
  double mu = 0.0;      // Pa
  double lambda = 0.0;  // Pa
  // The node pairs the tetrahedra couple, each once with its lower node first (global indices:
  // {a, b}, a ≤ b), and per tetrahedron the pair of each of its 10 blocks (a, b) with a ≤ b
  // locally, in the order the two loops over a and b ≥ a meet them: the stiffness goes out summed
  // per pair (K_ba = K_abᵀ, so the pairs with a > b are not kept).
  std::vector<std::array<int32_t, 2>> pairs;
  std::vector<std::array<int32_t, 10>> pairOfBlock;
};

// The tetrahedra's rest data; Young's modulus E (Pa) and Poisson's ratio ν.
FemElements makeFemElements(int32_t firstNode, std::span<const Vec3> restPositions,
                            std::span<const std::array<int32_t, 4>> tetrahedra, double youngsModulus,
                            double poissonRatio);

// Elastic forces at `position` added to `force` (indexed by global node minus `offset`); the
// rotation of each tetrahedron written to `rotations` when it is not empty.
void addFemForces(const FemElements& elements, std::span<const Vec3> position, std::span<Vec3> force,
                  int32_t offset, std::span<Mat3> rotations = {});

// −h² K with the given rotations, as 3×3 node-pair blocks (global indices), one per coupled pair
// {a, b} with a ≤ b: the block of (b, a) is the transpose of (a, b)'s.
void addFemStiffnessBlocks(const FemElements& elements, std::span<const Mat3> rotations, double timeStep,
                           std::vector<NodePairStiffness>& out);

}  // namespace tandem
