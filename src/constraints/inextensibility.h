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
#pragma once

#include <tandem/world.h>

#include "solver/solver_state.h"

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
}

inline void warmStartInextensibility(const InextensibilityRow& row, SolverContext& ctx) {
  if (row.effectiveMass != 0.0) applyNodeImpulse(row.node, row.jacobian, row.lambda, ctx);
}

inline void solveInextensibility(InextensibilityRow& row, SolverContext& ctx, SweepStats& stats) {
  if (row.effectiveMass == 0.0) return;
  stats.add(solveNodeRow(row.node, row.jacobian, row.effectiveMass, row.bias, row.stepLambdaMin,
                         row.stepLambdaMax, row.lambda, ctx));
}

}  // namespace tandem
