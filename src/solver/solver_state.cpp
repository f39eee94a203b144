#include "solver/solver_state.h"

#include <Eigen/LU>
#include <Eigen/SVD>

namespace tandem {

void RigidSolverState::restrictMotion(const LockedRows& lockedRows) {
  if (lockedRows.rows() == 0 || inverseMass == 0.0) {
    freedoms = 6;
    motionBasis.setIdentity();
    return;
  }
  // G: an orthonormal basis of the null space of the locked rows, from the right singular
  // vectors whose singular values vanish (relative to the largest).
  const Eigen::JacobiSVD<LockedRows> svd(lockedRows, Eigen::ComputeFullV);
  const auto& singular = svd.singularValues();
  const double tolerance = 1e-9 * (singular.size() > 0 ? singular[0] : 1.0);
  int rank = 0;
  for (Eigen::Index i = 0; i < singular.size(); ++i) rank += singular[i] > tolerance ? 1 : 0;
  freedoms = 6 - rank;
  motionBasis.setZero();
  motionBasis.leftCols(freedoms) = svd.matrixV().rightCols(freedoms);
  reducedInverseMass.setZero();
  if (freedoms == 0) return;
  // Gᵀ 𝕄 G with 𝕄 = diag(m I, I_world): the mass of the free directions.
  Mat6 mass = Mat6::Zero();
  mass.topLeftCorner<3, 3>() = (1.0 / inverseMass) * Mat3::Identity();
  mass.bottomRightCorner<3, 3>() = inverseInertia.inverse();
  const auto basis = motionBasis.leftCols(freedoms);
  Mat6 reducedMass = Mat6::Zero();
  reducedMass.topLeftCorner(freedoms, freedoms) = basis.transpose() * mass * basis;
  reducedInverseMass.topLeftCorner(freedoms, freedoms) = reducedMass.topLeftCorner(freedoms, freedoms).inverse();
}

}  // namespace tandem
