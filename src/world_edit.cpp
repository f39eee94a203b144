// World: pushing and moving rigid bodies, collision filters, hinge limits and motors, and
// removing things with everything that refers to them.
#include "world_impl.h"

#include <algorithm>
#include <iterator>

namespace tandem {
namespace {

Status checkFinite(const Vec3& v, const char* who, const char* what) {
  if (!v.allFinite()) return Error{std::string(who) + ": " + what + " is not finite"};
  return {};
}

}  // namespace

// ---- Pushing and moving rigid bodies -----------------------------------------------------

// A live dynamic body, or the error naming what is wrong.
template <class WorldImpl>
static Status checkDynamic(const WorldImpl& w, RigidBodyId body, const char* who) {
  if (Status s = w.rigidSlots.check(body.index, body.generation); !s) return Error{std::string(who) + ": " + s.message()};
  if (!w.bullet.isDynamic(body.index))
    return Error{std::string(who) + ": rigid body '" + w.rigidNames[body.index] + "' is static or kinematic"};
  return {};
}

Status World::applyForce(RigidBodyId body, const Vec3& force) {
  if (Status s = checkDynamic(*m_impl, body, "apply force"); !s) return s;
  if (Status s = checkFinite(force, "apply force", "force"); !s) return s;
  m_impl->bullet.addForce(body.index, force, Vec3::Zero());
  return {};
}

Status World::applyForceAtPoint(RigidBodyId body, const Vec3& force, const Vec3& point) {
  if (Status s = checkDynamic(*m_impl, body, "apply force at point"); !s) return s;
  if (Status s = checkFinite(force, "apply force at point", "force"); !s) return s;
  if (Status s = checkFinite(point, "apply force at point", "point"); !s) return s;
  const Vec3 offset = point - m_impl->bullet.position(body.index);
  m_impl->bullet.addForce(body.index, force, offset.cross(force));
  return {};
}

Status World::applyTorque(RigidBodyId body, const Vec3& torque) {
  if (Status s = checkDynamic(*m_impl, body, "apply torque"); !s) return s;
  if (Status s = checkFinite(torque, "apply torque", "torque"); !s) return s;
  m_impl->bullet.addForce(body.index, Vec3::Zero(), torque);
  return {};
}

Status World::applyImpulse(RigidBodyId body, const Vec3& impulse) {
  if (Status s = checkDynamic(*m_impl, body, "apply impulse"); !s) return s;
  if (Status s = checkFinite(impulse, "apply impulse", "impulse"); !s) return s;
  m_impl->bullet.applyImpulse(body.index, impulse, Vec3::Zero());
  m_impl->forgetMovingSupport(body.index);
  return {};
}

Status World::applyImpulseAtPoint(RigidBodyId body, const Vec3& impulse, const Vec3& point) {
  if (Status s = checkDynamic(*m_impl, body, "apply impulse at point"); !s) return s;
  if (Status s = checkFinite(impulse, "apply impulse at point", "impulse"); !s) return s;
  if (Status s = checkFinite(point, "apply impulse at point", "point"); !s) return s;
  m_impl->bullet.applyImpulse(body.index, impulse, point - m_impl->bullet.position(body.index));
  m_impl->forgetMovingSupport(body.index);
  return {};
}

Status World::applyAngularImpulse(RigidBodyId body, const Vec3& angularImpulse) {
  if (Status s = checkDynamic(*m_impl, body, "apply angular impulse"); !s) return s;
  if (Status s = checkFinite(angularImpulse, "apply angular impulse", "angular impulse"); !s) return s;
  m_impl->bullet.applyAngularImpulse(body.index, angularImpulse);
  m_impl->forgetMovingSupport(body.index);
  return {};
}

Status World::setRigidLinearVelocity(RigidBodyId body, const Vec3& velocity) {
  if (Status s = checkDynamic(*m_impl, body, "set linear velocity"); !s) return s;
  if (Status s = checkFinite(velocity, "set linear velocity", "velocity"); !s) return s;
  m_impl->bullet.setLinearVelocity(body.index, velocity);
  m_impl->forgetMovingSupport(body.index);
  return {};
}

Status World::setRigidAngularVelocity(RigidBodyId body, const Vec3& velocity) {
  if (Status s = checkDynamic(*m_impl, body, "set angular velocity"); !s) return s;
  if (Status s = checkFinite(velocity, "set angular velocity", "angular velocity"); !s) return s;
  m_impl->bullet.setAngularVelocity(body.index, velocity);
  m_impl->forgetMovingSupport(body.index);
  return {};
}

Status World::setRigidPose(RigidBodyId body, const Vec3& position, const Quat& orientation) {
  if (Status s = m_impl->rigidSlots.check(body.index, body.generation); !s) return Error{"set pose: " + s.message()};
  if (Status s = checkFinite(position, "set pose", "position"); !s) return s;
  if (!orientation.coeffs().allFinite() || orientation.norm() < 1e-9)
    return Error{"set pose: orientation must be a finite non-zero quaternion"};
  m_impl->bullet.setPose(body.index, position, orientation);
  m_impl->forgetMovingSupport(body.index);
  return {};
}

// ---- Collision filters -------------------------------------------------------------------

Status World::setRigidCollisionFilter(RigidBodyId body, uint32_t group, uint32_t mask) {
  if (Status s = m_impl->rigidSlots.check(body.index, body.generation); !s)
    return Error{"collision filter: " + s.message()};
  m_impl->rigidGroup[body.index] = group;
  m_impl->rigidMask[body.index] = mask;
  m_impl->bullet.setCollisionFilter(body.index, group, mask);
  return {};
}

uint32_t World::rigidCollisionGroup(RigidBodyId body) const {
  return m_impl->lookup(m_impl->rigidSlots, body) ? m_impl->rigidGroup[body.index] : 0u;
}
uint32_t World::rigidCollisionMask(RigidBodyId body) const {
  return m_impl->lookup(m_impl->rigidSlots, body) ? m_impl->rigidMask[body.index] : 0u;
}

Status World::setDeformableCollisionFilter(DeformableId body, uint32_t group, uint32_t mask) {
  if (Status s = m_impl->deformableSlots.check(body.index, body.generation); !s)
    return Error{"collision filter: " + s.message()};
  m_impl->deformables[body.index].collision.group = group;
  m_impl->deformables[body.index].collision.mask = mask;
  return {};
}

// ---- Hinges --------------------------------------------------------------------------------

template <class WorldImpl>
static Status checkHinge(const WorldImpl& w, JointId hinge, const char* who) {
  if (Status s = w.jointSlots.check(hinge.index, hinge.generation); !s) return Error{std::string(who) + ": " + s.message()};
  if (!w.bullet.isHinge(hinge.index))
    return Error{std::string(who) + ": joint " + std::to_string(hinge.index) + " is a fixed joint, not a hinge"};
  return {};
}

Status World::setHingeLimits(JointId hinge, double lower, double upper) {
  if (Status s = checkHinge(*m_impl, hinge, "hinge limits"); !s) return s;
  if (std::isnan(lower) || std::isnan(upper) || (lower <= upper && (lower < -M_PI || upper > M_PI)))
    return Error{"hinge limits: limits must lie in [-pi, pi] rad (lower > upper for none), got [" +
                 formatNumber(lower) + ", " + formatNumber(upper) + "]"};
  m_impl->bullet.setHingeLimits(hinge.index, lower, upper);
  return {};
}

Status World::setHingeMotor(JointId hinge, bool enabled, double targetSpeed, double maxTorque) {
  if (Status s = checkHinge(*m_impl, hinge, "hinge motor"); !s) return s;
  if (!std::isfinite(targetSpeed)) return Error{"hinge motor: target speed must be finite"};
  if (!(std::isfinite(maxTorque) && maxTorque >= 0))
    return Error{"hinge motor: max torque must be >= 0 and finite, got " + formatNumber(maxTorque) + " N·m"};
  m_impl->bullet.setHingeMotor(hinge.index, enabled, targetSpeed, maxTorque);
  return {};
}

double World::hingeAngle(JointId hinge) const {
  if (!m_impl->lookup(m_impl->jointSlots, hinge)) return 0.0;
  if (!m_impl->bullet.isHinge(hinge.index)) {
    if (m_impl->lookupError.empty()) m_impl->lookupError = "joint " + std::to_string(hinge.index) + " is not a hinge";
    return 0.0;
  }
  return m_impl->bullet.hingeAngle(hinge.index);
}

double World::hingeSpeed(JointId hinge) const {
  if (!m_impl->lookup(m_impl->jointSlots, hinge)) return 0.0;
  if (!m_impl->bullet.isHinge(hinge.index)) {
    if (m_impl->lookupError.empty()) m_impl->lookupError = "joint " + std::to_string(hinge.index) + " is not a hinge";
    return 0.0;
  }
  return m_impl->bullet.hingeSpeed(hinge.index);
}

// ---- Rigid contacts ------------------------------------------------------------------------

std::vector<RigidContact> World::rigidContacts() const {
  const Impl& w = *m_impl;
  std::vector<RigidContact> contacts;
  const auto points = w.bullet.contactPoints();
  contacts.reserve(points.size());
  for (const bullet::BulletWorld::ContactPoint& p : points)
    contacts.push_back({w.rigidId(p.bodyA), w.rigidId(p.bodyB), p.pointOnA, p.pointOnB, p.normal, p.distance,
                        p.normalImpulse, p.frictionImpulse});
  return contacts;
}

// ---- Removal -------------------------------------------------------------------------------

// Erases the anchor or fixed point rows `erase` picks, with their slots.
template <class Row, class Pick>
static void eraseRows(std::vector<Row>& rows, IdSlots& slots, Pick erase) {
  for (int32_t position = static_cast<int32_t>(rows.size()) - 1; position >= 0; --position) {
    if (!erase(rows[position])) continue;
    rows.erase(rows.begin() + position);
    const int32_t slot = slots.slotAt(position);
    if (slot >= 0) slots.remove(slot, true);
  }
}

template <class WorldImpl, class Pick>
static void releaseGrabs(WorldImpl& w, Pick pick) {
  for (size_t g = 0; g < w.rows.grabs.size(); ++g) {
    if (!w.rows.grabs[g].active || !pick(w.rows.grabs[g])) continue;
    w.rows.grabs[g] = GrabRow{};
    w.grabSlots.remove(static_cast<int32_t>(g), false);
  }
}

Status World::removeAnchor(AnchorId anchor) {
  Impl& w = *m_impl;
  if (Status s = w.anchorSlots.check(anchor.index, anchor.generation); !s) return Error{"remove anchor: " + s.message()};
  w.rows.anchors.erase(w.rows.anchors.begin() + w.anchorSlots.position(anchor.index));
  w.anchorSlots.remove(anchor.index, true);
  w.directBlocksStale = true;
  return {};
}

Status World::removeFixedPoint(FixedPointId fixedPoint) {
  Impl& w = *m_impl;
  if (Status s = w.fixedPointSlots.check(fixedPoint.index, fixedPoint.generation); !s)
    return Error{"remove fixed point: " + s.message()};
  w.rows.fixedPoints.erase(w.rows.fixedPoints.begin() + w.fixedPointSlots.position(fixedPoint.index));
  w.fixedPointSlots.remove(fixedPoint.index, true);
  w.directBlocksStale = true;
  return {};
}

Status World::removeJoint(JointId joint) {
  Impl& w = *m_impl;
  if (Status s = w.jointSlots.check(joint.index, joint.generation); !s) return Error{"remove joint: " + s.message()};
  w.bullet.removeJoint(joint.index);
  w.jointSlots.remove(joint.index, false);
  ++w.rigidStructureVersion;
  return {};
}

// Out of Bullet (with its joints and Bullet's contacts), and out of Tandem: its anchors, grabs,
// contacts and the supports it gave. Its slot stays, inert and filtered out of every collision,
// until a new body takes it.
Status World::removeRigidBody(RigidBodyId body) {
  Impl& w = *m_impl;
  if (Status s = w.rigidSlots.check(body.index, body.generation); !s) return Error{"remove rigid body: " + s.message()};
  const int32_t b = body.index;
  for (int joint : w.bullet.jointsOf(b)) {
    w.bullet.removeJoint(joint);
    w.jointSlots.remove(joint, false);
  }
  w.bullet.removeRigidBody(b);
  eraseRows(w.rows.anchors, w.anchorSlots, [b](const AnchorRow& row) { return row.body == b; });
  releaseGrabs(w, [b](const GrabRow& row) { return row.onRigid() && row.body == b; });
  std::erase_if(w.rows.contacts, [b](const ContactRow& row) { return row.body == b; });
  w.setPreviousContacts();  // the warm-start impulses of the contacts left
  for (DeformableRecord& record : w.deformables) {
    Supports& supports = record.supports;
    for (size_t i = 0; i < supports.body.size(); ++i)
      if (supports.body[i] == b) {
        supports.normal[i].setZero();
        supports.body[i] = -1;
        supports.moves[i] = 0;
      }
    for (size_t i = 0; i < supports.holdBody.size(); ++i)
      if (supports.holdBody[i] == b) {
        supports.holdBody[i] = -1;
        supports.holdImpulse[i].setZero();
      }
  }
  w.rigid[b] = RigidSolverState{};
  w.forgetMovingSupport(b);
  w.rigidGroup[b] = w.rigidMask[b] = 0;  // collides with nothing of Tandem's
  w.rigidSlots.remove(b, false);
  w.directBlocksStale = true;
  ++w.rigidStructureVersion;
  return {};
}

// Its rows, springs, fixed points, anchors, grabs and contacts go; its nodes stay in the node
// arrays (every row elsewhere indexes them) but inert: no mass, no motion, no collision, no model.
Status World::removeDeformable(DeformableId body) {
  Impl& w = *m_impl;
  if (Status s = w.deformableSlots.check(body.index, body.generation); !s)
    return Error{"remove deformable: " + s.message()};
  DeformableRecord& record = w.deformables[body.index];
  const int32_t first = record.firstNode, end = record.firstNode + record.nodeCount;
  const auto inBody = [first, end](int32_t node) { return node >= first && node < end; };
  const auto anyIn = [&](const auto& nodes) {
    return std::any_of(std::begin(nodes), std::end(nodes), [&](int32_t n) { return inBody(n); });
  };
  std::erase_if(w.springs, [&](const EdgeSpring& s) { return inBody(s.nodeA) || inBody(s.nodeB); });
  std::erase_if(w.rows.inextensibility, [&](const InextensibilityRow& row) { return anyIn(row.node); });
  std::erase_if(w.rows.bending, [&](const BendingRow& row) { return anyIn(row.node); });
  eraseRows(w.rows.fixedPoints, w.fixedPointSlots, [&](const FixedPointRow& row) { return inBody(row.node); });
  eraseRows(w.rows.anchors, w.anchorSlots, [&](const AnchorRow& row) { return anyIn(row.node); });
  releaseGrabs(w, [&](const GrabRow& row) { return !row.onRigid() && anyIn(row.node); });
  std::erase_if(w.rows.contacts, [&](const ContactRow& row) { return anyIn(row.node); });
  w.setPreviousContacts();  // the warm-start impulses of the contacts left
  for (int32_t n = first; n < end; ++n) {
    w.nodes.velocity[n].setZero();
    w.nodes.force[n].setZero();
    w.nodes.inverseMass[n] = 0.0;
  }
  record.removed = true;
  record.collision.enabled = false;
  record.collision.group = record.collision.mask = 0;
  record.implicitStep = false;
  record.implicit = ImplicitBody{};
  record.paradigm = ParadigmSettings{};  // mass-spring: no model runs on its (massless) nodes
  record.damping = 0.0;
  record.restMesh = DeformableMesh{};
  record.surfaceNodes.clear();
  record.surfaceTriangles.clear();
  record.surfaceEdges.clear();
  record.paradigmEdges.clear();
  record.paradigmRest = PositionBasedRest{};
  w.deformableSlots.remove(body.index, false);
  w.directBlocksStale = true;
  return {};
}

}  // namespace tandem
