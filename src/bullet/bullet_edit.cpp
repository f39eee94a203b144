// BulletWorld: pushing, moving, filtering and removing bodies and joints; hinge limits and motors.
#include "bullet/bullet_world_impl.h"

namespace tandem::bullet {

bool BulletWorld::isRemoved(int body) const { return m_impl->removed[body] != 0; }

std::vector<int> BulletWorld::jointsOf(int body) const {
  std::vector<int> found;
  const btRigidBody* b = m_impl->bodies[body].get();
  for (size_t j = 0; j < m_impl->joints.size(); ++j) {
    const btTypedConstraint* joint = m_impl->joints[j].get();
    if (joint && (&joint->getRigidBodyA() == b || &joint->getRigidBodyB() == b)) found.push_back(static_cast<int>(j));
  }
  return found;
}

// Out of the dynamics world: Bullet drops its broadphase pairs and their manifolds with it. The
// object stays in its slot with no mass and no motion, so that every per-slot array stays valid.
void BulletWorld::removeRigidBody(int body) {
  Impl& w = *m_impl;
  btRigidBody& b = *w.bodies[body];
  w.world.removeRigidBody(&b);
  b.setMassProps(0.0, btVector3(0, 0, 0));
  b.setLinearVelocity(btVector3(0, 0, 0));
  b.setAngularVelocity(btVector3(0, 0, 0));
  b.clearForces();
  w.pendingForce[body].setZero();
  w.pendingTorque[body].setZero();
  w.stepForce[body].setZero();
  w.stepTorque[body].setZero();
  w.removed[body] = 1;
  std::erase_if(w.pairImpulses, [&](const Impl::PairImpulse& p) { return p.bodyA == body || p.bodyB == body; });
  std::erase_if(w.contactPoints, [&](const ContactPoint& p) { return p.bodyA == body || p.bodyB == body; });
}

void BulletWorld::removeJoint(int joint) {
  Impl& w = *m_impl;
  w.world.removeConstraint(w.joints[joint].get());
  w.joints[joint].reset();
  w.isHinge[joint] = 0;
  w.motorMaxTorque[joint] = 0.0;
}

void BulletWorld::addForce(int body, const Vec3& force, const Vec3& torque) {
  m_impl->pendingForce[body] += force;
  m_impl->pendingTorque[body] += torque;
  wake(body);
}

void BulletWorld::applyImpulse(int body, const Vec3& impulse, const Vec3& offsetFromCentre) {
  wake(body);
  m_impl->bodies[body]->applyImpulse(toBt(impulse), toBt(offsetFromCentre));
}

void BulletWorld::applyAngularImpulse(int body, const Vec3& angularImpulse) {
  wake(body);
  m_impl->bodies[body]->applyTorqueImpulse(toBt(angularImpulse));
}

void BulletWorld::setLinearVelocity(int body, const Vec3& velocity) {
  wake(body);
  m_impl->bodies[body]->setLinearVelocity(toBt(velocity));
}

void BulletWorld::setAngularVelocity(int body, const Vec3& velocity) {
  wake(body);
  m_impl->bodies[body]->setAngularVelocity(toBt(velocity));
}

// The pose everywhere Bullet keeps one: the body, its interpolation pose, its motion state (a
// kinematic body's target) and its broadphase box.
void BulletWorld::setPose(int body, const Vec3& position, const Quat& orientation) {
  Impl& w = *m_impl;
  btRigidBody& b = *w.bodies[body];
  const btTransform pose(toBt(orientation.normalized()), toBt(position));
  b.setCenterOfMassTransform(pose);
  b.setInterpolationWorldTransform(pose);
  w.motionStates[body]->setWorldTransform(pose);
  if (!w.removed[body]) w.world.updateSingleAabb(&b);
  if (b.getInvMass() > 0) wake(body);
}

// Bullet reads a proxy's filter when pairs are made: the body leaves the world and comes back
// with the new one, so that pairs the filter now forbids go too.
void BulletWorld::setCollisionFilter(int body, uint32_t group, uint32_t mask) {
  Impl& w = *m_impl;
  if (w.removed[body]) return;
  btRigidBody& b = *w.bodies[body];
  const std::vector<int> joints = jointsOf(body);
  for (int j : joints) w.world.removeConstraint(w.joints[j].get());
  w.world.removeRigidBody(&b);
  w.world.addRigidBody(&b, static_cast<int>(group), static_cast<int>(mask));
  for (int j : joints) w.world.addConstraint(w.joints[j].get(), true);
}

bool BulletWorld::isHinge(int joint) const {
  return joint >= 0 && joint < static_cast<int>(m_impl->isHinge.size()) && m_impl->isHinge[joint];
}

// Bullet's hinge angle and motor speed are body A's rotation relative to B about A's axis, as
// Tandem's are.
void BulletWorld::setHingeLimits(int joint, double lower, double upper) {
  auto& hinge = static_cast<btHingeConstraint&>(*m_impl->joints[joint]);
  if (lower > upper)
    hinge.setLimit(1.0, -1.0);  // Bullet's "no limit"
  else
    hinge.setLimit(lower, upper);
}

void BulletWorld::setHingeMotor(int joint, bool enabled, double targetSpeed, double maxTorque) {
  auto& hinge = static_cast<btHingeConstraint&>(*m_impl->joints[joint]);
  m_impl->motorMaxTorque[joint] = enabled ? maxTorque : 0.0;
  hinge.enableAngularMotor(enabled, targetSpeed, 0.0);  // the bound is set per solve
  if (enabled) wake(m_impl->joints[joint]->getRigidBodyA().getUserIndex());
}

double BulletWorld::hingeAngle(int joint) const {
  return static_cast<btHingeConstraint&>(*m_impl->joints[joint]).getHingeAngle();
}

double BulletWorld::hingeSpeed(int joint) const {
  const auto& hinge = static_cast<const btHingeConstraint&>(*m_impl->joints[joint]);
  const btRigidBody& a = hinge.getRigidBodyA();
  const btRigidBody& b = hinge.getRigidBodyB();
  const btVector3 axis = a.getCenterOfMassTransform().getBasis() * hinge.getAFrame().getBasis().getColumn(2);
  return (a.getAngularVelocity() - b.getAngularVelocity()).dot(axis);
}

}  // namespace tandem::bullet
