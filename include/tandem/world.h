// The Tandem world: Bullet rigid bodies and Tandem deformable bodies stepped together.
//
// Units are SI throughout: metres, kilograms, seconds, newtons. Impulses are in N·s.
// Everything a user adds is referred to by a small typed index; nothing hands out pointers.
#pragma once

#include <tandem/export.h>
#include <tandem/mesh.h>

#include <array>
#include <tandem/report.h>
#include <tandem/types.h>

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>
#include <string_view>

namespace tandem {

// ---- Ids and what a bad id gets --------------------------------------------------------------
//
// Every id is a slot index and a generation. Removing a thing frees its slot; a rigid body,
// joint, anchor, fixed point or grab added later may take the slot with the next generation
// (deformables never reuse a slot). An id is live while its slot holds that generation: an id
// of something removed, or of a slot since reused, is stale and is refused, never taken for
// whatever the slot holds now.
//
// One rule for every call that takes an id:
//  - A call that returns Status or Result refuses a bad or stale id with an error naming it
//    ("rigid body 7: no such rigid body (the world has 3 slots)", "anchor 2 (generation 0) was
//    removed"), and changes nothing.
//  - A query that returns a value (rigidPosition, nodePositions, anchorState, ...) has a live id
//    as its precondition. Given a bad or stale id it returns a neutral value (zero vectors, the
//    identity rotation, 0, false, an empty span or string) and records the error, which
//    takeLookupError() hands back. This holds in every build type: nothing asserts, throws or
//    crashes. Check an id beforehand with contains().
// Ids made from a bare index (RigidBodyId{3}) carry generation 0: they name the slot's first
// occupant.
struct RigidBodyId {
  int32_t index = -1;
  uint32_t generation = 0;
  friend bool operator==(RigidBodyId, RigidBodyId) = default;
};
struct DeformableId {
  int32_t index = -1;
  uint32_t generation = 0;
  friend bool operator==(DeformableId, DeformableId) = default;
};
struct AnchorId {
  int32_t index = -1;
  uint32_t generation = 0;
  friend bool operator==(AnchorId, AnchorId) = default;
};
struct FixedPointId {
  int32_t index = -1;
  uint32_t generation = 0;
  friend bool operator==(FixedPointId, FixedPointId) = default;
};
struct JointId {
  int32_t index = -1;
  uint32_t generation = 0;
  friend bool operator==(JointId, JointId) = default;
};
struct GrabId {
  int32_t index = -1;
  uint32_t generation = 0;
  friend bool operator==(GrabId, GrabId) = default;
};

// Collision filtering: two things (rigid bodies or deformables) collide when
// (groupA & maskB) != 0 and (groupB & maskA) != 0. By default everything is in group 1 and
// collides with all groups. A deformable's contacts with itself are governed by selfCollision.
inline constexpr uint32_t kDefaultCollisionGroup = 1;
inline constexpr uint32_t kAllCollisionGroups = 0xFFFFFFFFu;
inline bool collisionGroupsMeet(uint32_t groupA, uint32_t maskA, uint32_t groupB, uint32_t maskB) {
  return (groupA & maskB) != 0 && (groupB & maskA) != 0;
}

inline constexpr double kUnbounded = std::numeric_limits<double>::infinity();

// ---- Solver ---------------------------------------------------------------------------------

// How a contact's friction impulse is bounded. Coulomb: |λₜ| ≤ μ λₙ, by the contact's own
// normal impulse, right whatever presses the surfaces together. Pressure: the paper's
// |λₜ| ≤ μ m |g·n| h, from the weight of the contact's mass alone.
enum class FrictionModel { Coulomb, Pressure };

struct SolverSettings {
  int iterations = 4;        // K: each is one Bullet iteration, then one sweep over Tandem's rows
  int substeps = 1;          // n: the solve and the integration run n times per step, each over h/n
  double baumgarte = 0.1;    // β·h: the fraction of a position error corrected per step (β = 0.1/h)
  bool warmStart = true;     // start each row from last step's impulse
  FrictionModel friction = FrictionModel::Coulomb;
  double contactSlop = 0.001;  // m of penetration left alone, so resting contacts do not jitter
};

struct WorldSettings {
  Vec3 gravity{0.0, -9.81, 0.0};  // m/s²
  SolverSettings solver;
  // A node or rigid body faster than this (m/s), or with a non-finite state, means the
  // simulation diverged: step() reports it instead of carrying on with garbage.
  double divergenceSpeed = 1.0e4;
};

// ---- Rigid bodies (Bullet) ------------------------------------------------------------------

enum class ShapeType { Box, Sphere, Cylinder, Capsule, Plane, ConvexHull, TriangleMesh, Compound };

// How a body is drawn when that is not its collision shape (a mesh body: its triangles, while it
// collides as convex hulls). In the body's frame; triangles counter-clockwise seen from outside.
struct VisualMesh {
  std::vector<Vec3> positions;
  std::vector<std::array<int32_t, 3>> triangles;
  bool empty() const { return triangles.empty(); }
};

struct TANDEM_API RigidShape {
  ShapeType type = ShapeType::Box;
  Vec3 halfExtents{0.5, 0.5, 0.5};  // box
  double radius = 0.5;              // sphere, cylinder, capsule
  double halfHeight = 0.5;          // cylinder, capsule: along the body's local y axis
  Vec3 planeNormal{0.0, 1.0, 0.0};  // plane: points n with n·x = planeOffset
  double planeOffset = 0.0;
  std::vector<Vec3> points;                       // convex hull: its points; triangle mesh: its vertices
  std::vector<std::array<int32_t, 3>> triangles;  // triangle mesh (static bodies only)
  std::vector<std::vector<Vec3>> hulls;           // compound: each convex part's points
  VisualMesh visual;  // drawn instead of the collision shape when not empty (renderer, viewer, export)

  static RigidShape box(const Vec3& halfExtents);
  static RigidShape sphere(double radius);
  static RigidShape cylinder(double radius, double halfHeight);
  static RigidShape capsule(double radius, double halfHeight);
  static RigidShape plane(const Vec3& normal, double offset);
  static RigidShape convexHull(std::vector<Vec3> points);  // in the body's frame, about its centre of mass
  static RigidShape triangleMesh(std::vector<Vec3> vertices, std::vector<std::array<int32_t, 3>> triangles);
  // Several convex hulls moving as one body (Bullet's btCompoundShape of btConvexHullShapes), each
  // of at least 4 points spanning a volume, in the body's frame about its centre of mass.
  // Rigid bodies built from a closed mesh (include/tandem/mesh_body.h) are one hull or these.
  static RigidShape compound(std::vector<std::vector<Vec3>> hulls);
};

enum class MotionType { Dynamic, Static, Kinematic };

struct RigidBodyDesc {
  std::string name;
  RigidShape shape;
  MotionType motion = MotionType::Dynamic;
  double mass = 1.0;  // kg, dynamic bodies only
  // kg·m²: the principal moments of inertia about the centre of mass, along the body's own axes
  // (each > 0, and none more than the sum of the other two). Unset: Bullet's, from the shape and
  // the mass (exact for boxes, spheres, cylinders and capsules; the bounding box's for hulls and
  // compounds). A mesh body (makeMeshBody) has them from its volume.
  std::optional<Vec3> inertia;
  Vec3 position = Vec3::Zero();
  Quat orientation = Quat::Identity();
  Vec3 linearVelocity = Vec3::Zero();   // m/s
  Vec3 angularVelocity = Vec3::Zero();  // rad/s, world frame
  double friction = 0.5;
  double restitution = 0.0;
  // Velocity damping, as Bullet's: the fraction of the linear (angular) velocity a dynamic body
  // loses per second, each in [0, 1]; v(t) = v(0) (1 − d)^t when nothing else acts. Air drag or a
  // body's own losses, which an undamped simulation keeps for ever (a pendulum swings on).
  double linearDamping = 0.0;
  double angularDamping = 0.0;
  // Bullet lets a body that has been slow for 2 s sleep: it stops moving and stops reporting
  // contact forces. Turn this off for bodies whose contact forces you read. (A body anchored
  // to a deformable never falls asleep on its own; put to sleep, it wakes when the deformable
  // moves.)
  bool canSleep = true;
  uint32_t collisionGroup = kDefaultCollisionGroup;  // see collisionGroupsMeet
  uint32_t collisionMask = kAllCollisionGroups;
};

// A revolute joint about `axis` through `pivot` (both world frame, at creation time),
// between `bodyA` and `bodyB`, or between `bodyA` and the world when bodyB is unset.
//
// Its angle is bodyA's rotation about the axis relative to bodyB (or the world) since the hinge
// was made, right-handed about `axis`, in radians; its speed is the rate of that angle.
// Limits keep the angle in [lowerLimit, upperLimit] (lowerLimit > upperLimit: no limit); the
// motor drives the speed towards motorTargetSpeed with at most motorMaxTorque (N·m), both
// through Bullet's btHingeConstraint.
struct HingeDesc {
  RigidBodyId bodyA;
  std::optional<RigidBodyId> bodyB;
  Vec3 pivot = Vec3::Zero();
  Vec3 axis{0.0, 0.0, 1.0};
  double lowerLimit = 1.0;  // rad; the default (lower > upper) is no limit
  double upperLimit = -1.0;
  bool motor = false;
  double motorTargetSpeed = 0.0;  // rad/s
  double motorMaxTorque = 0.0;    // N·m
};

// One contact point between two rigid bodies (Bullet's) in the last step. Impulses are on
// bodyA; bodyB got the opposite. With n substeps each substep's points are listed, so the
// impulses of all points of a pair sum to what the pair exchanged over the step.
struct RigidContact {
  RigidBodyId bodyA, bodyB;
  Vec3 pointOnA = Vec3::Zero();  // world frame, m
  Vec3 pointOnB = Vec3::Zero();
  Vec3 normal = Vec3::UnitY();   // from B to A
  double distance = 0.0;         // m, negative when penetrating
  double normalImpulse = 0.0;    // N·s, >= 0
  Vec3 frictionImpulse = Vec3::Zero();  // N·s, tangential
};

// Holds `bodyA` to `bodyB` (or to the world when bodyB is unset) in their pose at creation time.
struct FixedJointDesc {
  RigidBodyId bodyA;
  std::optional<RigidBodyId> bodyB;
};

// ---- Deformable bodies ----------------------------------------------------------------------

// How an inextensibility row's impulse is bounded (paper §4.2).
enum class InextensibilityMode {
  ResistBoth,         // -maxForce·h ≤ λ ≤ maxForce·h
  ResistCompression,  // 0 ≤ λ ≤ maxForce·h: pushes apart, never pulls
  ResistStretch,      // -maxForce·h ≤ λ ≤ 0: pulls together, never pushes
};

struct InextensibilitySettings {
  bool enabled = false;
  InextensibilityMode mode = InextensibilityMode::ResistBoth;
  double maxForce = kUnbounded;  // N; the impulse bound per step is maxForce·h
  bool shearEdges = false;       // also on the mesh's shear edges (a cloth's diagonals)
};

// Bending resists folding across each interior edge (paper §4.5) as a damped spring of the
// given natural frequency, up to maxForce. An infinite frequency makes it the paper's rigid row.
struct BendingSettings {
  bool enabled = false;
  double maxForce = 1.0;     // N; bounds |λ| ≤ maxForce·h
  double frequency = 10.0;   // Hz: how stiff
  double dampingRatio = 1.0;
};

struct MassSpringSettings {
  double stiffness = 0.0;  // N/m per edge spring
  double damping = 0.0;    // N·s/m per edge spring, along the edge
  // Linearised backward Euler (stable at any stiffness, slightly damped); false steps the springs
  // explicitly: cheaper, but stable only while h √(k/m) stays below about 2 at every node.
  bool implicit = true;
};

// How a deformable's bilateral rows (fixed points, anchors and inextensibility without force
// bounds) are solved in each sweep. Direct: exactly, as one block (sparse LDLᵀ factorised once
// per step): rigid-grade ropes and attachments at any mass ratio. Iterative: by the projected
// Gauss-Seidel sweep like every other row, cheaper per sweep for large cloths but slow to
// converge when light nodes hold heavy bodies. Auto: direct for ropes (chains, whose block costs
// time linear in their length) at any length; for surfaces and solids up to kAutoDirectRowLimit rows.
enum class RowSolverKind { Auto, Direct, Iterative };
inline constexpr int kAutoDirectRowLimit = 1500;

// How a deformable computes the unconstrained velocity of its nodes each step (paper §3); the
// solver treats every paradigm alike, and they mix freely in one scene.
enum class ParadigmType {
  MassSpring,     // forces from the springs on its edges (DeformableDesc::springs)
  ShapeMatching,  // goals from its rest shape matched onto it (paper eq. 2)
  PositionBased,  // goals from projecting its distance and volume constraints (paper eq. 3)
  CorotationalFem,  // linear elasticity on its tetrahedra, rotations removed, solved implicitly
};

struct ParadigmSettings {
  ParadigmType type = ParadigmType::MassSpring;
  double stiffness = 1.0;  // k in (0, 1]: how far towards its goals a body goes per step
  double damping = 0.0;    // γ in [0, 1]
  int iterations = 4;      // constraint projections per step (position-based)
  double youngsModulus = 50e3;  // E, Pa (co-rotational FEM)
  double poissonRatio = 0.3;    // ν in [0, 0.5) (co-rotational FEM)
};

struct CollisionSettings {
  bool enabled = true;         // against rigid bodies and other deformables
  bool selfCollision = false;  // against itself, away from its own neighbourhood
  double thickness = 0.005;    // m: the surface is kept this far from anything it touches
  double friction = 0.5;       // μ; a contact's μ is the product of both sides'
  uint32_t group = kDefaultCollisionGroup;  // see collisionGroupsMeet
  uint32_t mask = kAllCollisionGroups;
};

struct DeformableDesc {
  std::string name;
  DeformableMesh mesh;
  MassSpringSettings springs;
  InextensibilitySettings inextensibility;
  BendingSettings bending;
  ParadigmSettings paradigm;
  CollisionSettings collision;
  RowSolverKind rowSolver = RowSolverKind::Auto;
  // 1/s: each step, every node loses this fraction per second of its velocity relative to the
  // body's mean velocity. Internal motion dies down; momentum is untouched.
  double damping = 0.0;
};

// A contact of a deformable surface in the last step. Impulses are on the deformable (side A);
// the other side got the opposite. They include what the deformable's model gave the node
// holding it on its support (normal and, for FEM and spring bodies on still surfaces, friction).
struct ContactReport {
  DeformableId deformable;
  std::optional<RigidBodyId> rigid;          // side B: a rigid body, or
  std::optional<DeformableId> other;         // a deformable (possibly the same one)
  Vec3 point = Vec3::Zero();                 // on side A, m
  Vec3 normal = Vec3::UnitY();               // from B to A
  double gap = 0.0;                          // m at the start of the step, thickness taken off
  double normalImpulse = 0.0;                // N·s, ≥ 0
  Vec3 frictionImpulse = Vec3::Zero();       // N·s, tangential
};

// A point fixed in a rigid body that a point of a deformable is held to: a node, or a point
// with barycentric weights on up to four nodes (an edge, a face or a tetrahedron).
struct TANDEM_API AnchorDesc {
  DeformableId deformable;
  std::array<int32_t, 4> nodes{-1, -1, -1, -1};
  std::array<double, 4> weights{1.0, 0.0, 0.0, 0.0};  // must sum to 1
  int nodeCount = 1;
  RigidBodyId body;
  std::optional<Vec3> localPoint;  // in the body's frame; default: where the deformable point is now
  double maxForce = kUnbounded;    // N; the anchor lets go of nothing, it only limits its pull

  static AnchorDesc node(DeformableId deformable, int32_t node, RigidBodyId body);
};

struct AnchorState {
  Vec3 impulse = Vec3::Zero();  // N·s applied to the deformable in the last step (body gets −impulse)
  Vec3 worldPointOnBody = Vec3::Zero();
  Vec3 worldPointOnDeformable = Vec3::Zero();
};

// ---- Grabs and ray casts: what a hand or a mouse needs ---------------------------------------

// A point of a dynamic rigid body, or of a deformable (a node, or barycentric on up to four
// nodes), pulled towards a target by a damped spring of natural frequency `frequency` up to
// `maxForce`. The spring scales with the point's effective mass, so a cloth node and a heavy
// box follow alike; it is a row of the interleaved solve, so what the point is tied to answers
// in the same step (src/constraints/grab.h).
struct GrabDesc {
  std::optional<RigidBodyId> body;         // either a rigid body (dynamic) ...
  std::optional<DeformableId> deformable;  // ... or a deformable
  Vec3 point = Vec3::Zero();               // rigid: the grabbed point, world frame, now
  std::array<int32_t, 4> nodes{-1, -1, -1, -1};        // deformable: local node indices
  std::array<double, 4> weights{1.0, 0.0, 0.0, 0.0};   // summing to 1
  int nodeCount = 1;
  Vec3 target = Vec3::Zero();  // world frame; moved with setGrabTarget
  double frequency = 5.0;      // Hz
  double dampingRatio = 1.0;
  double maxForce = kUnbounded;  // N
};

// The first surface a ray meets: a rigid body's shape, or a deformable's surface triangle.
struct RayHit {
  std::optional<RigidBodyId> rigid;
  std::optional<DeformableId> deformable;
  std::array<int32_t, 3> nodes{-1, -1, -1};  // deformable: the triangle's local node indices
  std::array<double, 3> weights{};            //   and the hit's barycentric weights on them
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitY();  // facing the ray's origin
  double distance = 0.0;        // m from the origin along the (normalised) direction
};

// A copy of a world's whole state (World::snapshot): see World::restore.
class TANDEM_API WorldSnapshot {
 public:
  WorldSnapshot();
  ~WorldSnapshot();
  WorldSnapshot(WorldSnapshot&&) noexcept;
  WorldSnapshot& operator=(WorldSnapshot&&) noexcept;
  WorldSnapshot(const WorldSnapshot&) = delete;
  WorldSnapshot& operator=(const WorldSnapshot&) = delete;
  bool empty() const;      // default-made: holds no state
  double time() const;     // the world's time when it was taken
  int64_t stepCount() const;

  struct Data;
  explicit WorldSnapshot(std::unique_ptr<Data> data);
  const Data* data() const { return m_data.get(); }

 private:
  std::unique_ptr<Data> m_data;
};

class TANDEM_API World {
 public:
  World();  // default settings; change them with setSettings
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  // Settings (validated: a bad value is refused with a message and nothing changes)
  Status setSettings(const WorldSettings& settings);
  const WorldSettings& settings() const;

  // ---- Ids (see "Ids and what a bad id gets" above) ----
  bool contains(RigidBodyId id) const;  // live: added and not removed since
  bool contains(DeformableId id) const;
  bool contains(JointId id) const;
  bool contains(AnchorId id) const;
  bool contains(FixedPointId id) const;
  bool contains(GrabId id) const;
  // The first bad-id error a value-returning query recorded since the last call (ok if none);
  // the record is cleared.
  Status takeLookupError() const;

  // ---- Rigid bodies and joints ----
  Result<RigidBodyId> addRigidBody(const RigidBodyDesc& desc);
  Result<JointId> addHinge(const HingeDesc& desc);
  Result<JointId> addFixedJoint(const FixedJointDesc& desc);
  int rigidBodyCount() const;                // live bodies
  std::vector<RigidBodyId> rigidBodies() const;  // the live bodies' ids, by index
  std::optional<RigidBodyId> findRigidBody(std::string_view name) const;
  const std::string& rigidName(RigidBodyId body) const;
  Vec3 rigidPosition(RigidBodyId body) const;  // centre of mass, world frame
  Quat rigidOrientation(RigidBodyId body) const;
  Vec3 rigidLinearVelocity(RigidBodyId body) const;
  Vec3 rigidAngularVelocity(RigidBodyId body) const;
  double rigidMass(RigidBodyId body) const;  // 0 for static and kinematic bodies
  Mat3 rigidInertia(RigidBodyId body) const;  // kg·m², world frame, about the centre of mass; 0 if not dynamic
  bool rigidIsAwake(RigidBodyId body) const;
  Status putRigidToSleep(RigidBodyId body);
  Status setRigidCanSleep(RigidBodyId body, bool canSleep);
  // RigidBodyDesc::linearDamping and angularDamping, each in [0, 1], from the next step on
  // (kept in snapshots).
  Status setRigidDamping(RigidBodyId body, double linearDamping, double angularDamping);
  // Moves a kinematic body to this pose by the end of the next step (its velocity follows).
  Status setKinematicTarget(RigidBodyId body, const Vec3& position, const Quat& orientation);

  // Pushing a dynamic body. Forces (N) and torques (N·m) accumulate until the next step and act
  // uniformly over it (every substep), then are cleared; impulses (N·s) change the velocity at
  // once: Δv = J/m, Δω = I⁻¹ (r × J) with r from the centre of mass to the point. Points are
  // in the world frame. Each wakes the body. Static and kinematic bodies are refused.
  Status applyForce(RigidBodyId body, const Vec3& force);  // at the centre of mass
  Status applyForceAtPoint(RigidBodyId body, const Vec3& force, const Vec3& point);
  Status applyTorque(RigidBodyId body, const Vec3& torque);
  Status applyImpulse(RigidBodyId body, const Vec3& impulse);  // at the centre of mass
  Status applyImpulseAtPoint(RigidBodyId body, const Vec3& impulse, const Vec3& point);
  Status applyAngularImpulse(RigidBodyId body, const Vec3& angularImpulse);  // N·m·s: Δω = I⁻¹ L
  // Velocities of a dynamic body (m/s; rad/s, world frame); wakes it.
  Status setRigidLinearVelocity(RigidBodyId body, const Vec3& velocity);
  Status setRigidAngularVelocity(RigidBodyId body, const Vec3& velocity);
  // Teleports a body (any motion type) to a pose: centre of mass and orientation, world frame.
  // Velocities are kept; a dynamic body is woken; a kinematic body's target becomes this pose.
  // Anchors and joints on it pull it back towards what they hold in the next step.
  Status setRigidPose(RigidBodyId body, const Vec3& position, const Quat& orientation);
  // Who collides with the body from now on (see collisionGroupsMeet).
  Status setRigidCollisionFilter(RigidBodyId body, uint32_t group, uint32_t mask);
  uint32_t rigidCollisionGroup(RigidBodyId body) const;
  uint32_t rigidCollisionMask(RigidBodyId body) const;

  // Sum of the normal impulses (N·s) of Bullet's contacts between two rigid bodies in the last step.
  double rigidContactImpulse(RigidBodyId a, RigidBodyId b) const;
  // Every contact point between rigid bodies in the last step (see RigidContact).
  std::vector<RigidContact> rigidContacts() const;
  // Total impulse (N·s) and angular impulse about the centre of mass (N·m·s) that Tandem's
  // rows put on a rigid body in the last step.
  Vec3 deformableImpulseOnRigid(RigidBodyId body) const;
  Vec3 deformableAngularImpulseOnRigid(RigidBodyId body) const;
  // The same as a mean force (N) and torque about the centre of mass (N·m) over the last step.
  Vec3 deformableForceOnRigid(RigidBodyId body) const;
  Vec3 deformableTorqueOnRigid(RigidBodyId body) const;

  // Hinges (joints made by addHinge; a fixed joint's id is refused): see HingeDesc.
  Status setHingeLimits(JointId hinge, double lower, double upper);  // lower > upper: no limit
  Status setHingeMotor(JointId hinge, bool enabled, double targetSpeed, double maxTorque);
  double hingeAngle(JointId hinge) const;  // rad
  double hingeSpeed(JointId hinge) const;  // rad/s

  // ---- Deformable bodies ----
  Result<DeformableId> addDeformable(const DeformableDesc& desc);
  int deformableCount() const;                   // live deformables
  std::vector<DeformableId> deformableIds() const;  // the live deformables' ids, by index
  std::optional<DeformableId> findDeformable(std::string_view name) const;
  const std::string& deformableName(DeformableId body) const;
  std::span<const Vec3> nodePositions(DeformableId body) const;
  std::span<const Vec3> nodeVelocities(DeformableId body) const;
  std::span<const double> nodeInverseMasses(DeformableId body) const;
  const DeformableMesh& restMesh(DeformableId body) const;  // the mesh as added
  Status setNodeVelocity(DeformableId body, int32_t node, const Vec3& velocity);
  // Moves a node (a teleport: no velocity, no collision on the way); its rest shape is unchanged.
  Status setNodePosition(DeformableId body, int32_t node, const Vec3& position);
  // Pins a node where it is: its inverse mass becomes zero.
  Status fixNode(DeformableId body, int32_t node);
  // Who the deformable's surface collides with from now on (see collisionGroupsMeet).
  Status setDeformableCollisionFilter(DeformableId body, uint32_t group, uint32_t mask);

  // ---- Constraints between a deformable and the world or a rigid body ----
  Result<FixedPointId> addFixedPoint(DeformableId body, int32_t node, const Vec3& target,
                                     double maxForce = kUnbounded);
  Status setFixedPointTarget(FixedPointId id, const Vec3& target);  // kinematic target
  Vec3 fixedPointImpulse(FixedPointId id) const;                    // N·s on the node, last step
  Result<AnchorId> addAnchor(const AnchorDesc& desc);
  AnchorState anchorState(AnchorId id) const;

  // ---- Removal ----
  // Each takes the thing out of the world with everything that refers to it: a rigid body's
  // joints, anchors, grabs and contacts (Bullet's and Tandem's); a deformable's springs, rows,
  // fixed points, anchors, grabs and contacts. Warm-start impulses of what remains are kept.
  // The removed ids (and those of what went with them) are refused from then on.
  Status removeRigidBody(RigidBodyId body);
  Status removeDeformable(DeformableId body);
  Status removeJoint(JointId joint);
  Status removeAnchor(AnchorId anchor);
  Status removeFixedPoint(FixedPointId fixedPoint);

  // ---- Grabs (one at a time or many) ----
  Result<GrabId> addGrab(const GrabDesc& desc);
  Status setGrabTarget(GrabId id, const Vec3& target);
  Status removeGrab(GrabId id);
  Vec3 grabImpulse(GrabId id) const;  // N·s on the grabbed point in the last step
  Vec3 grabPoint(GrabId id) const;    // where the grabbed point is now

  // The nearest rigid shape or deformable surface along a ray (static bodies included), if any
  // within maxDistance.
  std::optional<RayHit> castRay(const Vec3& origin, const Vec3& direction, double maxDistance = 1.0e3) const;

  // The shape a rigid body was made with, in its frame about its centre of mass.
  const RigidShape& rigidShape(RigidBodyId body) const;

  // Contacts of deformable surfaces in the last step.
  std::vector<ContactReport> contacts() const;

  // ---- Stepping ----
  // A step that produces a non-finite state returns an error naming the body and node (or
  // rigid body) and leaves the world in that state for inspection.
  Status step(double timeStep);
  const StepReport& lastReport() const;
  double time() const;  // simulated seconds so far
  int64_t stepCount() const;
  double lastTimeStep() const;  // h of the last step (0 before the first): impulses / h are forces

  // ---- Save and restore ----
  // A copy of the whole state the next step reads: rigid bodies (pose, velocities, sleep state,
  // forces applied since the last step, Bullet's contact points with their warm-start
  // impulses), deformables (nodes, models' state, supports), every row with its warm-start
  // impulse, grabs' and fixed points' targets, settings, time. restore() puts it back: stepping
  // on from there repeats, bit for bit, what stepping on from the snapshot did (see
  // docs/architecture.md for the one Bullet state that is rebuilt rather than copied).
  // A snapshot restores only into the world it was taken from (not into another world, even one
  // made later at the same address), and only while that world holds the same rigid bodies and
  // joints (adding or removing one since makes restore refuse). Deformables, anchors, fixed points
  // and grabs removed since come back; those added since go, and their ids are refused.
  WorldSnapshot snapshot() const;
  Status restore(const WorldSnapshot& snapshot);

  // Momentum of every dynamic thing in the world (deformable nodes with finite mass and dynamic
  // rigid bodies), for checking conservation.
  Vec3 totalLinearMomentum() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace tandem
