// Fixed point: a node held to a point in the world, which may move (a kinematic target).
//
// Derivation (paper eq. 8–15, made rigid-grade). The paper's scalar C = ½|x − y|² has the
// Jacobian (x − y)ᵀ, which vanishes exactly when the constraint is satisfied, so it loses its
// direction at rest. Tandem uses the vector constraint instead, three rows solved as one block:
//
//   C  = x − y                       (3 rows, metres)
//   Ċ  = v − u,   u = ẏ ≈ (y_new − y_old) / h, the target's velocity over the step
//   J  = I (3×3) on the node
//   K  = J M⁻¹ Jᵀ = m⁻¹ I,   effective mass K⁻¹ = m I
//   bias b = β C − u,   β = baumgarte / h
//   Δλ = −m (v + b),   λ ∈ ball(|λ| ≤ maxForce·h)   (λ is the impulse on the node, N·s)
//   v ← v + m⁻¹ Δλ
//
// C is evaluated at the start of the step against the target's old position y_old, so a
// moving target is followed without lag and any drift is corrected at the rate β.
#pragma once

#include "solver/solver_state.h"

#include <cstdint>

namespace tandem {

struct FixedPointRow {
  // Definition
  int32_t node = 0;
  Vec3 target = Vec3::Zero();          // where the node should be at the end of this step
  Vec3 previousTarget = Vec3::Zero();  // where it was at the start
  double maxForce = 0.0;               // N
  bool inDirectBlock = false;  // solved by a DirectBlock, not by the PGS sweep
  // Per step
  double effectiveMass = 0.0;
  double maxImpulse = 0.0;
  Vec3 bias = Vec3::Zero();
  Vec3 lambda = Vec3::Zero();  // accumulated impulse of a substep, kept for warm starting
  Vec3 stepImpulse = Vec3::Zero();  // summed over the step's substeps: what is reported
};

inline Vec3 fixedPointError(const Vec3& position, const Vec3& target) { return position - target; }

// Clamps an accumulated vector impulse to a ball: the block form of λ⁻ ≤ λ ≤ λ⁺.
inline Vec3 clampToBall(const Vec3& impulse, double radius) {
  const double norm = impulse.norm();
  return norm > radius ? Vec3(impulse * (radius / norm)) : impulse;
}

inline void prepareFixedPoint(FixedPointRow& row, const NodeArrays& nodes, double timeStep, double biasRate) {
  const double inverseMass = nodes.inverseMass[row.node];
  row.effectiveMass = inverseMass > 0 ? 1.0 / inverseMass : 0.0;
  row.maxImpulse = row.maxForce * timeStep;
  const Vec3 targetVelocity = (row.target - row.previousTarget) / timeStep;
  row.bias = biasRate * fixedPointError(nodes.position[row.node], row.previousTarget) - targetVelocity;
}

inline void warmStartFixedPoint(const FixedPointRow& row, SolverContext& ctx) {
  ctx.velocity[row.node] += ctx.inverseMass[row.node] * row.lambda;
}

inline void solveFixedPoint(FixedPointRow& row, SolverContext& ctx, SweepStats& stats) {
  if (row.effectiveMass == 0.0) return;
  Vec3& v = ctx.velocity[row.node];
  const Vec3 previous = row.lambda;
  row.lambda = clampToBall(previous - row.effectiveMass * (v + row.bias), row.maxImpulse);
  const Vec3 delta = row.lambda - previous;
  v += ctx.inverseMass[row.node] * delta;
  for (int k = 0; k < 3; ++k) stats.add(delta[k]);
}

}  // namespace tandem
