// Grab: a point of a rigid body, or a barycentric point of a deformable, pulled towards a
// moving target by a damped spring with a force bound: the mouse's grip in the viewer, or a
// user's hand. It is a row of the interleaved solve like any other, so whatever the grabbed
// point is tied to (the cloth's other rows, the sphere under it) answers in the same step.
//
// Derivation: the vector constraint of a fixed point or an anchor, made soft. With p the
// grabbed point (p = Σ wₖ xₖ on a deformable; p = c + a,
// a = R r, on a rigid body) and y the target:
//
//   C  = p − y_old                    (3 rows, metres, at the start of the step)
//   Ċ  = ṗ − u,   u = (y_new − y_old) / h, the target's velocity over the step
//   K  = Σ wₖ² mₖ⁻¹ I                         (deformable point)
//   K  = m⁻¹ I − [a]ₓ I⁻¹ [a]ₓ                 (rigid point; symmetric, positive)
//
// A spring k = m_s ω², damper c = 2 ζ m_s ω (ω = 2π f) on C, integrated implicitly, turns the
// rigid row Δλ = −K⁻¹ (Ċ + β C) into the soft one (Catto's soft constraints, GDC 2011):
//
//   γ = 1 / (h (c + h k)),   biasRate = k / (c + h k)
//   Δλ = −(K + γ I)⁻¹ (Ċ + biasRate C + γ λ),   λ ∈ ball(|λ| ≤ maxForce·h)
//
// m_s is the mass the hand moves: a rigid body's mass, or a deformable's whole mass (a cloth
// lifted by one node hangs from it, so the spring must carry all of it). Held still against
// gravity, Δλ = 0 and λ = m_s g h give the sag C = −γ λ / biasRate = −g / ω² whatever is held;
// maxForce keeps a grab from flinging anything or tearing it through a wall. The row is never
// stiffer than the rigid one (γ > 0), so it is stable at any f. λ is the impulse on the grabbed
// point; on a rigid body it acts at a: v ← v + m⁻¹ Δλ, ω ← ω + I⁻¹ (a × Δλ).
#pragma once

#include "constraints/fixed_point.h"  // clampToBall
#include "solver/solver_state.h"

#include <Eigen/LU>

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace tandem {

struct GrabRow {
  // Definition
  bool active = false;             // released grabs keep their slot until it is reused
  std::array<int32_t, 4> node{};   // deformable point: nodes and weights (unused: weight 0)
  std::array<double, 4> weight{};
  int32_t body = -1;               // rigid point: the body, and r in its frame about the centre of mass
  Vec3 localPoint = Vec3::Zero();
  Vec3 target = Vec3::Zero();          // where the point should go by the end of this step
  Vec3 previousTarget = Vec3::Zero();  // where the target was at the start
  double springMass = 0.0;  // m_s, kg
  double frequency = 5.0;   // Hz
  double dampingRatio = 1.0;
  double maxForce = 0.0;  // N
  // Per step
  Vec3 offset = Vec3::Zero();  // a = R r
  Mat3 effectiveMass = Mat3::Zero();  // (K + γ I)⁻¹, zero when nothing can move
  Vec3 bias = Vec3::Zero();  // biasRate C − u
  double softness = 0.0;     // γ
  double maxImpulse = 0.0;
  Vec3 lambda = Vec3::Zero();
  Vec3 stepImpulse = Vec3::Zero();  // summed over the step's substeps: what is reported

  bool onRigid() const { return body >= 0; }

  Vec3 point(std::span<const Vec3> positions, const RigidSolverState* rigid) const {
    if (rigid) return rigid->centerOfMass + rigid->orientation * localPoint;
    return barycentricSum(node, weight, positions);
  }
};

inline void prepareGrab(GrabRow& row, const NodeArrays& nodes, std::span<const RigidSolverState> rigid,
                        double timeStep) {
  Mat3 k = Mat3::Zero();
  if (row.onRigid()) {
    const RigidSolverState& body = rigid[row.body];
    row.offset = body.orientation * row.localPoint;
    k = body.pointCompliance(row.offset);
  } else {
    double inverseMass = 0.0;
    for (int j = 0; j < 4; ++j) inverseMass += row.weight[j] * row.weight[j] * nodes.inverseMass[row.node[j]];
    k = inverseMass * Mat3::Identity();
  }
  const double omega = 2.0 * std::numbers::pi * row.frequency;
  const double stiffness = row.springMass * omega * omega;
  const double damping = 2.0 * row.dampingRatio * row.springMass * omega;
  row.softness = 1.0 / (timeStep * (damping + timeStep * stiffness));
  row.effectiveMass.setZero();
  if (k.norm() > 0) row.effectiveMass = (k + row.softness * Mat3::Identity()).inverse();
  const Vec3 error = row.point(nodes.position, row.onRigid() ? &rigid[row.body] : nullptr) - row.previousTarget;
  const double biasRate = stiffness / (damping + timeStep * stiffness);
  row.bias = biasRate * error - (row.target - row.previousTarget) / timeStep;
  row.maxImpulse = row.maxForce * timeStep;
}

inline Vec3 grabVelocity(const GrabRow& row, const SolverContext& ctx) {
  if (row.onRigid()) return ctx.rigid[row.body].velocityAt(row.offset);
  return barycentricSum(row.node, row.weight, ctx.velocity);
}

inline void applyGrabImpulse(const GrabRow& row, const Vec3& impulse, SolverContext& ctx) {
  if (row.onRigid()) {
    ctx.rigid[row.body].applyImpulse(impulse, row.offset);
    return;
  }
  for (int k = 0; k < 4; ++k) ctx.velocity[row.node[k]] += (row.weight[k] * ctx.inverseMass[row.node[k]]) * impulse;
}

inline void warmStartGrab(const GrabRow& row, SolverContext& ctx) { applyGrabImpulse(row, row.lambda, ctx); }

inline void solveGrab(GrabRow& row, SolverContext& ctx, SweepStats& stats) {
  if (row.effectiveMass.isZero()) return;
  const Vec3 previous = row.lambda;
  const Vec3 step = -(row.effectiveMass * (grabVelocity(row, ctx) + row.bias + row.softness * previous));
  row.lambda = clampToBall(previous + step, row.maxImpulse);
  const Vec3 delta = row.lambda - previous;
  applyGrabImpulse(row, delta, ctx);
  for (int k = 0; k < 3; ++k) stats.add(delta[k]);
}

}  // namespace tandem
