// Inextensibility: two nodes kept at their rest distance L, with bounded impulses (paper §4.2).
//
// Derivation. The paper writes C = ½(|x_j − x_i|² − L²) with the unnormalised Jacobian
// ±(x_j − x_i); Tandem uses the length form, whose λ is a plain impulse in N·s so that the
// bound "maxForce" means newtons whatever the edge length:
//
//   d  = x_j − x_i,   n = d / |d|
//   C  = |d| − L                       (metres; > 0 when stretched)
//   Ċ  = n · (v_j − v_i)
//   J  = [ −nᵀ  nᵀ ]
//   K  = m_i⁻¹ + m_j⁻¹,   effective mass K⁻¹
//   bias b = β C,   β = baumgarte / h
//   Δλ = −K⁻¹ (Ċ + b),   then clamp the accumulated λ to [λ⁻, λ⁺]:
//     ResistBoth:        λ ∈ [−F h, F h]
//     ResistCompression: λ ∈ [0, F h]     (pushes the nodes apart only)
//     ResistStretch:     λ ∈ [−F h, 0]    (pulls them together only)
//   v_i ← v_i − m_i⁻¹ Δλ n,   v_j ← v_j + m_j⁻¹ Δλ n
//
// A stretched edge needs Ċ < 0, i.e. λ < 0: "resist stretch" is the negative half-range, as in
// the paper's sign convention. Σ J = 0, so these rows never change linear momentum.
//
// Geometric stiffness in the sweep. The row holds Ċ = n · (v_j − v_i) with n fixed at the
// step's start, so a sideways relative velocity u⊥ is free to first order; over the step it
// still lengthens the edge by h² |u⊥|² / 2ℓ. A taut edge of tension f = |λ| / h resists being
// turned with the stiffness K_g = (f / ℓ)(I − n nᵀ) (Tournier et al. 2015), which the direct
// blocks put into their matrix (solver/direct_block.h) and the sweep did not have: on the
// 51 × 51 cloth draped on the sphere, the bending and friction rows turned the edges of its
// hanging folds at 0.6 m/s across them, each step stretched them by 12 %, strain limiting
// pulled them back by position (41 passes every step, never converging) and the cloth buzzed
// at 0.05 m/s RMS for ever, at any K (docs/solver.md, thirteenth session). So each swept edge
// that was taut last step (λ < 0) also gets, after its row, the implicit spring of K_g on the
// velocity change the step's rows have made, u = (v_j − v_i) − (v⁰_j − v⁰_i) with v⁰ the
// velocities before the warm start: with s = h² K_g's scale = h |λ| / ℓ (kg) and the sideways
// impulse p of this step (perpendicular to n, from zero), the Gauss-Seidel update of
// s u⊥ + p = 0 is
//   δp = −(s u⊥ + p) / (s (m_i⁻¹ + m_j⁻¹) + 1),   v_i ← v_i − m_i⁻¹ δp,   v_j ← v_j + m_j⁻¹ δp
// (equal and opposite: momentum kept). Its fixed point is the block's (M + h² K_g) Δv = Jᵀ λ.
// The draped cloth then comes to rest (0.003 m/s RMS after 10 s) and the passes converge.
#pragma once

#include <tandem/world.h>

#include "solver/solver_state.h"

#include <algorithm>
#include <array>
#include <cstdint>

namespace tandem {

struct InextensibilityRow {
  // Definition
  std::array<int32_t, 2> node{};
  double restLength = 0.0;
  double lambdaMin = 0.0;  // per second of force bound: multiplied by h each step
  double lambdaMax = 0.0;
  bool inDirectBlock = false;  // solved by a DirectBlock, not by the PGS sweep
  // Per step
  std::array<Vec3, 2> jacobian{Vec3::Zero(), Vec3::Zero()};
  double effectiveMass = 0.0;
  double bias = 0.0;
  double lambda = 0.0;
  double stepLambdaMin = 0.0;
  double stepLambdaMax = 0.0;
  double sidewaysMass = 0.0;            // s = h |λ| / ℓ from last step's tension (geometric stiffness), kg
  Vec3 sidewaysImpulse = Vec3::Zero();  // p: this step's, perpendicular to the edge
};

inline double inextensibilityError(const Vec3& xi, const Vec3& xj, double restLength) {
  return (xj - xi).norm() - restLength;
}

// The force bounds (N) of a mode; the row's impulse bounds are these times h.
inline std::array<double, 2> inextensibilityForceBounds(InextensibilityMode mode, double maxForce) {
  switch (mode) {
    case InextensibilityMode::ResistCompression: return {0.0, maxForce};
    case InextensibilityMode::ResistStretch: return {-maxForce, 0.0};
    case InextensibilityMode::ResistBoth: break;
  }
  return {-maxForce, maxForce};
}

inline void prepareInextensibility(InextensibilityRow& row, const NodeArrays& nodes, double timeStep,
                                   double biasRate) {
  const Vec3 d = nodes.position[row.node[1]] - nodes.position[row.node[0]];
  const double length = d.norm();
  const double inverseMass = nodes.inverseMass[row.node[0]] + nodes.inverseMass[row.node[1]];
  if (length < 1e-12 || inverseMass == 0.0) {
    row.effectiveMass = 0.0;  // coincident or both pinned: no direction to act along
    row.lambda = 0.0;
    return;
  }
  const Vec3 n = d / length;
  row.jacobian = {-n, n};
  row.effectiveMass = 1.0 / inverseMass;
  row.bias = biasRate * (length - row.restLength);
  row.stepLambdaMin = row.lambdaMin * timeStep;
  row.stepLambdaMax = row.lambdaMax * timeStep;
  row.sidewaysMass = row.lambda < 0.0 ? -row.lambda * timeStep / length : 0.0;
  row.sidewaysImpulse.setZero();
}

inline void warmStartInextensibility(const InextensibilityRow& row, SolverContext& ctx) {
  if (row.effectiveMass != 0.0) applyNodeImpulse(row.node, row.jacobian, row.lambda, ctx);
}

// The geometric stiffness of a swept edge (above) on its nodes' velocities vᵢ, v_j, held by the
// caller; `ctx.startVelocity` holds v⁰.
inline void applyGeometricStiffness(InextensibilityRow& row, const SolverContext& ctx, Vec3& vi, Vec3& vj) {
  if (row.sidewaysMass == 0.0 || row.effectiveMass == 0.0 || ctx.startVelocity.empty()) return;
  const int32_t i = row.node[0], j = row.node[1];
  const Vec3& n = row.jacobian[1];
  Vec3 u = (vj - vi) - (ctx.startVelocity[j] - ctx.startVelocity[i]);
  u -= u.dot(n) * n;
  const double s = row.sidewaysMass;
  const double w = ctx.inverseMass[i] + ctx.inverseMass[j];
  const Vec3 delta = -(s * u + row.sidewaysImpulse) / (s * w + 1.0);
  row.sidewaysImpulse += delta;
  vi -= ctx.inverseMass[i] * delta;
  vj += ctx.inverseMass[j] * delta;
}

inline void solveGeometricStiffness(InextensibilityRow& row, SolverContext& ctx) {
  applyGeometricStiffness(row, ctx, ctx.velocity[row.node[0]], ctx.velocity[row.node[1]]);
}

// A swept edge's sweep: its row, then its geometric stiffness, on the two velocities loaded once
// (the same arithmetic as solveNodeRow's on the row, then solveGeometricStiffness).
inline void solveSweptEdge(InextensibilityRow& row, SolverContext& ctx, SweepStats& stats) {
  if (row.effectiveMass == 0.0) return;
  const int32_t i = row.node[0], j = row.node[1];
  Vec3 vi = ctx.velocity[i], vj = ctx.velocity[j];
  double jv = row.bias;
  jv += row.jacobian[0].dot(vi);
  jv += row.jacobian[1].dot(vj);
  const double previous = row.lambda;
  row.lambda = std::clamp(previous - row.effectiveMass * jv, row.stepLambdaMin, row.stepLambdaMax);
  const double delta = row.lambda - previous;
  vi += (delta * ctx.inverseMass[i]) * row.jacobian[0];
  vj += (delta * ctx.inverseMass[j]) * row.jacobian[1];
  stats.add(delta);
  applyGeometricStiffness(row, ctx, vi, vj);
  ctx.velocity[i] = vi;
  ctx.velocity[j] = vj;
}

}  // namespace tandem
