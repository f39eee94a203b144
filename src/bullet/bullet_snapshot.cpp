// BulletWorld: saving and restoring everything of Bullet's that the next step reads.
//
// Bodies: poses (with the interpolation pose and the motion state, a kinematic body's target),
// velocities, sleep state and the forces applied for the next step. Contacts: the points of
// every manifold with points, each with its warm-start impulses, lifetime and friction
// directions (btManifoldPoint copied whole). Joints: hinge limits and motors.
//
// What is not copied is rebuilt: the broadphase's pairs and the manifolds that hold the points
// come from a collision pass at the restored poses, and the saved points then replace whatever
// that pass put in them. The solver takes the manifolds with points in the order of their
// bodies (bullet_world_impl.h, solveAll), so the broadphase's own history (which pairs it made
// and dropped, in which order) does not reach the solve. It still decides Bullet's simulation
// islands, which only decide when bodies fall asleep: a restored run can let a body fall
// asleep at a different step than the original when two bodies' padded boxes overlap in one
// broadphase and not in the other (docs/architecture.md).
#include "bullet/bullet_world_impl.h"

namespace tandem::bullet {

std::unique_ptr<BulletWorld::State> BulletWorld::saveState() const {
  const Impl& w = *m_impl;
  auto state = std::make_unique<State>();
  for (size_t b = 0; b < w.bodies.size(); ++b) {
    const btRigidBody& body = *w.bodies[b];
    State::Body saved;
    saved.transform = body.getWorldTransform();
    saved.interpolationTransform = body.getInterpolationWorldTransform();
    w.motionStates[b]->getWorldTransform(saved.motionStateTransform);
    saved.linearVelocity = body.getLinearVelocity();
    saved.angularVelocity = body.getAngularVelocity();
    saved.interpolationLinearVelocity = body.getInterpolationLinearVelocity();
    saved.interpolationAngularVelocity = body.getInterpolationAngularVelocity();
    saved.activationState = body.getActivationState();
    saved.deactivationTime = body.getDeactivationTime();
    saved.hitFraction = body.getHitFraction();
    saved.linearDamping = body.getLinearDamping();
    saved.angularDamping = body.getAngularDamping();
    saved.pendingForce = w.pendingForce[b];
    saved.pendingTorque = w.pendingTorque[b];
    saved.stepForce = w.stepForce[b];
    saved.stepTorque = w.stepTorque[b];
    state->bodies.push_back(saved);
  }
  const btDispatcher* dispatcher = w.world.getDispatcher();
  for (int m = 0; m < dispatcher->getNumManifolds(); ++m) {
    const btPersistentManifold* manifold = const_cast<btDispatcher*>(dispatcher)->getManifoldByIndexInternal(m);
    if (manifold->getNumContacts() == 0) continue;
    State::Manifold saved{manifold->getBody0()->getUserIndex(), manifold->getBody1()->getUserIndex(), {}};
    for (int p = 0; p < manifold->getNumContacts(); ++p) saved.points.push_back(manifold->getContactPoint(p));
    state->manifolds.push_back(std::move(saved));
  }
  for (size_t j = 0; j < w.joints.size(); ++j) {
    if (!w.isHinge[j] || !w.joints[j]) continue;
    const auto& hinge = static_cast<const btHingeConstraint&>(*w.joints[j]);
    state->hinges.push_back({static_cast<int>(j), hinge.getLowerLimit(), hinge.getUpperLimit(),
                             const_cast<btHingeConstraint&>(hinge).getEnableAngularMotor(),
                             const_cast<btHingeConstraint&>(hinge).getMotorTargetVelocity(), w.motorMaxTorque[j]});
  }
  state->pairImpulses = w.pairImpulses;
  state->contactPoints = w.contactPoints;
  return state;
}

int BulletWorld::restoreState(const State& state) {
  Impl& w = *m_impl;
  for (size_t b = 0; b < w.bodies.size(); ++b) {
    btRigidBody& body = *w.bodies[b];
    const State::Body& saved = state.bodies[b];
    body.setCenterOfMassTransform(saved.transform);  // also the world inertia
    body.setInterpolationWorldTransform(saved.interpolationTransform);
    w.motionStates[b]->setWorldTransform(saved.motionStateTransform);
    body.setLinearVelocity(saved.linearVelocity);
    body.setAngularVelocity(saved.angularVelocity);
    body.setInterpolationLinearVelocity(saved.interpolationLinearVelocity);
    body.setInterpolationAngularVelocity(saved.interpolationAngularVelocity);
    body.forceActivationState(saved.activationState);
    body.setDeactivationTime(saved.deactivationTime);
    body.setHitFraction(saved.hitFraction);
    body.setDamping(saved.linearDamping, saved.angularDamping);
    body.clearForces();
    w.pendingForce[b] = saved.pendingForce;
    w.pendingTorque[b] = saved.pendingTorque;
    w.stepForce[b] = saved.stepForce;
    w.stepTorque[b] = saved.stepTorque;
  }
  for (const State::Hinge& saved : state.hinges) {
    auto& hinge = static_cast<btHingeConstraint&>(*w.joints[saved.joint]);
    hinge.setLimit(saved.lower, saved.upper);
    hinge.enableAngularMotor(saved.motor, saved.targetVelocity, 0.0);
    w.motorMaxTorque[saved.joint] = saved.maxTorque;
  }
  // Pairs and manifolds at the restored poses, then the saved points in them.
  w.world.performDiscreteCollisionDetection();
  btDispatcher* dispatcher = w.world.getDispatcher();
  for (int m = 0; m < dispatcher->getNumManifolds(); ++m) dispatcher->getManifoldByIndexInternal(m)->clearManifold();
  int unplaced = 0;
  for (const State::Manifold& saved : state.manifolds) {
    btPersistentManifold* target = nullptr;
    for (int m = 0; m < dispatcher->getNumManifolds() && !target; ++m) {
      btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
      if (manifold->getBody0()->getUserIndex() == saved.body0 && manifold->getBody1()->getUserIndex() == saved.body1 &&
          manifold->getNumContacts() == 0)
        target = manifold;
    }
    if (!target) {  // the broadphase made no pair for them at these poses
      ++unplaced;
      continue;
    }
    for (const btManifoldPoint& point : saved.points) target->addManifoldPoint(point);
  }
  w.pairImpulses = state.pairImpulses;
  w.contactPoints = state.contactPoints;
  return unplaced;
}

}  // namespace tandem::bullet
