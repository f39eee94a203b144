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

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

// A rigid body as the row solver sees it during one step. Velocities are loaded from (and
// stored back to) the Bullet solver body before and after each of Tandem's sweeps.
//
// Joints to the still world. A body hinged (or fixed) to a static or kinematic body can move
// only in the directions its joints leave free: (v, ω) = G q̇ for a basis G (6 × k, velocities
// of the centre of mass and angular, k = `freedoms`). Its response to an impulse P at offset r
// is then not the free body's, Δ(v, ω) = 𝕄⁻¹ (P, r × P) with 𝕄 = diag(m I, I), but the
// constrained one, Δ(v, ω) = G (Gᵀ 𝕄 G)⁻¹ Gᵀ (P, r × P): a wheel on an axle turns and does not
// move off it. Tandem's rows use that response, so their impulses are the ones the joint lets
// act: with the free response, each sweep pushed the wheel off its pivot, Bullet's joint rows
// pulled it back in the next iteration, the two never agreed within K iterations, and the
// wheel under a rope's load sagged 8 mm (docs/solver.md). A body with a joint to another
// movable body stays free (k = 6, G = I): its joint is Bullet's to solve.
struct RigidSolverState {
  Vec3 linearVelocity = Vec3::Zero();
  Vec3 angularVelocity = Vec3::Zero();
  Vec3 loadedLinearVelocity = Vec3::Zero();  // as loaded, so only the change is stored back
  Vec3 loadedAngularVelocity = Vec3::Zero();
  Vec3 centerOfMass = Vec3::Zero();
  Quat orientation = Quat::Identity();
  double inverseMass = 0.0;                 // 0 for static, kinematic and sleeping bodies
  Mat3 inverseInertia = Mat3::Zero();       // world frame
  int freedoms = 6;                         // k: 6 for a free body, fewer when jointed to the world
  Mat6 motionBasis = Mat6::Identity();      // G in its first k columns
  Mat6 reducedInverseMass = Mat6::Zero();   // (Gᵀ 𝕄 G)⁻¹ in its top-left k × k corner
  Vec3 impulse = Vec3::Zero();              // total applied by Tandem's rows this step
  Vec3 angularImpulse = Vec3::Zero();       // about the centre of mass

  bool isJointed() const { return freedoms < 6; }

  Vec3 velocityAt(const Vec3& offset) const { return linearVelocity + angularVelocity.cross(offset); }

  // Gᵀ (P, r × P) / P: the generalised impulse of a unit impulse along each axis at `offset`,
  // in the body's free directions (k × 3; only the first k rows used).
  Eigen::Matrix<double, 6, 3> freeDirectionsOfPoint(const Vec3& offset) const {
    Eigen::Matrix<double, 6, 3> point;
    point.topRows<3>() = Mat3::Identity();
    point.bottomRows<3>() = crossMatrix(offset);
    return motionBasis.transpose() * point;
  }

  // The inverse effective mass of the body's point at `offset` from its centre of mass:
  // Δv = (m⁻¹ I − [a]ₓ I⁻¹ [a]ₓ) P for an impulse P there; for a jointed body,
  // Δv = Uᵀ (Gᵀ 𝕄 G)⁻¹ U P with U = Gᵀ (I; [a]ₓ).
  Mat3 pointCompliance(const Vec3& offset) const {
    if (isJointed()) {
      const Eigen::Matrix<double, 6, 3> u = freeDirectionsOfPoint(offset);
      const int k = freedoms;
      return u.topRows(k).transpose() * reducedInverseMass.topLeftCorner(k, k) * u.topRows(k);
    }
    const Mat3 cross = crossMatrix(offset);
    return inverseMass * Mat3::Identity() - cross * inverseInertia * cross;
  }

  // The velocity change of a generalised impulse (F, τ) about the centre of mass.
  void applyGeneralisedImpulse(const Vec3& force, const Vec3& torque) {
    if (inverseMass == 0.0 && !isJointed()) return;  // static, kinematic or asleep: it does not move
    if (isJointed()) {
      const int k = freedoms;
      Vec6 generalised;
      generalised << force, torque;
      const Vec6 change = motionBasis.leftCols(k) * (reducedInverseMass.topLeftCorner(k, k) *
                                                     (motionBasis.leftCols(k).transpose() * generalised));
      linearVelocity += change.head<3>();
      angularVelocity += change.tail<3>();
      return;
    }
    linearVelocity += inverseMass * force;
    angularVelocity += inverseInertia * torque;
  }

  void applyImpulse(const Vec3& p, const Vec3& offset) {
    const Vec3 angular = offset.cross(p);
    impulse += p;
    angularImpulse += angular;
    applyGeneralisedImpulse(p, angular);
  }

  // Rows of (v, ω) that joints to the still world hold at zero: at most four joints' worth.
  using LockedRows = Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor, 24, 6>;
  // Restricts the body to the null space of `lockedRows`; no rows: free again.
  void restrictMotion(const LockedRows& lockedRows);
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
  // The nodes' velocities before the warm start: what the swept edges' geometric stiffness
  // measures the rows' velocity change from (constraints/inextensibility.h).
  std::span<const Vec3> startVelocity = {};
  // Which of the (sub)step's K sweeps this is, from 0 (solver/swept_edge_solve.h runs in the first
  // two but not the last, and makes its list of rows in the first).
  int iteration = 0;
  int iterations = 1;  // K
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
