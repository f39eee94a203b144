// BulletWorld's internals, shared by the files that implement it (bullet_world.cpp: building
// and stepping; bullet_edit.cpp: pushing, moving, filtering and removing; bullet_snapshot.cpp:
// saving and restoring). Internal to src/bullet.
#pragma once

#include "bullet/bullet_world.h"

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionDispatch/btSimulationIslandManager.h>

#include <algorithm>
#include <memory>
#include <vector>

namespace tandem::bullet {



// Collision margin of convex hulls and triangle meshes, which Bullet puts outside the shape (m).
inline constexpr btScalar kHullMargin = 0.002;

inline btVector3 toBt(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
inline Vec3 fromBt(const btVector3& v) { return {v.x(), v.y(), v.z()}; }
inline btQuaternion toBt(const Quat& q) { return {q.x(), q.y(), q.z(), q.w()}; }
inline Quat fromBt(const btQuaternion& q) { return Quat(q.w(), q.x(), q.y(), q.z()); }
inline Mat3 fromBt(const btMatrix3x3& m) {
  Mat3 out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out(r, c) = m[r][c];
  return out;
}

// Bullet's sequential-impulse solver with Tandem's sweep after each of its iterations.
// Bullet's own loop may stop early once its residual is small; this one always runs the
// requested count, because Tandem's rows need every sweep even when Bullet has nothing to do.
class CoupledSolver final : public btSequentialImpulseConstraintSolver {
 public:
  SolverHooks* hooks = nullptr;

  btAlignedObjectArray<btSolverBody>& solverBodies() { return m_tmpSolverBodyPool; }

 protected:
  btScalar solveGroupCacheFriendlySetup(btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds,
                                        int numManifolds, btTypedConstraint** constraints, int numConstraints,
                                        const btContactSolverInfo& info, btIDebugDraw* debugDrawer) override {
    const btScalar result = btSequentialImpulseConstraintSolver::solveGroupCacheFriendlySetup(
        bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info, debugDrawer);
    if (hooks) hooks->afterSetup();
    return result;
  }

  btScalar solveGroupCacheFriendlyIterations(btCollisionObject** bodies, int numBodies,
                                             btPersistentManifold** manifolds, int numManifolds,
                                             btTypedConstraint** constraints, int numConstraints,
                                             const btContactSolverInfo& info, btIDebugDraw* debugDrawer) override {
    solveGroupCacheFriendlySplitImpulseIterations(bodies, numBodies, manifolds, numManifolds, constraints,
                                                  numConstraints, info, debugDrawer);
    for (int iteration = 0; iteration < info.m_numIterations; ++iteration) {
      m_leastSquaresResidual = solveSingleIteration(iteration, bodies, numBodies, manifolds, numManifolds,
                                                    constraints, numConstraints, info, debugDrawer);
      if (hooks) hooks->afterIteration(iteration);
    }
    return 0;
  }
};

// Exposes the protected stages of Bullet's step so Tandem can call them in its own order.
class SteppedDynamicsWorld final : public btDiscreteDynamicsWorld {
 public:
  using btDiscreteDynamicsWorld::btDiscreteDynamicsWorld;

  void predict(btScalar h) {
    saveKinematicState(h);
    applyGravity();
    predictUnconstraintMotion(h);
    getDispatchInfo().m_timeStep = h;
    getDispatchInfo().m_stepCount = 0;
    getDispatchInfo().m_debugDraw = getDebugDrawer();
    createPredictiveContacts(h);
  }

  void detect() {
    performDiscreteCollisionDetection();
    calculateSimulationIslands();
  }

  // One solver call over every body, manifold and joint: Tandem's sweep then runs once per
  // iteration for the whole scene. Islands are still built so that sleeping works.
  // The manifolds with contact points go to the solver in the order of their bodies' indices,
  // not in the dispatcher's order (which follows the broadphase's history of pairs made and
  // dropped): the solve then depends on the contacts alone, so a restored snapshot steps on
  // bit for bit (bullet_snapshot.cpp).
  void solveAll(btScalar h) {
    getSolverInfo().m_timeStep = h;
    m_islandManager->buildIslands(getDispatcher(), getCollisionWorld());
    m_enabledJoints.clear();
    for (int i = 0; i < getNumConstraints(); ++i)
      if (getConstraint(i)->isEnabled()) m_enabledJoints.push_back(getConstraint(i));
    btCollisionObjectArray& objects = getCollisionObjectArray();
    m_solvedManifolds.clear();
    for (int m = 0; m < getDispatcher()->getNumManifolds(); ++m) {
      btPersistentManifold* manifold = getDispatcher()->getManifoldByIndexInternal(m);
      if (manifold->getNumContacts() > 0) m_solvedManifolds.push_back(manifold);
    }
    std::stable_sort(m_solvedManifolds.begin(), m_solvedManifolds.end(), manifoldOrder);
    const int manifoldCount = static_cast<int>(m_solvedManifolds.size());
    m_constraintSolver->prepareSolve(objects.size(), manifoldCount);
    m_constraintSolver->solveGroup(objects.size() ? &objects[0] : nullptr, objects.size(),
                                   manifoldCount ? m_solvedManifolds.data() : nullptr,
                                   manifoldCount, m_enabledJoints.empty() ? nullptr : m_enabledJoints.data(),
                                   static_cast<int>(m_enabledJoints.size()), getSolverInfo(), getDebugDrawer(),
                                   getDispatcher());
    m_constraintSolver->allSolved(getSolverInfo(), getDebugDrawer());
  }

  // The manifolds the last solve used, in its order.
  const std::vector<btPersistentManifold*>& solvedManifolds() const { return m_solvedManifolds; }

  static bool manifoldOrder(const btPersistentManifold* a, const btPersistentManifold* b) {
    const int a0 = a->getBody0()->getUserIndex(), a1 = a->getBody1()->getUserIndex();
    const int b0 = b->getBody0()->getUserIndex(), b1 = b->getBody1()->getUserIndex();
    return a0 != b0 ? a0 < b0 : a1 < b1;
  }

  void finish(btScalar h) {
    integrateTransforms(h);
    updateActions(h);
    updateActivationState(h);
    clearForces();
    synchronizeMotionStates();
  }

 private:
  std::vector<btTypedConstraint*> m_enabledJoints;
  std::vector<btPersistentManifold*> m_solvedManifolds;
};

// Bullet's collision configuration, set up before the dispatcher reads it:
// - Contact pools of 256 manifolds and 256 algorithms, not Bullet's 4,096 each, which it writes
//   through when a world is made (0.83 ms per empty world, 15 ms under AddressSanitizer; now
//   0.04 ms). Past a pool Bullet takes manifolds and algorithms from the heap, so this only moves
//   the cost of very large rigid scenes to the steps where their pairs first touch.
// - A convex shape on a plane gets its whole contact patch at once (Bullet's plane algorithm
//   perturbed about the normal), not one point per step: with one point a 10 cm box on the
//   ground rocked on its corners and sank 15 mm into it, at any iteration count.
struct CollisionConfiguration final : btDefaultCollisionConfiguration {
  CollisionConfiguration() : btDefaultCollisionConfiguration(poolSizes()) { setPlaneConvexMultipointIterations(); }
  static btDefaultCollisionConstructionInfo poolSizes() {
    btDefaultCollisionConstructionInfo info;
    info.m_defaultMaxPersistentManifoldPoolSize = 256;
    info.m_defaultMaxCollisionAlgorithmPoolSize = 256;
    return info;
  }
};

struct BulletWorld::Impl {
  CollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  CoupledSolver solver;
  SteppedDynamicsWorld world{&dispatcher, &broadphase, &solver, &configuration};

  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btDefaultMotionState>> motionStates;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  std::vector<std::unique_ptr<btTypedConstraint>> joints;
  std::vector<std::vector<btScalar>> meshVertices;  // kept alive for Bullet's triangle meshes
  std::vector<std::vector<int>> meshIndices;
  std::vector<std::unique_ptr<btTriangleIndexVertexArray>> meshArrays;
  struct PairImpulse {
    int bodyA, bodyB;  // bodyA < bodyB
    double impulse;    // N·s, summed over the step's solves
  };
  std::vector<PairImpulse> pairImpulses;  // reused from step to step
  std::vector<BulletWorld::ContactPoint> contactPoints;  // of the step's solves, reused
  std::vector<RigidSolverState::LockedRows> lockedRows;  // per body, reused (restrictJointedBodies)
  std::vector<int> weldGroup;

  // Per body: forces and torques applied since the last step, and those acting in this one.
  std::vector<Vec3> pendingForce, pendingTorque, stepForce, stepTorque;
  std::vector<char> removed;  // per body: taken out of the world (its slot kept until reused)
  // Per joint: whether it is a hinge, and its motor's torque bound (N·m); Bullet's bound is an
  // impulse per solve, set from it each solve.
  std::vector<char> isHinge;
  std::vector<double> motorMaxTorque;

  ~Impl() {
    for (int i = world.getNumConstraints() - 1; i >= 0; --i) world.removeConstraint(world.getConstraint(i));
    for (size_t b = 0; b < bodies.size(); ++b)
      if (!removed[b]) world.removeRigidBody(bodies[b].get());
  }

  const btSolverBody* solverBody(int body) const {
    const int id = bodies[body]->getCompanionId();
    if (id < 0) return nullptr;  // static: Bullet shares one fixed solver body and sets no id
    return &const_cast<CoupledSolver&>(solver).solverBodies()[id];
  }
};

// What BulletWorld::saveState copies (bullet_snapshot.cpp).
struct BulletWorld::State {
  struct Body {
    btTransform transform, interpolationTransform, motionStateTransform;
    btVector3 linearVelocity, angularVelocity, interpolationLinearVelocity, interpolationAngularVelocity;
    int activationState;
    btScalar deactivationTime, hitFraction;
    btScalar linearDamping, angularDamping;  // World::setRigidDamping changes them
    Vec3 pendingForce, pendingTorque, stepForce, stepTorque;
  };
  struct Manifold {
    int body0, body1;
    std::vector<btManifoldPoint> points;
  };
  struct Hinge {
    int joint;
    btScalar lower, upper;
    bool motor;
    btScalar targetVelocity;
    double maxTorque;
  };
  std::vector<Body> bodies;
  std::vector<Manifold> manifolds;  // those with points
  std::vector<Hinge> hinges;
  std::vector<Impl::PairImpulse> pairImpulses;
  std::vector<ContactPoint> contactPoints;
};

}  // namespace tandem::bullet
