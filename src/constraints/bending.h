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
//   bias b = β C,   β = baumgarte / h   (the paper's bias, −β|n_L·n_R − n⁰_L·n⁰_R|, has one
//            sign whatever the direction of the error; Tandem's is the constraint's own error)
//   λ ∈ [−F h, F h]: F (newtons) is the bending strength
//
// Σ J = [−2(x_D − x_C) + (x_R − x_C) + (x_L − x_C)] / L = 0, so momentum is conserved.
// Like the paper's, this C is quadratic in the fold angle near a flat rest state: the rows
// act once the cloth has started to fold, and grow stiffer as it folds further.
#pragma once

#include "solver/solver_state.h"

#include <array>
#include <cstdint>

namespace tandem {

struct BendingRow {
  // Definition: node = {i, j, left, right}
  std::array<int32_t, 4> node{};
  double restDot = 0.0;         // C⁰, m²
  double restEdgeLength = 1.0;  // L, m
  double maxForce = 0.0;        // N
  // Per step
  std::array<Vec3, 4> jacobian{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  double effectiveMass = 0.0;
  double bias = 0.0;
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
  row.jacobian = {-(wings - center) * scale, -(wings - center) * scale, (x[row.node[3]] - center) * scale,
                  (x[row.node[2]] - center) * scale};
  const double inverseMass = nodeInverseMassSum(row.node, row.jacobian, nodes.inverseMass);
  row.effectiveMass = inverseMass > 1e-12 ? 1.0 / inverseMass : 0.0;
  row.bias = biasRate * bendingError(row, x);
  row.maxImpulse = row.maxForce * timeStep;
  if (row.effectiveMass == 0.0) row.lambda = 0.0;
}

inline void warmStartBending(const BendingRow& row, SolverContext& ctx) {
  if (row.effectiveMass != 0.0) applyNodeImpulse(row.node, row.jacobian, row.lambda, ctx);
}

inline void solveBending(BendingRow& row, SolverContext& ctx, SweepStats& stats) {
  if (row.effectiveMass == 0.0) return;
  stats.add(solveNodeRow(row.node, row.jacobian, row.effectiveMass, row.bias, -row.maxImpulse, row.maxImpulse,
                         row.lambda, ctx));
}

}  // namespace tandem
