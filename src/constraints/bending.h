// Bending: resists folding across an edge shared by two triangles (paper §4.5).
//
// Derivation. For the hinge edge (x_i, x_j) with wing nodes x_L and x_R, let the edge midpoint
// be x_C = (x_i + x_j)/2 and the wing midpoint x_D = (x_L + x_R)/2. The paper's constraint is
// the dot product of the two wings seen from the edge midpoint, held at its rest value; Tandem
// divides it by the rest edge length L so that C is in metres and λ in N·s, as for the
// other rows:
//
//   C  = [ (x_L − x_C) · (x_R − x_C) − C⁰ ] / L
//   Ċ  = [ v_L·(x_R − x_C) + v_R·(x_L − x_C) − (v_i + v_j)·(x_D − x_C) ] / L
//   J  = [ −(x_D − x_C)ᵀ, −(x_D − x_C)ᵀ, (x_R − x_C)ᵀ, (x_L − x_C)ᵀ ] / L   (i, j, L, R)
//   K  = Σₖ mₖ⁻¹ |Jₖ|²,   effective mass K⁻¹
//   λ ∈ [−F h, F h]: F (newtons) is the bending strength
//
// Soft, not rigid. The paper's row is rigid (bias β C, the paper's −β|n_L·n_R − n⁰_L·n⁰_R| having
// one sign whatever the direction of the error) and bounded, and a rigid row that saturates at
// its bound switches between ±F h like a relay, which sustains oscillations: a cloth draped
// over an edge keeps swinging. Tandem makes the row a damped spring on C of natural frequency
// f and damping ratio ζ (Box2D v3's soft step, independent of the masses):
//   ω = 2π f,  a₁ = 2ζ + h ω,  a₂ = h ω a₁,  a₃ = 1 / (1 + a₂)
//   Δλ = −a₂ a₃ K⁻¹ (Ċ + (ω / a₁) C) − a₃ λ,   then the bound on λ
// An infinite frequency gives back the paper's rigid row (bias β C, no softening).
//
// Warm start across a turn. Each (sub)step starts from the last one's λ, but the Jacobian has
// changed since: the fold turns and its wings swing. λ applied along the new J is an impulse no
// sweep found, and what the row may give, F h, is large against a fine cloth's nodes (0.05 N for
// 20 ms on the 11 mg nodes of a 201 × 201 cloth: 90 m/s); its skirt, whipping past the sphere at
// 15 m/s (ten edge lengths a substep), was kicked by warm starts along turned wings faster than
// K = 2 sweeps a substep took the kicks back, and diverged. So the impulse itself is carried, not
// its coefficient: of the impulses the new row can give, Jᵀ λ', the one whose velocity change is
// nearest in the mass metric W to last step's W J₀ᵀ λ,
//   λ' = (J W J₀ᵀ / J W Jᵀ) λ,   then bounded to ±F h,
// λ itself while J does not change (nor the masses), less the further the wings have swung.
// Measured (`GAUNTLET_ONLY="cloth 201" build/bench/gauntlet_study 2:4`, thirty-first session):
// the 201 × 201 cloth on the sphere at K = 2 with 4 substeps diverged at step 32 and now drapes
// (4.2 % worst stretch after contact); not warm starting the bending rows at all did too, and
// carrying the impulse keeps what the warm start gives a cloth at rest.
//
// Σ J = [−2(x_D − x_C) + (x_R − x_C) + (x_L − x_C)] / L = 0, so momentum is conserved.
// Like the paper's, this C is quadratic in the fold angle near a flat rest state: the rows
// act once the cloth has started to fold, and grow stiffer as it folds further.
#pragma once

#include "solver/solver_state.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace tandem {

struct BendingRow {
  // Definition: node = {i, j, left, right}
  std::array<int32_t, 4> node{};
  double restDot = 0.0;         // C⁰, m²
  double restEdgeLength = 1.0;  // L, m
  double maxForce = 0.0;        // N
  double frequency = std::numeric_limits<double>::infinity();  // Hz; infinite: rigid, as the paper
  double dampingRatio = 1.0;
  // Per step
  std::array<Vec3, 4> jacobian{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  double effectiveMass = 0.0;
  double bias = 0.0;
  double massScale = 1.0;     // a₂ a₃
  double impulseScale = 0.0;  // a₃
  double maxImpulse = 0.0;
  double lambda = 0.0;
};

inline double bendingDot(const Vec3& xi, const Vec3& xj, const Vec3& xl, const Vec3& xr) {
  const Vec3 center = 0.5 * (xi + xj);
  return (xl - center).dot(xr - center);
}

inline double bendingError(const BendingRow& row, std::span<const Vec3> x) {
  return (bendingDot(x[row.node[0]], x[row.node[1]], x[row.node[2]], x[row.node[3]]) - row.restDot) /
         row.restEdgeLength;
}

inline void prepareBending(BendingRow& row, const NodeArrays& nodes, double timeStep, double biasRate) {
  const auto& x = nodes.position;
  const Vec3 center = 0.5 * (x[row.node[0]] + x[row.node[1]]);
  const Vec3 wings = 0.5 * (x[row.node[2]] + x[row.node[3]]);
  const double scale = 1.0 / row.restEdgeLength;
  const std::array<Vec3, 4> previousJacobian = row.jacobian;
  row.jacobian = {-(wings - center) * scale, -(wings - center) * scale, (x[row.node[3]] - center) * scale,
                  (x[row.node[2]] - center) * scale};
  const double inverseMass = nodeInverseMassSum(row.node, row.jacobian, nodes.inverseMass);
  row.effectiveMass = inverseMass > 1e-12 ? 1.0 / inverseMass : 0.0;
  if (std::isinf(row.frequency)) {  // rigid, as the paper
    row.bias = biasRate * bendingError(row, x);
    row.massScale = 1.0;
    row.impulseScale = 0.0;
  } else {
    const double omega = 2 * 3.14159265358979323846 * row.frequency;
    const double a1 = 2 * row.dampingRatio + timeStep * omega;
    const double a2 = timeStep * omega * a1;
    const double a3 = 1.0 / (1.0 + a2);
    row.bias = omega / a1 * bendingError(row, x);
    row.massScale = a2 * a3;
    row.impulseScale = a3;
  }
  row.maxImpulse = row.maxForce * timeStep;
  // The warm start: last (sub)step's impulse carried onto the new Jacobian (derivation above).
  double carried = 0.0;
  for (size_t k = 0; k < 4; ++k) carried += nodes.inverseMass[row.node[k]] * row.jacobian[k].dot(previousJacobian[k]);
  row.lambda = std::clamp(row.lambda * carried * row.effectiveMass, -row.maxImpulse, row.maxImpulse);
}

inline void warmStartBending(const BendingRow& row, SolverContext& ctx) {
  if (row.effectiveMass != 0.0) applyNodeImpulse(row.node, row.jacobian, row.lambda, ctx);
}

inline void solveBending(BendingRow& row, SolverContext& ctx, SweepStats& stats) {
  if (row.effectiveMass == 0.0) return;
  double rate = row.bias;
  for (size_t k = 0; k < 4; ++k) rate += row.jacobian[k].dot(ctx.velocity[row.node[k]]);
  const double previous = row.lambda;
  row.lambda = std::clamp(previous - row.massScale * row.effectiveMass * rate - row.impulseScale * previous,
                          -row.maxImpulse, row.maxImpulse);
  const double delta = row.lambda - previous;
  applyNodeImpulse(row.node, row.jacobian, delta, ctx);
  stats.add(delta);
}

}  // namespace tandem
