#include "bullet/bullet_world_impl.h"

#include <LinearMath/btConvexHullComputer.h>

#include <algorithm>
#include <cassert>
#include <vector>

namespace tandem::bullet {

std::vector<Eigen::Vector4d> convexHullPlanes(const std::vector<Vec3>& points) {
  btConvexHullComputer computer;
  std::vector<double> coordinates;
  for (const Vec3& p : points) coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});
  computer.compute(coordinates.data(), 3 * static_cast<int>(sizeof(double)), static_cast<int>(points.size()), 0, 0);
  std::vector<Eigen::Vector4d> planes;
  for (int f = 0; f < computer.faces.size(); ++f) {
    // Newell's normal over the face's counter-clockwise vertices.
    const btConvexHullComputer::Edge* first = &computer.edges[computer.faces[f]];
    Vec3 normal = Vec3::Zero(), centre = Vec3::Zero();
    int count = 0;
    const btConvexHullComputer::Edge* edge = first;
    do {
      const Vec3 a = fromBt(computer.vertices[edge->getSourceVertex()]);
      const Vec3 b = fromBt(computer.vertices[edge->getTargetVertex()]);
      normal += a.cross(b);
      centre += a;
      ++count;
      edge = edge->getNextEdgeOfFace();
    } while (edge != first);
    if (normal.norm() < 1e-12) continue;
    normal.normalize();
    planes.emplace_back(normal.x(), normal.y(), normal.z(), normal.dot(centre / count));
  }
  return planes;
}

std::vector<Vec3> convexHullVertices(const std::vector<Vec3>& points) {
  btConvexHullComputer computer;
  std::vector<double> coordinates;
  for (const Vec3& p : points) coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});
  computer.compute(coordinates.data(), 3 * static_cast<int>(sizeof(double)), static_cast<int>(points.size()), 0, 0);
  std::vector<Vec3> vertices;
  for (int v = 0; v < computer.vertices.size(); ++v) vertices.push_back(fromBt(computer.vertices[v]));
  return vertices;
}

namespace {
std::unique_ptr<btConvexHullShape> makeHull(const std::vector<Vec3>& points) {
  auto hull = std::make_unique<btConvexHullShape>();
  for (const Vec3& p : points) hull->addPoint(toBt(p), false);
  hull->setMargin(kHullMargin);  // Bullet's 4 cm default lies outside the hull: it would look 4 cm larger
  hull->recalcLocalAabb();
  return hull;
}

// A compound that owns its children (Bullet's only points at them).
struct OwningCompoundShape final : btCompoundShape {
  std::vector<std::unique_ptr<btCollisionShape>> children;
};
}  // namespace

BulletWorld::BulletWorld(const Vec3& gravity) : m_impl(std::make_unique<Impl>()) {
  m_impl->world.setGravity(toBt(gravity));
  m_impl->world.getSimulationIslandManager()->setSplitIslands(false);
  // Contacts start each step from the whole of last step's impulses, not Bullet's default 85 %
  // of them. With 85 % every resting contact had to find the other 15 % of its normal and
  // friction impulse again within the step's few iterations, and never quite did: a box alone on
  // the ground slid at 0.3 mm/s with a steady spin, for ever, and three boxes stacked on the
  // ground came apart, the top one 0.57 m away after 8 s at K = 4 (17 cm at K = 2). Whole, the
  // solve carries the resting solution over from step to step, as Box2D's and Jolt's do, and both
  // stay put to the micrometre (RigidApi.BoxesRestingOnTheGroundAndOnEachOtherStayPut).
  m_impl->world.getSolverInfo().m_warmstartingFactor = 1.0;
}

BulletWorld::~BulletWorld() = default;

void BulletWorld::setGravity(const Vec3& gravity) { m_impl->world.setGravity(toBt(gravity)); }

int BulletWorld::addRigidBody(const RigidBodyDesc& desc, int slot) {
  std::unique_ptr<btCollisionShape> shape;
  const RigidShape& s = desc.shape;
  switch (s.type) {
    case ShapeType::Box: shape = std::make_unique<btBoxShape>(toBt(s.halfExtents)); break;
    case ShapeType::Sphere: shape = std::make_unique<btSphereShape>(s.radius); break;
    case ShapeType::Cylinder:
      shape = std::make_unique<btCylinderShape>(btVector3(s.radius, s.halfHeight, s.radius));
      break;
    case ShapeType::Capsule: shape = std::make_unique<btCapsuleShape>(s.radius, 2.0 * s.halfHeight); break;
    case ShapeType::Plane:
      shape = std::make_unique<btStaticPlaneShape>(toBt(s.planeNormal.normalized()), s.planeOffset);
      break;
    case ShapeType::ConvexHull: shape = makeHull(s.points); break;
    case ShapeType::Compound: {
      auto compound = std::make_unique<OwningCompoundShape>();
      for (const std::vector<Vec3>& points : s.hulls) {
        compound->children.push_back(makeHull(points));
        compound->addChildShape(btTransform::getIdentity(), compound->children.back().get());
      }
      shape = std::move(compound);
      break;
    }
    case ShapeType::TriangleMesh: {
      // Bullet keeps pointers into the arrays: they live as long as the world.
      auto& vertices = m_impl->meshVertices.emplace_back();
      auto& indices = m_impl->meshIndices.emplace_back();
      for (const Vec3& p : s.points) vertices.insert(vertices.end(), {p.x(), p.y(), p.z()});
      for (const auto& t : s.triangles) indices.insert(indices.end(), {t[0], t[1], t[2]});
      auto array = std::make_unique<btTriangleIndexVertexArray>(
          static_cast<int>(s.triangles.size()), indices.data(), 3 * static_cast<int>(sizeof(int)),
          static_cast<int>(s.points.size()), vertices.data(), 3 * static_cast<int>(sizeof(btScalar)));
      shape = std::make_unique<btBvhTriangleMeshShape>(array.get(), true);
      shape->setMargin(kHullMargin);
      m_impl->meshArrays.push_back(std::move(array));
      break;
    }
  }
  const bool dynamic = desc.motion == MotionType::Dynamic;
  const double mass = dynamic ? desc.mass : 0.0;
  btVector3 inertia(0, 0, 0);
  if (dynamic) {
    if (desc.inertia)
      inertia = toBt(*desc.inertia);
    else
      shape->calculateLocalInertia(mass, inertia);
  }

  btTransform pose(toBt(desc.orientation.normalized()), toBt(desc.position));
  auto motionState = std::make_unique<btDefaultMotionState>(pose);
  btRigidBody::btRigidBodyConstructionInfo info(mass, motionState.get(), shape.get(), inertia);
  info.m_friction = desc.friction;
  info.m_restitution = desc.restitution;
  info.m_linearDamping = desc.linearDamping;  // applied in each prediction: v ← v (1 − d)^h
  info.m_angularDamping = desc.angularDamping;
  auto body = std::make_unique<btRigidBody>(info);
  if (desc.motion == MotionType::Kinematic) {
    body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
    body->setActivationState(DISABLE_DEACTIVATION);
  }
  if (!desc.canSleep) body->setActivationState(DISABLE_DEACTIVATION);
  if (dynamic) {
    body->setLinearVelocity(toBt(desc.linearVelocity));
    body->setAngularVelocity(toBt(desc.angularVelocity));
  }
  body->setUserIndex(slot);  // for ray casts and contact reports
  m_impl->world.addRigidBody(body.get(), static_cast<int>(desc.collisionGroup), static_cast<int>(desc.collisionMask));

  Impl& w = *m_impl;
  if (slot == static_cast<int>(w.bodies.size())) {
    w.shapes.emplace_back();
    w.motionStates.emplace_back();
    w.bodies.emplace_back();
    for (auto* v : {&w.pendingForce, &w.pendingTorque, &w.stepForce, &w.stepTorque}) v->push_back(Vec3::Zero());
    w.removed.push_back(0);
  }
  w.shapes[slot] = std::move(shape);
  w.motionStates[slot] = std::move(motionState);
  w.bodies[slot] = std::move(body);
  for (auto* v : {&w.pendingForce, &w.pendingTorque, &w.stepForce, &w.stepTorque}) (*v)[slot].setZero();
  w.removed[slot] = 0;
  return slot;
}

namespace {
// Puts a joint into its slot (a removed one, or a new one at the end).
void placeJoint(std::vector<std::unique_ptr<btTypedConstraint>>& joints, int slot,
                std::unique_ptr<btTypedConstraint> joint) {
  if (slot == static_cast<int>(joints.size())) joints.emplace_back();
  joints[slot] = std::move(joint);
}
}  // namespace

int BulletWorld::addHinge(const HingeDesc& desc, int slot) {
  btRigidBody& a = *m_impl->bodies[desc.bodyA.index];
  const btVector3 pivot = toBt(desc.pivot);
  const btVector3 axis = toBt(desc.axis.normalized());
  const btTransform aInverse = a.getCenterOfMassTransform().inverse();
  std::unique_ptr<btHingeConstraint> hinge;
  if (desc.bodyB) {
    btRigidBody& b = *m_impl->bodies[desc.bodyB->index];
    const btTransform bInverse = b.getCenterOfMassTransform().inverse();
    hinge = std::make_unique<btHingeConstraint>(a, b, aInverse * pivot, bInverse * pivot,
                                                aInverse.getBasis() * axis, bInverse.getBasis() * axis);
  } else {
    hinge = std::make_unique<btHingeConstraint>(a, aInverse * pivot, aInverse.getBasis() * axis);
  }
  m_impl->world.addConstraint(hinge.get(), true);
  placeJoint(m_impl->joints, slot, std::move(hinge));
  if (slot == static_cast<int>(m_impl->isHinge.size())) {
    m_impl->isHinge.push_back(0);
    m_impl->motorMaxTorque.push_back(0.0);
  }
  m_impl->isHinge[slot] = 1;
  setHingeLimits(slot, desc.lowerLimit, desc.upperLimit);
  setHingeMotor(slot, desc.motor, desc.motorTargetSpeed, desc.motorMaxTorque);
  return slot;
}

int BulletWorld::addFixedJoint(const FixedJointDesc& desc, int slot) {
  btRigidBody& a = *m_impl->bodies[desc.bodyA.index];
  btRigidBody& b = desc.bodyB ? *m_impl->bodies[desc.bodyB->index] : btTypedConstraint::getFixedBody();
  // Frames: A's own, and where A is now in B's frame, so the joint holds the present pose.
  const btTransform frameInB = b.getCenterOfMassTransform().inverse() * a.getCenterOfMassTransform();
  auto joint = std::make_unique<btFixedConstraint>(a, b, btTransform::getIdentity(), frameInB);
  m_impl->world.addConstraint(joint.get(), true);
  placeJoint(m_impl->joints, slot, std::move(joint));
  if (slot == static_cast<int>(m_impl->isHinge.size())) {
    m_impl->isHinge.push_back(0);
    m_impl->motorMaxTorque.push_back(0.0);
  }
  m_impl->isHinge[slot] = 0;
  return slot;
}

int BulletWorld::rigidBodyCount() const { return static_cast<int>(m_impl->bodies.size()); }
int BulletWorld::jointSlotCount() const { return static_cast<int>(m_impl->joints.size()); }

// Gravity, then the forces the user applied for this step (Bullet's own accumulators are
// cleared after each substep's integration, so they are applied again in each substep).
void BulletWorld::predictRigidMotion(double timeStep) {
  Impl& w = *m_impl;
  for (size_t b = 0; b < w.bodies.size(); ++b) {
    if (w.stepForce[b].isZero() && w.stepTorque[b].isZero()) continue;
    w.bodies[b]->applyCentralForce(toBt(w.stepForce[b]));
    w.bodies[b]->applyTorque(toBt(w.stepTorque[b]));
  }
  w.world.predict(timeStep);
}

void BulletWorld::detectCollisions(double) { m_impl->world.detect(); }

void BulletWorld::solve(double timeStep, int iterations, SolverHooks& hooks) {
  m_impl->world.getSolverInfo().m_numIterations = iterations;
  for (size_t j = 0; j < m_impl->joints.size(); ++j)  // a motor's bound is an impulse per solve
    if (m_impl->isHinge[j] && m_impl->joints[j]) {
      auto& hinge = static_cast<btHingeConstraint&>(*m_impl->joints[j]);
      hinge.setMaxMotorImpulse(m_impl->motorMaxTorque[j] * timeStep);
    }
  m_impl->solver.hooks = &hooks;
  m_impl->world.solveAll(timeStep);
  m_impl->solver.hooks = nullptr;
  addContactImpulses();
}

void BulletWorld::integrate(double timeStep) { m_impl->world.finish(timeStep); }

void BulletWorld::loadRigidProperties(std::span<RigidSolverState> states) const {
  assert(states.size() == m_impl->bodies.size());
  for (size_t i = 0; i < states.size(); ++i) {
    RigidSolverState& state = states[i];
    const btRigidBody& body = *m_impl->bodies[i];
    const bool movable = body.getInvMass() > 0 && body.isActive();
    state.inverseMass = movable ? body.getInvMass() : 0.0;
    state.inverseInertia = movable ? fromBt(body.getInvInertiaTensorWorld()) : Mat3::Zero();
    state.centerOfMass = fromBt(body.getCenterOfMassPosition());
    state.orientation = fromBt(body.getOrientation());
    state.linearVelocity = fromBt(body.getLinearVelocity());
    state.angularVelocity = fromBt(body.getAngularVelocity());
  }
  restrictJointedBodies(states);
}

// What joints to immovable bodies (static, kinematic, asleep, the world) allow is a kinematic
// fact: a movable body hinged to the world can only turn about the hinge, whatever else is
// attached to it. Bodies welded together by fixed joints move as one, so each member of a welded
// group is held by every world joint of the group: a wheel with flanges fixed to it is still a
// wheel on an axle. Each member keeps its own mass (RigidSolverState::restrictMotion): an impulse
// on it then carries exactly its momentum, and Bullet's welds share it out. Joints between two
// movable bodies other than welds, and joint types not known here, restrict nothing.
void BulletWorld::restrictJointedBodies(std::span<RigidSolverState> states) const {
  const auto& bodies = m_impl->bodies;
  auto indexOf = [&](const btRigidBody& body) -> int {
    const int id = body.getUserIndex();  // set to the body's index when it was added
    return id >= 0 && static_cast<size_t>(id) < bodies.size() && bodies[static_cast<size_t>(id)].get() == &body ? id : -1;
  };
  auto movable = [&](int body) { return body >= 0 && states[static_cast<size_t>(body)].inverseMass > 0.0; };
  // Welded groups: union-find over fixed joints between movable bodies.
  std::vector<int>& group = m_impl->weldGroup;
  group.resize(states.size());
  for (size_t i = 0; i < group.size(); ++i) group[i] = static_cast<int>(i);
  auto root = [&](int i) {
    while (group[static_cast<size_t>(i)] != i) i = group[static_cast<size_t>(i)] = group[static_cast<size_t>(group[static_cast<size_t>(i)])];
    return i;
  };
  bool anyWorldJoint = false, anyWeld = false;
  for (const auto& joint : m_impl->joints) {
    if (!joint || !joint->isEnabled()) continue;
    const int a = indexOf(joint->getRigidBodyA()), b = indexOf(joint->getRigidBodyB());
    if (movable(a) && movable(b)) {
      if (dynamic_cast<const btFixedConstraint*>(joint.get())) {
        group[static_cast<size_t>(root(a))] = root(b);
        anyWeld = true;
      }
    } else if (movable(a) || movable(b)) {
      anyWorldJoint = true;
    }
  }
  if (!anyWorldJoint) {
    for (RigidSolverState& state : states) state.restrictMotion({});
    return;
  }
  // Each world joint's rows, per member of its group, about the member's own centre.
  std::vector<RigidSolverState::LockedRows>& locked = m_impl->lockedRows;
  locked.assign(states.size(), RigidSolverState::LockedRows(0, 6));
  for (const auto& joint : m_impl->joints) {
    if (!joint || !joint->isEnabled()) continue;
    const int a = indexOf(joint->getRigidBodyA()), b = indexOf(joint->getRigidBodyB());
    if (movable(a) == movable(b)) continue;
    const bool onA = movable(a);
    const int held = onA ? a : b;
    const auto* hinge = dynamic_cast<const btHingeConstraint*>(joint.get());
    const bool fixed = dynamic_cast<const btFixedConstraint*>(joint.get()) != nullptr;
    if (!hinge && !fixed) continue;
    Vec3 pivot = Vec3::Zero(), axis = Vec3::UnitZ();
    if (hinge) {
      const btTransform frame =
          bodies[static_cast<size_t>(held)]->getCenterOfMassTransform() * (onA ? hinge->getAFrame() : hinge->getBFrame());
      pivot = fromBt(frame.getOrigin());
      axis = fromBt(frame.getBasis().getColumn(2)).normalized();
    }
    const int heldGroup = root(held);
    const size_t firstMember = anyWeld ? 0 : static_cast<size_t>(held);
    const size_t endMember = anyWeld ? states.size() : static_cast<size_t>(held) + 1;
    for (size_t member = firstMember; member < endMember; ++member) {
      if (!movable(static_cast<int>(member)) || root(static_cast<int>(member)) != heldGroup) continue;
      RigidSolverState::LockedRows& rows = locked[member];
      const Eigen::Index first = rows.rows();
      if (first + 6 > rows.MaxRowsAtCompileTime) continue;  // already held by four joints
      if (fixed) {
        rows.conservativeResize(first + 6, 6);
        rows.block<6, 6>(first, 0) = Mat6::Identity();
        continue;
      }
      // The pivot p is held, v + ω × (p − c) = 0; ω has no part across the axis a.
      const Vec3 across1 = axis.unitOrthogonal(), across2 = axis.cross(across1);
      rows.conservativeResize(first + 5, 6);
      rows.block<3, 3>(first, 0) = Mat3::Identity();
      rows.block<3, 3>(first, 3) = -crossMatrix(pivot - states[member].centerOfMass);
      rows.row(first + 3) << 0, 0, 0, across1.transpose();
      rows.row(first + 4) << 0, 0, 0, across2.transpose();
    }
  }
  for (size_t i = 0; i < states.size(); ++i) states[i].restrictMotion(locked[i]);
}

void BulletWorld::loadRigidVelocities(std::span<RigidSolverState> states) const {
  assert(states.size() == m_impl->bodies.size());
  for (size_t i = 0; i < states.size(); ++i) {
    RigidSolverState& state = states[i];
    const btSolverBody* solverBody = m_impl->solverBody(static_cast<int>(i));
    if (solverBody && solverBody->m_originalBody) {
      state.linearVelocity = fromBt(solverBody->m_linearVelocity + solverBody->m_externalForceImpulse +
                                    solverBody->m_deltaLinearVelocity);
      state.angularVelocity = fromBt(solverBody->m_angularVelocity + solverBody->m_externalTorqueImpulse +
                                     solverBody->m_deltaAngularVelocity);
    } else {
      state.linearVelocity.setZero();
      state.angularVelocity.setZero();
    }
    state.loadedLinearVelocity = state.linearVelocity;
    state.loadedAngularVelocity = state.angularVelocity;
  }
}

void BulletWorld::storeRigidVelocities(std::span<RigidSolverState> states) {
  for (size_t i = 0; i < states.size(); ++i) {
    RigidSolverState& state = states[i];
    if (state.inverseMass == 0.0) continue;
    btSolverBody& solverBody = m_impl->solver.solverBodies()[m_impl->bodies[i]->getCompanionId()];
    solverBody.m_deltaLinearVelocity += toBt(state.linearVelocity - state.loadedLinearVelocity);
    solverBody.m_deltaAngularVelocity += toBt(state.angularVelocity - state.loadedAngularVelocity);
    state.loadedLinearVelocity = state.linearVelocity;
    state.loadedAngularVelocity = state.angularVelocity;
  }
}

Vec3 BulletWorld::position(int body) const { return fromBt(m_impl->bodies[body]->getCenterOfMassPosition()); }
Quat BulletWorld::orientation(int body) const { return fromBt(m_impl->bodies[body]->getOrientation()); }
Vec3 BulletWorld::linearVelocity(int body) const { return fromBt(m_impl->bodies[body]->getLinearVelocity()); }
Vec3 BulletWorld::angularVelocity(int body) const { return fromBt(m_impl->bodies[body]->getAngularVelocity()); }
double BulletWorld::mass(int body) const {
  const double inverse = m_impl->bodies[body]->getInvMass();
  return inverse > 0 ? 1.0 / inverse : 0.0;
}
Mat3 BulletWorld::inertia(int body) const {
  const btRigidBody& b = *m_impl->bodies[body];
  if (b.getInvMass() == 0) return Mat3::Zero();
  return fromBt(b.getInvInertiaTensorWorld()).inverse();
}
bool BulletWorld::isAwake(int body) const { return m_impl->bodies[body]->isActive(); }
bool BulletWorld::isDynamic(int body) const { return m_impl->bodies[body]->getInvMass() > 0; }
void BulletWorld::wake(int body) {
  btRigidBody& b = *m_impl->bodies[body];
  if (b.getActivationState() == ISLAND_SLEEPING) b.forceActivationState(ACTIVE_TAG);
  b.activate(true);
}
void BulletWorld::restartSleepTimer(int body) { m_impl->bodies[body]->setDeactivationTime(0); }
void BulletWorld::putToSleep(int body) {
  btRigidBody& b = *m_impl->bodies[body];
  b.forceActivationState(ISLAND_SLEEPING);
  b.setLinearVelocity(btVector3(0, 0, 0));
  b.setAngularVelocity(btVector3(0, 0, 0));
}
void BulletWorld::setCanSleep(int body, bool canSleep) {
  btRigidBody& b = *m_impl->bodies[body];
  if (b.isKinematicObject()) return;  // kinematic bodies never sleep
  b.forceActivationState(canSleep ? ACTIVE_TAG : DISABLE_DEACTIVATION);
  b.activate(true);
}
void BulletWorld::setDamping(int body, double linearDamping, double angularDamping) {
  m_impl->bodies[body]->setDamping(linearDamping, angularDamping);
}
void BulletWorld::setKinematicTarget(int body, const Vec3& position, const Quat& orientation) {
  m_impl->motionStates[body]->setWorldTransform(btTransform(toBt(orientation.normalized()), toBt(position)));
}

void BulletWorld::beginStep() {
  Impl& w = *m_impl;
  w.pairImpulses.clear();
  w.contactPoints.clear();
  w.stepForce.swap(w.pendingForce);
  w.stepTorque.swap(w.pendingTorque);
  for (Vec3& f : w.pendingForce) f.setZero();
  for (Vec3& t : w.pendingTorque) t.setZero();
}

std::span<const BulletWorld::ContactPoint> BulletWorld::contactPoints() const { return m_impl->contactPoints; }

// After each solve: its contact impulses added per pair of bodies (a step of n substeps solves
// n times; what it reports is their sum).
void BulletWorld::addContactImpulses() {
  for (const btPersistentManifold* manifold : m_impl->world.solvedManifolds()) {
    double total = 0.0;
    const int a = manifold->getBody0()->getUserIndex(), b = manifold->getBody1()->getUserIndex();
    for (int p = 0; p < manifold->getNumContacts(); ++p) {
      const btManifoldPoint& point = manifold->getContactPoint(p);
      total += point.m_appliedImpulse;
      const Vec3 friction = point.m_appliedImpulseLateral1 * fromBt(point.m_lateralFrictionDir1) +
                            point.m_appliedImpulseLateral2 * fromBt(point.m_lateralFrictionDir2);
      m_impl->contactPoints.push_back({a, b, fromBt(point.getPositionWorldOnA()), fromBt(point.getPositionWorldOnB()),
                                       fromBt(point.m_normalWorldOnB), point.getDistance(), point.m_appliedImpulse,
                                       friction});
    }
    if (total == 0.0) continue;
    const int low = std::min(a, b), high = std::max(a, b);
    auto& pairs = m_impl->pairImpulses;
    auto pair = std::find_if(pairs.begin(), pairs.end(), [&](const Impl::PairImpulse& q) {
      return q.bodyA == low && q.bodyB == high;
    });
    if (pair == pairs.end())
      pairs.push_back({low, high, total});
    else
      pair->impulse += total;
  }
}

double BulletWorld::contactImpulse(int bodyA, int bodyB) const {
  const int low = std::min(bodyA, bodyB), high = std::max(bodyA, bodyB);
  for (const Impl::PairImpulse& pair : m_impl->pairImpulses)
    if (pair.bodyA == low && pair.bodyB == high) return pair.impulse;
  return 0.0;
}

int BulletWorld::manifoldCount() const { return m_impl->world.getDispatcher()->getNumManifolds(); }
std::optional<BulletWorld::RayHit> BulletWorld::castRay(const Vec3& from, const Vec3& to) const {
  btCollisionWorld::ClosestRayResultCallback result(toBt(from), toBt(to));
  m_impl->world.rayTest(toBt(from), toBt(to), result);
  if (!result.hasHit() || !result.m_collisionObject) return std::nullopt;
  return RayHit{result.m_collisionObject->getUserIndex(), result.m_closestHitFraction,
                fromBt(result.m_hitNormalWorld).normalized()};
}
int BulletWorld::jointCount() const { return m_impl->world.getNumConstraints(); }
double BulletWorld::sleepingThreshold(int body) const {
  return m_impl->bodies[body]->getLinearSleepingThreshold();
}

}  // namespace tandem::bullet
