// The rigid state Tandem's rows act on: a body jointed to the still world responds to an
// impulse only in the directions its joints leave free (src/solver/solver_state.h).
#include "solver/solver_state.h"

#include <gtest/gtest.h>

namespace tandem {
namespace {

struct HingedBody {
  RigidSolverState state;
  Vec3 pivot{0.3, -0.1, 0.05};
  Vec3 axis = Vec3(0.2, 0.1, 1.0).normalized();
  Mat3 inertia;

  HingedBody() {
    state.inverseMass = 1.0 / 2.5;
    const Mat3 rotation = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
    inertia = rotation * Vec3(0.1, 0.25, 0.4).asDiagonal() * rotation.transpose();
    state.inverseInertia = inertia.inverse();
    state.centerOfMass = Vec3(0.1, 0.2, -0.1);
    state.restrictMotion(lockedRows());
  }

  // The hinge's rows as Bullet's joint holds them: the pivot still, no turning across the axis.
  RigidSolverState::LockedRows lockedRows() const {
    RigidSolverState::LockedRows rows(5, 6);
    const Vec3 across1 = axis.unitOrthogonal(), across2 = axis.cross(across1);
    rows.block<3, 3>(0, 0) = Mat3::Identity();
    rows.block<3, 3>(0, 3) = -crossMatrix(pivot - state.centerOfMass);
    rows.row(3) << 0, 0, 0, across1.transpose();
    rows.row(4) << 0, 0, 0, across2.transpose();
    return rows;
  }
};

TEST(RigidSolverState, AHingedBodyTurnsAboutItsAxisAsTheLeverLawSays) {
  HingedBody hinged;
  EXPECT_EQ(hinged.state.freedoms, 1);
  const Vec3 point(0.5, 0.4, 0.2), impulse(1.0, -2.0, 0.5);
  const Vec3 offset = point - hinged.state.centerOfMass;
  hinged.state.applyImpulse(impulse, offset);
  // ω = a (a · ((x − p) × P)) / I_p, I_p = aᵀ I a + m |a × (c − p)|² (parallel axes), v = ω × (c − p).
  const Vec3 lever = hinged.state.centerOfMass - hinged.pivot;
  const double axisInertia = hinged.axis.dot(hinged.inertia * hinged.axis) + 2.5 * hinged.axis.cross(lever).squaredNorm();
  const Vec3 angular = hinged.axis * hinged.axis.dot((point - hinged.pivot).cross(impulse)) / axisInertia;
  EXPECT_LT((hinged.state.angularVelocity - angular).norm(), 1e-12);
  EXPECT_LT((hinged.state.linearVelocity - angular.cross(lever)).norm(), 1e-12);
  // The pivot does not move.
  EXPECT_LT(hinged.state.velocityAt(hinged.pivot - hinged.state.centerOfMass).norm(), 1e-12);
  // The impulse report is the impulse applied, whatever the joint took of it.
  EXPECT_LT((hinged.state.impulse - impulse).norm(), 1e-15);
}

TEST(RigidSolverState, PointComplianceOfAJointedBodyIsItsResponse) {
  HingedBody hinged;
  const Vec3 offset(0.2, 0.3, -0.4);
  const Mat3 compliance = hinged.state.pointCompliance(offset);
  EXPECT_LT((compliance - compliance.transpose()).norm(), 1e-14);
  for (int axis = 0; axis < 3; ++axis) {
    RigidSolverState probe = hinged.state;
    probe.applyImpulse(Vec3::Unit(axis), offset);
    EXPECT_LT((probe.velocityAt(offset) - compliance.col(axis)).norm(), 1e-12);
  }
  // Rank one: only the tangent of the circle about the axis moves.
  const Vec3 tangent = hinged.axis.cross(offset + hinged.state.centerOfMass - hinged.pivot);
  EXPECT_NEAR(compliance.trace(), tangent.dot(compliance * tangent) / tangent.squaredNorm(), 1e-12);
}

TEST(RigidSolverState, FreeAndFixedBodies) {
  HingedBody free;
  free.state.restrictMotion(RigidSolverState::LockedRows(0, 6));
  EXPECT_EQ(free.state.freedoms, 6);
  const Vec3 offset(0.1, -0.2, 0.3), impulse(0.0, 1.0, 2.0);
  free.state.applyImpulse(impulse, offset);
  EXPECT_LT((free.state.linearVelocity - impulse / 2.5).norm(), 1e-14);
  EXPECT_LT((free.state.angularVelocity - free.state.inverseInertia * offset.cross(impulse)).norm(), 1e-12);

  HingedBody fixed;
  fixed.state.restrictMotion(RigidSolverState::LockedRows::Identity(6, 6));
  EXPECT_EQ(fixed.state.freedoms, 0);
  fixed.state.applyImpulse(impulse, offset);
  EXPECT_EQ(fixed.state.linearVelocity.norm() + fixed.state.angularVelocity.norm(), 0.0);
  EXPECT_EQ(fixed.state.pointCompliance(offset).norm(), 0.0);
}

}  // namespace
}  // namespace tandem
