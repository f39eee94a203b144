// Anchor: a point of a deformable (a node, or a barycentric point of up to four nodes) held to
// a point fixed in a rigid body. Two-way: the body is pulled as hard as the deformable.
//
// Derivation (paper §4.1, made rigid-grade). Let the deformable point be p = Σₖ wₖ xₖ with
// Σ wₖ = 1, the body's centre of mass c, orientation R and the anchor's body-frame point r,
// so its world offset is a = R r. The paper's scalar row along the separation direction
// vanishes when the anchor is satisfied; Tandem uses the vector constraint, three rows solved
// as one 3×3 block:
//
//   C  = Σ wₖ xₖ − (c + a)                               (3 rows, metres)
//   Ċ  = Σ wₖ vₖ − v_b − ω × a = Σ wₖ vₖ − v_b + [a]ₓ ω
//   J  = [ w₁ I … wₙ I | −I | [a]ₓ ]     (nodes | body linear | body angular)
//   K  = J M⁻¹ Jᵀ = (Σ wₖ² mₖ⁻¹ + m_b⁻¹) I − [a]ₓ I_b⁻¹ [a]ₓ     (symmetric, positive)
//   bias b = β C,   β = baumgarte / h
//   Δλ = −K⁻¹ (Ċ + b),   λ ∈ ball(|λ| ≤ maxForce·h)   (λ: impulse on the deformable, N·s)
//   vₖ ← vₖ + wₖ mₖ⁻¹ Δλ;   the body gets −Δλ at a:
//   v_b ← v_b − m_b⁻¹ Δλ,   ω ← ω − I_b⁻¹ (a × Δλ)
//
// Solving the block exactly makes a single anchor converge in one sweep whatever the mass
// ratio between the body and the nodes. Static, kinematic and sleeping bodies enter with
// m_b⁻¹ = 0 and I_b⁻¹ = 0 (kinematic bodies still bring their velocity).
#pragma once

#include "constraints/fixed_point.h"  // clampToBall
#include "solver/solver_state.h"

#include <Eigen/LU>

#include <array>
#include <cmath>
#include <cstdint>

namespace tandem {

struct AnchorRow {
  // Definition
  std::array<int32_t, 4> node{};
  std::array<double, 4> weight{};  // unused entries have weight 0 and repeat node[0]
  int32_t body = 0;
  Vec3 localPoint = Vec3::Zero();  // r, in the body frame relative to its centre of mass
  double maxForce = 0.0;           // N
  bool inDirectBlock = false;  // solved by a DirectBlock, not by the PGS sweep
  // Per step
  Vec3 offset = Vec3::Zero();  // a = R r
  Mat3 effectiveMass = Mat3::Zero();  // K⁻¹, zero when nothing can move
  Vec3 bias = Vec3::Zero();
  double maxImpulse = 0.0;
  Vec3 lambda = Vec3::Zero();        // this substep's impulse, kept for warm starting
  Vec3 stepImpulse = Vec3::Zero();   // summed over the step's substeps: what is reported

  Vec3 deformablePoint(std::span<const Vec3> x) const { return barycentricSum(node, weight, x); }
  Vec3 deformableVelocity(std::span<const Vec3> v) const { return deformablePoint(v); }
};

inline Vec3 anchorError(const AnchorRow& row, std::span<const Vec3> positions, const Vec3& centerOfMass,
                        const Quat& orientation) {
  return row.deformablePoint(positions) - (centerOfMass + orientation * row.localPoint);
}

inline void prepareAnchor(AnchorRow& row, const NodeArrays& nodes, const RigidSolverState& body, double timeStep,
                          double biasRate) {
  row.offset = body.orientation * row.localPoint;
  double nodeInverseMass = 0.0;
  for (int k = 0; k < 4; ++k) nodeInverseMass += row.weight[k] * row.weight[k] * nodes.inverseMass[row.node[k]];
  const Mat3 k = nodeInverseMass * Mat3::Identity() + body.pointCompliance(row.offset);
  row.effectiveMass.setZero();
  if (k.determinant() > 1e-12 * std::pow(k.norm(), 3)) row.effectiveMass = k.inverse();
  row.maxImpulse = row.maxForce * timeStep;
  row.bias = biasRate * anchorError(row, nodes.position, body.centerOfMass, body.orientation);
}

inline void applyAnchorImpulse(const AnchorRow& row, const Vec3& impulse, SolverContext& ctx) {
  for (int k = 0; k < 4; ++k) ctx.velocity[row.node[k]] += (row.weight[k] * ctx.inverseMass[row.node[k]]) * impulse;
  ctx.rigid[row.body].applyImpulse(-impulse, row.offset);
}

inline void warmStartAnchor(const AnchorRow& row, SolverContext& ctx) { applyAnchorImpulse(row, row.lambda, ctx); }

inline void solveAnchor(AnchorRow& row, SolverContext& ctx, SweepStats& stats) {
  if (row.effectiveMass.isZero()) return;
  const Vec3 relativeVelocity =
      row.deformableVelocity(ctx.velocity) - ctx.rigid[row.body].velocityAt(row.offset);
  const Vec3 previous = row.lambda;
  row.lambda = clampToBall(previous - row.effectiveMass * (relativeVelocity + row.bias), row.maxImpulse);
  const Vec3 delta = row.lambda - previous;
  applyAnchorImpulse(row, delta, ctx);
  for (int k = 0; k < 3; ++k) stats.add(delta[k]);
}

}  // namespace tandem
