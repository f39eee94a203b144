// The state the row solver reads and writes: node velocities and rigid-body velocities.
//
// Node data for every deformable body lives in one set of arrays (struct of arrays), so a row
// refers to a node by a single global index. Rigid bodies are indexed by RigidBodyId::index.
#pragma once

#include <tandem/types.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace tandem {

// [a]ₓ: the matrix with [a]ₓ b = a × b.
inline Mat3 crossMatrix(const Vec3& a) {
  Mat3 m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}

// Σ wₖ valuesₖ over a point's up to four nodes (unused entries have weight 0): the point's
// position or velocity.
inline Vec3 barycentricSum(const std::array<int32_t, 4>& node, const std::array<double, 4>& weight,
                           std::span<const Vec3> values) {
  Vec3 sum = Vec3::Zero();
  for (int k = 0; k < 4; ++k) sum += weight[k] * values[node[k]];
  return sum;
}

struct NodeArrays {
  std::vector<Vec3> position;
  std::vector<Vec3> velocity;  // during the solve: unconstrained velocity plus row impulses
  std::vector<Vec3> force;
  std::vector<double> inverseMass;

  size_t size() const { return position.size(); }
};

// A rigid body as the row solver sees it during one step. Velocities are loaded from (and
// stored back to) the Bullet solver body before and after each of Tandem's sweeps.
struct RigidSolverState {
  Vec3 linearVelocity = Vec3::Zero();
  Vec3 angularVelocity = Vec3::Zero();
  Vec3 loadedLinearVelocity = Vec3::Zero();  // as loaded, so only the change is stored back
  Vec3 loadedAngularVelocity = Vec3::Zero();
  Vec3 centerOfMass = Vec3::Zero();
  Quat orientation = Quat::Identity();
  double inverseMass = 0.0;                 // 0 for static, kinematic and sleeping bodies
  Mat3 inverseInertia = Mat3::Zero();       // world frame
  Vec3 impulse = Vec3::Zero();              // total applied by Tandem's rows this step
  Vec3 angularImpulse = Vec3::Zero();       // about the centre of mass

  Vec3 velocityAt(const Vec3& offset) const { return linearVelocity + angularVelocity.cross(offset); }

  // The inverse effective mass of the body's point at `offset` from its centre of mass:
  // Δv = (m⁻¹ I − [a]ₓ I⁻¹ [a]ₓ) P for an impulse P there.
  Mat3 pointCompliance(const Vec3& offset) const {
    const Mat3 cross = crossMatrix(offset);
    return inverseMass * Mat3::Identity() - cross * inverseInertia * cross;
  }

  void applyImpulse(const Vec3& p, const Vec3& offset) {
    const Vec3 angular = offset.cross(p);
    impulse += p;
    angularImpulse += angular;
    linearVelocity += inverseMass * p;
    angularVelocity += inverseInertia * angular;
  }
};

// A 3×3 block of stiffness between two nodes (global indices), as a direct block adds it to its
// H: the block (a, b) gets k. An elastic model hands over every (a, b) pair of its elements.
struct NodePairStiffness {
  int32_t nodeA = 0;
  int32_t nodeB = 0;
  Mat3 k = Mat3::Zero();
};

struct SolverContext {
  std::span<Vec3> velocity;
  std::span<const double> inverseMass;
  std::span<RigidSolverState> rigid;
  double timeStep = 0.0;
  double biasRate = 0.0;  // β = baumgarte / h, in 1/s
};

// Accumulates Δλ² over a sweep for the RMS reported per iteration.
struct SweepStats {
  double sumSquares = 0.0;
  long long rows = 0;
  void add(double deltaLambda) {
    sumSquares += deltaLambda * deltaLambda;
    ++rows;
  }
};

// One scalar row over N nodes, no rigid entry: the inner loop of the projected Gauss-Seidel
// sweep. Returns the clamped Δλ.
template <size_t N>
inline double solveNodeRow(const std::array<int32_t, N>& node, const std::array<Vec3, N>& jacobian,
                           double effectiveMass, double bias, double lambdaMin, double lambdaMax,
                           double& lambda, SolverContext& ctx) {
  double jv = bias;
  for (size_t k = 0; k < N; ++k) jv += jacobian[k].dot(ctx.velocity[node[k]]);
  const double previous = lambda;
  lambda = std::clamp(previous - effectiveMass * jv, lambdaMin, lambdaMax);
  const double delta = lambda - previous;
  for (size_t k = 0; k < N; ++k) ctx.velocity[node[k]] += (delta * ctx.inverseMass[node[k]]) * jacobian[k];
  return delta;
}

// Applies λ·Jᵀ to the nodes of a row (warm starting).
template <size_t N>
inline void applyNodeImpulse(const std::array<int32_t, N>& node, const std::array<Vec3, N>& jacobian,
                             double lambda, SolverContext& ctx) {
  for (size_t k = 0; k < N; ++k) ctx.velocity[node[k]] += (lambda * ctx.inverseMass[node[k]]) * jacobian[k];
}

// Σ m⁻¹ |J|² over a row's node entries.
template <size_t N>
inline double nodeInverseMassSum(const std::array<int32_t, N>& node, const std::array<Vec3, N>& jacobian,
                                 std::span<const double> inverseMass) {
  double sum = 0.0;
  for (size_t k = 0; k < N; ++k) sum += inverseMass[node[k]] * jacobian[k].squaredNorm();
  return sum;
}

}  // namespace tandem
