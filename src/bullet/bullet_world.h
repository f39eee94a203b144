// The one module that knows Bullet's dynamics world and constraint solver internals.
//
// Tandem drives Bullet stage by stage (World::step), and runs its own sweep inside Bullet's
// sequential-impulse solve: after Bullet's setup (warm start) and after each of Bullet's
// iterations (one PGS sweep over Tandem's rows), before Bullet writes velocities back.
// During the solve, Tandem's rows read and write the same btSolverBody velocities Bullet
// iterates on, through loadRigidStates/storeRigidStates.
#pragma once

#include <tandem/world.h>

#include "solver/solver_state.h"

#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace tandem::bullet {

class SolverHooks {
 public:
  virtual ~SolverHooks() = default;
  virtual void afterSetup() = 0;                 // solver bodies exist: warm start Tandem's rows
  virtual void afterIteration(int iteration) = 0;  // one of Bullet's iterations is done
};

// The face planes (n, d with n·x = d, n outward) of the convex hull of `points`.
std::vector<Eigen::Vector4d> convexHullPlanes(const std::vector<Vec3>& points);
// The vertices of the convex hull of `points` (the points that are corners of it).
std::vector<Vec3> convexHullVertices(const std::vector<Vec3>& points);

class BulletWorld {
 public:
  explicit BulletWorld(const Vec3& gravity);
  ~BulletWorld();
  BulletWorld(const BulletWorld&) = delete;
  BulletWorld& operator=(const BulletWorld&) = delete;

  void setGravity(const Vec3& gravity);

  // The descriptor is validated by the caller. Each goes into slot `slot` (a removed one, or the
  // next new one: rigidBodyCount() or jointSlotCount()) and returns it.
  int addRigidBody(const RigidBodyDesc& desc, int slot);
  int addHinge(const HingeDesc& desc, int slot);
  int addFixedJoint(const FixedJointDesc& desc, int slot);
  int rigidBodyCount() const;  // slots, removed bodies included: every array is indexed by slot
  int jointSlotCount() const;

  // Removal (bullet_edit.cpp). A removed body leaves the dynamics world (its contacts go with
  // it) and stays in its slot as an immovable ghost until the slot is reused. Its joints must
  // have been removed first.
  void removeRigidBody(int body);
  void removeJoint(int joint);
  bool isRemoved(int body) const;
  // The joints (slots) that hold a body.
  std::vector<int> jointsOf(int body) const;

  // Pushing and moving (bullet_edit.cpp); the caller checks that the body is dynamic.
  void addForce(int body, const Vec3& force, const Vec3& torque);  // for the next step
  void applyImpulse(int body, const Vec3& impulse, const Vec3& offsetFromCentre);
  void applyAngularImpulse(int body, const Vec3& angularImpulse);
  void setLinearVelocity(int body, const Vec3& velocity);
  void setAngularVelocity(int body, const Vec3& velocity);
  void setPose(int body, const Vec3& position, const Quat& orientation);
  void setCollisionFilter(int body, uint32_t group, uint32_t mask);

  // Hinges (bullet_edit.cpp): the angle and speed of body A relative to B about the axis.
  bool isHinge(int joint) const;
  void setHingeLimits(int joint, double lower, double upper);
  void setHingeMotor(int joint, bool enabled, double targetSpeed, double maxTorque);
  double hingeAngle(int joint) const;
  double hingeSpeed(int joint) const;

  // One contact point of the step's solves (RigidContact, by body slot).
  struct ContactPoint {
    int bodyA, bodyB;
    Vec3 pointOnA, pointOnB, normal;
    double distance, normalImpulse;
    Vec3 frictionImpulse;
  };
  std::span<const ContactPoint> contactPoints() const;

  // Everything of Bullet's that the next step reads (bullet_snapshot.cpp).
  struct State;
  std::unique_ptr<State> saveState() const;
  // Returns how many saved manifolds found no pair of the broadphase's to go into (their points
  // are lost; 0 unless bodies moved apart between the contact pass and the save).
  int restoreState(const State& state);

  // Stages of a step, in order.
  void predictRigidMotion(double timeStep);
  void detectCollisions(double timeStep);
  void solve(double timeStep, int iterations, SolverHooks& hooks);
  void integrate(double timeStep);

  // Pose, mass and world inertia of every body. Static, kinematic and sleeping bodies load as
  // immovable (zero inverse mass and inertia).
  void loadRigidProperties(std::span<RigidSolverState> states) const;
  // During the solve only: solver-body velocities in and out of Tandem's rigid state.
  void loadRigidVelocities(std::span<RigidSolverState> states) const;
  void storeRigidVelocities(std::span<RigidSolverState> states);

  // Queries
  Vec3 position(int body) const;
  Quat orientation(int body) const;
  Vec3 linearVelocity(int body) const;
  Vec3 angularVelocity(int body) const;
  double mass(int body) const;
  Mat3 inertia(int body) const;  // world frame; zero for static and kinematic bodies
  bool isAwake(int body) const;
  bool isDynamic(int body) const;
  void wake(int body);
  void restartSleepTimer(int body);  // an awake body stays awake at least another 2 s
  void putToSleep(int body);
  void setCanSleep(int body, bool canSleep);
  void setDamping(int body, double linearDamping, double angularDamping);
  void setKinematicTarget(int body, const Vec3& position, const Quat& orientation);
  double contactImpulse(int bodyA, int bodyB) const;  // N·s over the step, summed over its solves
  // At the start of a step: the contact impulse sums and points cleared, and the forces applied
  // since the last step made this step's (each substep's prediction applies them).
  void beginStep();
  int manifoldCount() const;
  int jointCount() const;
  struct RayHit {
    int body;
    double fraction;  // of the way from `from` to `to`
    Vec3 normal;
  };
  std::optional<RayHit> castRay(const Vec3& from, const Vec3& to) const;
  // The body's linear sleeping threshold (m/s): slower than this, Bullet lets it sleep.
  double sleepingThreshold(int body) const;

 private:
  void restrictJointedBodies(std::span<RigidSolverState> states) const;
  struct Impl;
  std::unique_ptr<Impl> m_impl;
  void addContactImpulses();
};

}  // namespace tandem::bullet
