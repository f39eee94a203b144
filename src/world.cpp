#include <tandem/world.h>

#include "bullet/bullet_world.h"
#include "collision/contact_detection.h"
#include "format.h"
#include "models/mass_spring.h"
#include "solver/constraint_rows.h"
#include "solver/direct_block.h"

#include <algorithm>
#include <chrono>
#include <set>
#include <cmath>
#include <string>
#include <unordered_map>
#include <unordered_set>

namespace tandem {
namespace {

bool isPositive(double value) { return value > 0 && !std::isnan(value); }  // +inf allowed

// Passes over the contacts no direct block holds, after the blocks, in each iteration.
constexpr int kFreeContactPasses = 4;

struct DeformableRecord {
  std::string name;
  int32_t firstNode = 0;
  int32_t nodeCount = 0;
  DeformableMesh restMesh;
  RowSolverKind rowSolver = RowSolverKind::Auto;
  CollisionSettings collision;
  double damping = 0.0;
  std::vector<int32_t> surfaceNodes;                       // global indices
  std::vector<std::array<int32_t, 3>> surfaceTriangles;    // global indices
  std::vector<std::array<int32_t, 2>> surfaceEdges;        // global indices
};

class StageClock {
 public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - m_last).count();
    m_last = now;
    return seconds;
  }

 private:
  std::chrono::steady_clock::time_point m_last = std::chrono::steady_clock::now();
};

Status validateSettings(const WorldSettings& settings) {
  if (!settings.gravity.allFinite()) return Error{"settings: gravity must be finite"};
  if (settings.solver.iterations < 1 || settings.solver.iterations > 1000)
    return Error{"settings: solver iterations must be in [1, 1000], got " + std::to_string(settings.solver.iterations)};
  if (!(settings.solver.baumgarte >= 0 && settings.solver.baumgarte <= 1))
    return Error{"settings: baumgarte (β·h) must be in [0, 1], got " + formatNumber(settings.solver.baumgarte)};
  if (!(settings.solver.contactSlop >= 0 && std::isfinite(settings.solver.contactSlop)))
    return Error{"settings: contact slop must be >= 0 m, got " + formatNumber(settings.solver.contactSlop)};
  if (!(settings.divergenceSpeed > 0))
    return Error{"settings: divergence speed must be positive, got " + formatNumber(settings.divergenceSpeed)};
  return {};
}

Status validateShape(const RigidShape& s, const std::string& who) {
  auto positiveFinite = [](double v) { return std::isfinite(v) && v > 0; };
  switch (s.type) {
    case ShapeType::Box:
      if (!s.halfExtents.allFinite() || s.halfExtents.minCoeff() <= 0)
        return Error{who + ": box half extents must be positive and finite"};
      break;
    case ShapeType::Sphere:
      if (!positiveFinite(s.radius)) return Error{who + ": sphere radius must be positive, got " + formatNumber(s.radius)};
      break;
    case ShapeType::Cylinder:
    case ShapeType::Capsule:
      if (!positiveFinite(s.radius) || !positiveFinite(s.halfHeight))
        return Error{who + ": radius and half height must be positive, got " + formatNumber(s.radius) + " and " +
                     formatNumber(s.halfHeight)};
      break;
    case ShapeType::Plane:
      if (!s.planeNormal.allFinite() || s.planeNormal.norm() < 1e-9 || !std::isfinite(s.planeOffset))
        return Error{who + ": plane normal must be a finite non-zero vector and the offset finite"};
      break;
    case ShapeType::ConvexHull: {
      if (s.points.size() < 4) return Error{who + ": a convex hull needs at least 4 points"};
      for (size_t i = 0; i < s.points.size(); ++i)
        if (!s.points[i].allFinite()) return Error{who + ": convex hull point " + std::to_string(i) + " is not finite"};
      bool solid = false;  // some four points span a volume
      for (size_t i = 2; i < s.points.size() && !solid; ++i)
        for (size_t j = i + 1; j < s.points.size() && !solid; ++j)
          solid = std::abs((s.points[1] - s.points[0]).dot((s.points[i] - s.points[0]).cross(s.points[j] - s.points[0]))) > 1e-12;
      if (!solid) return Error{who + ": the convex hull's points are flat (no volume)"};
      break;
    }
    case ShapeType::TriangleMesh: {
      if (s.triangles.empty()) return Error{who + ": a triangle mesh needs at least one triangle"};
      DeformableMesh mesh;  // reuse the mesh checks: indices, finiteness, degenerate triangles
      mesh.positions = s.points;
      mesh.masses.assign(s.points.size(), 1.0);
      mesh.triangles = s.triangles;
      if (Status status = validateMesh(mesh); !status) return Error{who + ": triangle mesh: " + status.message()};
      break;
    }
  }
  return {};
}

}  // namespace

RigidShape RigidShape::box(const Vec3& halfExtents) {
  RigidShape s;
  s.type = ShapeType::Box;
  s.halfExtents = halfExtents;
  return s;
}
RigidShape RigidShape::sphere(double radius) {
  RigidShape s;
  s.type = ShapeType::Sphere;
  s.radius = radius;
  return s;
}
RigidShape RigidShape::cylinder(double radius, double halfHeight) {
  RigidShape s;
  s.type = ShapeType::Cylinder;
  s.radius = radius;
  s.halfHeight = halfHeight;
  return s;
}
RigidShape RigidShape::capsule(double radius, double halfHeight) {
  RigidShape s = cylinder(radius, halfHeight);
  s.type = ShapeType::Capsule;
  return s;
}
RigidShape RigidShape::plane(const Vec3& normal, double offset) {
  RigidShape s;
  s.type = ShapeType::Plane;
  s.planeNormal = normal;
  s.planeOffset = offset;
  return s;
}

RigidShape RigidShape::convexHull(std::vector<Vec3> points) {
  RigidShape s;
  s.type = ShapeType::ConvexHull;
  s.points = std::move(points);
  return s;
}
RigidShape RigidShape::triangleMesh(std::vector<Vec3> vertices, std::vector<std::array<int32_t, 3>> triangles) {
  RigidShape s;
  s.type = ShapeType::TriangleMesh;
  s.points = std::move(vertices);
  s.triangles = std::move(triangles);
  return s;
}

AnchorDesc AnchorDesc::node(DeformableId deformable, int32_t node, RigidBodyId body) {
  AnchorDesc desc;
  desc.deformable = deformable;
  desc.nodes = {node, -1, -1, -1};
  desc.weights = {1.0, 0.0, 0.0, 0.0};
  desc.nodeCount = 1;
  desc.body = body;
  return desc;
}

struct World::Impl final : bullet::SolverHooks {
  WorldSettings settings;
  bullet::BulletWorld bullet;
  std::vector<std::string> rigidNames;
  std::vector<double> rigidFriction;  // for Tandem's collision detection
  std::vector<std::unique_ptr<geometry::CollisionShape>> rigidShapes;  // shapes with derived data
  std::vector<RigidSolverState> rigid;

  NodeArrays nodes;
  std::vector<DeformableRecord> deformables;
  std::vector<EdgeSpring> springs;
  ConstraintRows rows;
  std::vector<DirectBlock> directBlocks;
  bool directBlocksStale = true;  // rows were added since the blocks were built
  struct ContactImpulse {
    double normal;
    Vec3 friction;
  };
  std::unordered_map<uint64_t, ContactImpulse> previousContacts;  // by feature, for warm starting

  StepReport report;
  double time = 0.0;
  int64_t steps = 0;
  double timeStep = 0.0;  // of the step in progress

  explicit Impl(const WorldSettings& s) : settings(s), bullet(s.gravity) {}

  SolverContext context() {
    return {nodes.velocity, nodes.inverseMass, rigid, timeStep, settings.solver.baumgarte / timeStep};
  }

  // ---- Stage 1: models -----------------------------------------------------------------
  // Unconstrained node velocities: v* = v + h m⁻¹ (f_internal + f_external), gravity included.
  void computeUnconstrainedVelocities(double h) {
    for (Vec3& f : nodes.force) f.setZero();
    addSpringForces(springs, nodes);
    for (size_t i = 0; i < nodes.size(); ++i) {
      if (nodes.inverseMass[i] == 0.0) continue;
      nodes.velocity[i] += h * (settings.gravity + nodes.inverseMass[i] * nodes.force[i]);
    }
    for (const DeformableRecord& body : deformables) dampInternalMotion(body, h);
  }

  // v ← v − min(c h, 1) (v − v̄), v̄ the body's mass-weighted mean velocity over its free nodes.
  void dampInternalMotion(const DeformableRecord& body, double h) {
    if (body.damping == 0.0) return;
    Vec3 momentum = Vec3::Zero();
    double mass = 0.0;
    for (int32_t n = body.firstNode; n < body.firstNode + body.nodeCount; ++n)
      if (nodes.inverseMass[n] > 0) {
        momentum += nodes.velocity[n] / nodes.inverseMass[n];
        mass += 1.0 / nodes.inverseMass[n];
      }
    if (mass == 0.0) return;
    const Vec3 mean = momentum / mass;
    const double fraction = std::min(body.damping * h, 1.0);
    for (int32_t n = body.firstNode; n < body.firstNode + body.nodeCount; ++n)
      if (nodes.inverseMass[n] > 0) nodes.velocity[n] -= fraction * (nodes.velocity[n] - mean);
  }

  // ---- Stage 3: deformable contacts ---------------------------------------------------------
  void detectDeformableContacts(double h) {
    std::vector<CollisionSurface> surfaces;
    for (const DeformableRecord& body : deformables) {
      if (!body.collision.enabled) continue;
      surfaces.push_back({body.firstNode, body.nodeCount, body.surfaceNodes, body.surfaceTriangles,
                          body.surfaceEdges, body.restMesh.positions, body.collision.thickness,
                          body.collision.friction, body.collision.selfCollision});
    }
    std::vector<CollisionRigid> shapes(bullet.rigidBodyCount());
    for (int b = 0; b < bullet.rigidBodyCount(); ++b)
      shapes[b] = {rigidShapes[b].get(),        bullet.position(b),        bullet.orientation(b),
                   bullet.linearVelocity(b),    bullet.angularVelocity(b), rigidFriction[b],
                   bullet.mass(b)};
    std::unordered_set<uint64_t> anchored;
    for (const AnchorRow& row : rows.anchors)
      for (int k = 0; k < 4; ++k)
        if (row.weight[k] != 0.0) anchored.insert(nodeBodyKey(row.node[k], row.body));
    rows.contacts.clear();
    detectContacts(surfaces, nodes, shapes, anchored, h, rows.contacts);
    // Warm start from last step's impulse on the same feature, friction kept in the new plane.
    for (ContactRow& row : rows.contacts) {
      auto previous = previousContacts.find(row.key);
      if (previous == previousContacts.end()) continue;
      row.lambdaNormal = previous->second.normal;
      row.warmFriction = previous->second.friction;
    }
  }

  void rememberContacts() {
    previousContacts.clear();
    for (const ContactRow& row : rows.contacts)
      previousContacts[row.key] = {row.lambdaNormal, row.impulse() - row.lambdaNormal * row.normal};
  }

  // ---- Stage 4: rows ---------------------------------------------------------------------
  void prepareRows(double h) {
    if (directBlocksStale) buildDirectBlocks();
    bullet.loadRigidProperties(rigid);
    for (RigidSolverState& body : rigid) body.impulse = body.angularImpulse = Vec3::Zero();
    rows.prepare(nodes, rigid, settings.gravity, h, settings.solver.baumgarte / h, settings.solver.contactSlop);
    for (DirectBlock& block : directBlocks) {
      block.addContacts(rows, settings.solver.contactSlop);
      block.prepare(rows, nodes, rigid, h);
    }
    report.rowCounts = rows.countRows();
  }

  // One block per group of deformables tied together through dynamic rigid bodies by anchors
  // (union-find over deformables), so that a body shared by several of them is solved with
  // all of them at once.
  void buildDirectBlocks() {
    directBlocks.clear();
    std::vector<int32_t> group(deformables.size());
    for (size_t d = 0; d < group.size(); ++d) group[d] = static_cast<int32_t>(d);
    auto root = [&](int32_t d) {
      while (group[d] != d) d = group[d] = group[group[d]];
      return d;
    };
    std::vector<int32_t> firstDeformableOnBody(bullet.rigidBodyCount(), -1);
    for (const AnchorRow& row : rows.anchors) {
      const auto deformable = static_cast<int32_t>(&deformableOfNode(row.node[0]) - deformables.data());
      if (deformables[deformable].rowSolver == RowSolverKind::Iterative || !bullet.isDynamic(row.body)) continue;
      int32_t& other = firstDeformableOnBody[row.body];
      if (other < 0)
        other = deformable;
      else
        group[root(deformable)] = root(other);
    }
    for (size_t d = 0; d < deformables.size(); ++d) {
      if (root(static_cast<int32_t>(d)) != static_cast<int32_t>(d)) continue;
      std::vector<DirectBlock::NodeRange> ranges;
      bool forced = false, allowed = true;
      for (size_t member = 0; member < deformables.size(); ++member) {
        if (root(static_cast<int32_t>(member)) != static_cast<int32_t>(d)) continue;
        const DeformableRecord& record = deformables[member];
        forced |= record.rowSolver == RowSolverKind::Direct;
        allowed &= record.rowSolver != RowSolverKind::Iterative;
        ranges.push_back({record.firstNode, record.nodeCount});
      }
      if (!allowed) continue;
      DirectBlock block(std::move(ranges));
      block.collectRows(rows);
      if (block.scalarRowCount() == 0 || (!forced && block.scalarRowCount() > kAutoDirectRowLimit)) continue;
      block.claimRows(rows);
      directBlocks.push_back(std::move(block));
    }
    directBlocksStale = false;
  }

  // Bullet's islands know nothing of anchors and of Tandem's contacts, so Tandem decides sleep
  // for bodies that deformables hold or carry (anchored, or pushed by a contact last step): an
  // awake one does not fall asleep on its own (it keeps carrying, and reporting, its load); a
  // sleeping one (put to sleep on purpose) is immovable to Tandem's rows and wakes when any node
  // of such a deformable moves faster than the body's sleeping threshold.
  void manageSleepOfHeldBodies() {
    auto manage = [&](int32_t body, int32_t node) {
      if (!bullet.isDynamic(body)) return;
      if (bullet.isAwake(body)) {
        bullet.restartSleepTimer(body);
        return;
      }
      const DeformableRecord& deformable = deformableOfNode(node);
      const double threshold = bullet.sleepingThreshold(body);
      for (int32_t n = deformable.firstNode; n < deformable.firstNode + deformable.nodeCount; ++n)
        if (nodes.velocity[n].squaredNorm() > threshold * threshold) {
          bullet.wake(body);
          return;
        }
    };
    for (const AnchorRow& row : rows.anchors) manage(row.body, row.node[0]);
    for (const ContactRow& row : rows.contacts)  // last step's
      if (row.body >= 0 && row.lambdaNormal > 0) manage(row.body, row.node[0]);
  }

  const DeformableRecord& deformableOfNode(int32_t node) const {
    auto after = std::upper_bound(deformables.begin(), deformables.end(), node,
                                  [](int32_t n, const DeformableRecord& record) { return n < record.firstNode; });
    return *(after - 1);
  }

  // ---- Stage 5: interleaved solve (called from inside Bullet's solver) -------------------
  void afterSetup() override {
    bullet.loadRigidVelocities(rigid);
    SolverContext ctx = context();
    if (settings.solver.warmStart)
      rows.warmStart(ctx);
    else
      rows.clearImpulses();
    for (const DirectBlock& block : directBlocks) block.clearImpulses(rows);
    bullet.storeRigidVelocities(rigid);
  }

  // Bounded rows by projected Gauss-Seidel first, then each direct block exactly, so that a
  // sweep ends with the bilateral rows satisfied, then the contacts no block holds.
  void afterIteration(int) override {
    bullet.loadRigidVelocities(rigid);
    SolverContext ctx = context();
    SweepStats stats;
    rows.sweep(ctx, settings.solver.friction, stats);
    for (DirectBlock& block : directBlocks) block.solve(rows, ctx, stats);
    // Contacts among deformables couple in crowds (a cloth folded on itself); they are cheap
    // next to a block, so they get more passes than those with rigid bodies.
    if (!directBlocks.empty())
      for (int pass = 0; pass < kFreeContactPasses; ++pass) rows.sweepFreeContacts(ctx, stats, pass > 0);
    report.rmsDeltaLambda.push_back(stats.rows ? std::sqrt(stats.sumSquares / static_cast<double>(stats.rows)) : 0.0);
    bullet.storeRigidVelocities(rigid);
  }

  // ---- Stage 7: integrate ----------------------------------------------------------------
  void integrateNodes(double h) {
    for (size_t i = 0; i < nodes.size(); ++i) nodes.position[i] += h * nodes.velocity[i];
    pushOutOfContacts();
    for (FixedPointRow& row : rows.fixedPoints) row.previousTarget = row.target;
  }

  // A non-finite or absurdly fast state means the step diverged: say which body, and stop.
  // Split-impulse style: a contact found penetrating beyond the slop moves its deformable side
  // out by a fraction of the excess, without touching velocities, so resting contacts do not
  // bounce. Each node moves in proportion to its share of the contact's inverse mass.
  void pushOutOfContacts() {
    constexpr double kFraction = 0.2;
    for (const ContactRow& row : rows.contacts) {
      const double excess = -(row.gap + settings.solver.contactSlop);
      if (excess <= 0) continue;
      double inverseMass = 0.0;
      for (int k = 0; k < 4; ++k) inverseMass += row.coefficient[k] * row.coefficient[k] * nodes.inverseMass[row.node[k]];
      if (inverseMass == 0.0) continue;
      const Vec3 push = (kFraction * excess / inverseMass) * row.normal;
      for (int k = 0; k < 4; ++k) nodes.position[row.node[k]] += row.coefficient[k] * nodes.inverseMass[row.node[k]] * push;
    }
  }

  // Post-stabilisation (Cline and Pai 2003): velocity-level rows leave a drift of order
  // h² v² / L (a cloth corner whipping round at 60 rad/s stretches its edges by half in a step);
  // each block projects its nodes back onto its rows with the step's own factorisation.
  void projectDirectBlocks() {
    for (DirectBlock& block : directBlocks) block.projectPositions(rows, nodes);
  }

  Status checkDiverged() const {
    const double limit = settings.divergenceSpeed;
    auto bad = [limit](const Vec3& x, const Vec3& v) { return !x.allFinite() || !v.allFinite() || v.norm() > limit; };
    const std::string advice =
        ": the simulation diverged (try a smaller time step, more iterations or softer springs)";
    for (const DeformableRecord& body : deformables)
      for (int32_t i = 0; i < body.nodeCount; ++i) {
        const int32_t n = body.firstNode + i;
        if (bad(nodes.position[n], nodes.velocity[n]))
          return Error{"step " + std::to_string(steps) + ": deformable '" + body.name + "' node " + std::to_string(i) +
                       " has a non-finite or faster than " + formatNumber(limit) + " m/s state" + advice};
      }
    for (int b = 0; b < bullet.rigidBodyCount(); ++b)
      if (bad(bullet.position(b), bullet.linearVelocity(b)) || !bullet.angularVelocity(b).allFinite())
        return Error{"step " + std::to_string(steps) + ": rigid body '" + rigidNames[b] +
                     "' has a non-finite or faster than " + formatNumber(limit) + " m/s state" + advice};
    return {};
  }

  // ---- Lookups ---------------------------------------------------------------------------
  bool validRigid(RigidBodyId id) const { return id.index >= 0 && id.index < bullet.rigidBodyCount(); }
  bool validDeformable(DeformableId id) const {
    return id.index >= 0 && id.index < static_cast<int32_t>(deformables.size());
  }
  Result<int32_t> globalNode(DeformableId body, int32_t node, const char* who) const {
    if (!validDeformable(body)) return Error{std::string(who) + ": no deformable body with index " +
                                             std::to_string(body.index)};
    const DeformableRecord& record = deformables[body.index];
    if (node < 0 || node >= record.nodeCount)
      return Error{std::string(who) + ": node " + std::to_string(node) + " is out of range for deformable '" +
                   record.name + "' (" + std::to_string(record.nodeCount) + " nodes)"};
    return record.firstNode + node;
  }
};

World::World() : m_impl(std::make_unique<Impl>(WorldSettings{})) {}
World::~World() = default;

Status World::setSettings(const WorldSettings& settings) {
  if (Status s = validateSettings(settings); !s) return s;
  m_impl->settings = settings;
  m_impl->bullet.setGravity(settings.gravity);
  return {};
}
const WorldSettings& World::settings() const { return m_impl->settings; }

// ---- Rigid bodies -----------------------------------------------------------------------

Result<RigidBodyId> World::addRigidBody(const RigidBodyDesc& desc) {
  const std::string who = "rigid body '" + desc.name + "'";
  if (Status s = validateShape(desc.shape, who); !s) return Error{s.message()};
  if (desc.motion == MotionType::Dynamic && !(std::isfinite(desc.mass) && desc.mass > 0))
    return Error{who + ": mass must be positive and finite for a dynamic body, got " + formatNumber(desc.mass) + " kg"};
  if ((desc.shape.type == ShapeType::Plane || desc.shape.type == ShapeType::TriangleMesh) &&
      desc.motion != MotionType::Static)
    return Error{who + ": a plane or a triangle mesh can only be static"};
  if (!desc.position.allFinite()) return Error{who + ": position is not finite"};
  if (!desc.orientation.coeffs().allFinite() || desc.orientation.norm() < 1e-9)
    return Error{who + ": orientation must be a finite non-zero quaternion"};
  if (!desc.linearVelocity.allFinite() || !desc.angularVelocity.allFinite())
    return Error{who + ": velocity is not finite"};
  if (!(desc.friction >= 0 && std::isfinite(desc.friction)))
    return Error{who + ": friction must be >= 0, got " + formatNumber(desc.friction)};
  if (!(desc.restitution >= 0 && desc.restitution <= 1))
    return Error{who + ": restitution must be in [0, 1], got " + formatNumber(desc.restitution)};
  const int index = m_impl->bullet.addRigidBody(desc);
  m_impl->rigidNames.push_back(desc.name);
  m_impl->rigidFriction.push_back(desc.friction);
  auto shape = std::make_unique<geometry::CollisionShape>();
  shape->shape = desc.shape;
  if (desc.shape.type == ShapeType::ConvexHull) shape->planes = bullet::convexHullPlanes(desc.shape.points);
  if (desc.shape.type == ShapeType::TriangleMesh) shape->grid.build(desc.shape.points, desc.shape.triangles);
  m_impl->rigidShapes.push_back(std::move(shape));
  m_impl->rigid.emplace_back();
  return RigidBodyId{index};
}

Result<JointId> World::addHinge(const HingeDesc& desc) {
  if (!m_impl->validRigid(desc.bodyA)) return Error{"hinge: body A does not exist"};
  if (desc.bodyB && !m_impl->validRigid(*desc.bodyB)) return Error{"hinge: body B does not exist"};
  if (desc.bodyB && *desc.bodyB == desc.bodyA) return Error{"hinge: body A and body B are the same body"};
  if (!desc.pivot.allFinite()) return Error{"hinge: pivot is not finite"};
  if (!desc.axis.allFinite() || desc.axis.norm() < 1e-9) return Error{"hinge: axis must be a finite non-zero vector"};
  return JointId{m_impl->bullet.addHinge(desc)};
}

int World::rigidBodyCount() const { return m_impl->bullet.rigidBodyCount(); }
std::optional<RigidBodyId> World::findRigidBody(std::string_view name) const {
  for (size_t i = 0; i < m_impl->rigidNames.size(); ++i)
    if (m_impl->rigidNames[i] == name) return RigidBodyId{static_cast<int32_t>(i)};
  return std::nullopt;
}
const std::string& World::rigidName(RigidBodyId body) const { return m_impl->rigidNames.at(body.index); }
Vec3 World::rigidPosition(RigidBodyId body) const { return m_impl->bullet.position(body.index); }
Quat World::rigidOrientation(RigidBodyId body) const { return m_impl->bullet.orientation(body.index); }
Vec3 World::rigidLinearVelocity(RigidBodyId body) const { return m_impl->bullet.linearVelocity(body.index); }
Vec3 World::rigidAngularVelocity(RigidBodyId body) const { return m_impl->bullet.angularVelocity(body.index); }
double World::rigidMass(RigidBodyId body) const { return m_impl->bullet.mass(body.index); }
bool World::rigidIsAwake(RigidBodyId body) const { return m_impl->bullet.isAwake(body.index); }
void World::putRigidToSleep(RigidBodyId body) { m_impl->bullet.putToSleep(body.index); }
void World::setRigidCanSleep(RigidBodyId body, bool canSleep) { m_impl->bullet.setCanSleep(body.index, canSleep); }

Status World::setKinematicTarget(RigidBodyId body, const Vec3& position, const Quat& orientation) {
  if (!m_impl->validRigid(body)) return Error{"kinematic target: no rigid body with index " + std::to_string(body.index)};
  if (!position.allFinite() || !orientation.coeffs().allFinite() || orientation.norm() < 1e-9)
    return Error{"kinematic target: pose is not finite"};
  m_impl->bullet.setKinematicTarget(body.index, position, orientation);
  return {};
}

double World::rigidContactImpulse(RigidBodyId a, RigidBodyId b) const {
  return m_impl->bullet.contactImpulse(a.index, b.index);
}
Vec3 World::deformableImpulseOnRigid(RigidBodyId body) const { return m_impl->rigid[body.index].impulse; }
Vec3 World::deformableAngularImpulseOnRigid(RigidBodyId body) const {
  return m_impl->rigid[body.index].angularImpulse;
}
Vec3 World::deformableForceOnRigid(RigidBodyId body) const {
  return m_impl->timeStep > 0 ? Vec3(m_impl->rigid[body.index].impulse / m_impl->timeStep) : Vec3::Zero();
}
Vec3 World::deformableTorqueOnRigid(RigidBodyId body) const {
  return m_impl->timeStep > 0 ? Vec3(m_impl->rigid[body.index].angularImpulse / m_impl->timeStep) : Vec3::Zero();
}

// ---- Deformable bodies ------------------------------------------------------------------

Result<DeformableId> World::addDeformable(const DeformableDesc& desc) {
  const std::string who = "deformable '" + desc.name + "'";
  if (Status s = validateMesh(desc.mesh); !s) return Error{who + ": " + s.message()};
  const MassSpringSettings& springs = desc.springs;
  if (!(springs.stiffness >= 0 && std::isfinite(springs.stiffness)) ||
      !(springs.damping >= 0 && std::isfinite(springs.damping)))
    return Error{who + ": spring stiffness and damping must be >= 0 and finite"};
  if (desc.inextensibility.enabled && !isPositive(desc.inextensibility.maxForce))
    return Error{who + ": inextensibility max force must be positive, got " + formatNumber(desc.inextensibility.maxForce)};
  if (desc.bending.enabled && !isPositive(desc.bending.maxForce))
    return Error{who + ": bending max force must be positive, got " + formatNumber(desc.bending.maxForce)};
  if (desc.bending.enabled && (!isPositive(desc.bending.frequency) || !(desc.bending.dampingRatio >= 0)))
    return Error{who + ": bending frequency must be positive and its damping ratio >= 0"};
  if (!(std::isfinite(desc.damping) && desc.damping >= 0))
    return Error{who + ": damping must be >= 0 per second and finite, got " + formatNumber(desc.damping)};
  if (!(std::isfinite(desc.collision.thickness) && desc.collision.thickness >= 0))
    return Error{who + ": collision thickness must be >= 0 m and finite, got " + formatNumber(desc.collision.thickness)};
  if (!(std::isfinite(desc.collision.friction) && desc.collision.friction >= 0))
    return Error{who + ": friction must be >= 0 and finite, got " + formatNumber(desc.collision.friction)};

  Impl& w = *m_impl;
  const DeformableMesh& mesh = desc.mesh;
  const int32_t first = static_cast<int32_t>(w.nodes.size());
  for (int32_t i = 0; i < mesh.nodeCount(); ++i) {
    w.nodes.position.push_back(mesh.positions[i]);
    w.nodes.velocity.push_back(Vec3::Zero());
    w.nodes.force.push_back(Vec3::Zero());
    w.nodes.inverseMass.push_back(1.0 / mesh.masses[i]);
  }
  auto addEdge = [&](const std::array<int32_t, 2>& e, bool inextensible) {
    const double restLength = (mesh.positions[e[1]] - mesh.positions[e[0]]).norm();
    if (springs.stiffness > 0 || springs.damping > 0)
      w.springs.push_back({first + e[0], first + e[1], restLength, springs.stiffness, springs.damping});
    if (!inextensible) return;
    InextensibilityRow row;
    row.node = {first + e[0], first + e[1]};
    row.restLength = restLength;
    const auto bounds = inextensibilityForceBounds(desc.inextensibility.mode, desc.inextensibility.maxForce);
    row.lambdaMin = bounds[0];
    row.lambdaMax = bounds[1];
    w.rows.inextensibility.push_back(row);
  };
  for (const auto& e : mesh.edges) addEdge(e, desc.inextensibility.enabled);
  for (const auto& e : mesh.shearEdges) addEdge(e, desc.inextensibility.enabled && desc.inextensibility.shearEdges);
  if (desc.bending.enabled) {
    for (const EdgeHinge& hinge : findEdgeHinges(mesh.triangles)) {
      BendingRow row;
      row.node = {first + hinge.i, first + hinge.j, first + hinge.left, first + hinge.right};
      const auto& x = mesh.positions;
      row.restDot = bendingDot(x[hinge.i], x[hinge.j], x[hinge.left], x[hinge.right]);
      row.restEdgeLength = (x[hinge.j] - x[hinge.i]).norm();
      row.maxForce = desc.bending.maxForce;
      row.frequency = desc.bending.frequency;
      row.dampingRatio = desc.bending.dampingRatio;
      w.rows.bending.push_back(row);
    }
  }
  DeformableRecord record{desc.name, first, mesh.nodeCount(), mesh, desc.rowSolver, desc.collision, desc.damping, {},
                          {}, {}};
  // The collision surface: its triangles, and the nodes on them (every node when it has none).
  std::vector<bool> onSurface(mesh.nodeCount(), mesh.triangles.empty());
  for (const auto& t : mesh.triangles) {
    record.surfaceTriangles.push_back({first + t[0], first + t[1], first + t[2]});
    for (int32_t n : t) onSurface[n] = true;
  }
  for (int32_t n = 0; n < mesh.nodeCount(); ++n)
    if (onSurface[n]) record.surfaceNodes.push_back(first + n);
  // Its edges: the triangles' (each once), or a rope's.
  std::set<std::pair<int32_t, int32_t>> edges;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) edges.insert({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
  if (mesh.triangles.empty())
    for (const auto& e : mesh.edges) edges.insert({std::min(e[0], e[1]), std::max(e[0], e[1])});
  for (const auto& [i, j] : edges) record.surfaceEdges.push_back({first + i, first + j});
  w.deformables.push_back(std::move(record));
  w.directBlocksStale = true;
  return DeformableId{static_cast<int32_t>(w.deformables.size()) - 1};
}

int World::deformableCount() const { return static_cast<int>(m_impl->deformables.size()); }
std::optional<DeformableId> World::findDeformable(std::string_view name) const {
  for (size_t i = 0; i < m_impl->deformables.size(); ++i)
    if (m_impl->deformables[i].name == name) return DeformableId{static_cast<int32_t>(i)};
  return std::nullopt;
}
const std::string& World::deformableName(DeformableId body) const { return m_impl->deformables.at(body.index).name; }

std::span<const Vec3> World::nodePositions(DeformableId body) const {
  const DeformableRecord& r = m_impl->deformables.at(body.index);
  return std::span<const Vec3>(m_impl->nodes.position).subspan(r.firstNode, r.nodeCount);
}
std::span<const Vec3> World::nodeVelocities(DeformableId body) const {
  const DeformableRecord& r = m_impl->deformables.at(body.index);
  return std::span<const Vec3>(m_impl->nodes.velocity).subspan(r.firstNode, r.nodeCount);
}
std::span<const double> World::nodeInverseMasses(DeformableId body) const {
  const DeformableRecord& r = m_impl->deformables.at(body.index);
  return std::span<const double>(m_impl->nodes.inverseMass).subspan(r.firstNode, r.nodeCount);
}
const DeformableMesh& World::restMesh(DeformableId body) const { return m_impl->deformables.at(body.index).restMesh; }

Status World::setNodeVelocity(DeformableId body, int32_t node, const Vec3& velocity) {
  Result<int32_t> n = m_impl->globalNode(body, node, "set node velocity");
  if (!n) return n.status();
  if (!velocity.allFinite()) return Error{"set node velocity: velocity is not finite"};
  m_impl->nodes.velocity[*n] = velocity;
  return {};
}

Status World::fixNode(DeformableId body, int32_t node) {
  Result<int32_t> n = m_impl->globalNode(body, node, "fix node");
  if (!n) return n.status();
  m_impl->nodes.inverseMass[*n] = 0.0;
  m_impl->nodes.velocity[*n].setZero();
  return {};
}

// ---- Constraints ------------------------------------------------------------------------

Result<FixedPointId> World::addFixedPoint(DeformableId body, int32_t node, const Vec3& target, double maxForce) {
  Result<int32_t> n = m_impl->globalNode(body, node, "fixed point");
  if (!n) return Error{n.message()};
  if (!target.allFinite()) return Error{"fixed point: target is not finite"};
  if (!isPositive(maxForce)) return Error{"fixed point: max force must be positive, got " + formatNumber(maxForce)};
  FixedPointRow row;
  row.node = *n;
  row.target = row.previousTarget = target;
  row.maxForce = maxForce;
  m_impl->rows.fixedPoints.push_back(row);
  m_impl->directBlocksStale = true;
  return FixedPointId{static_cast<int32_t>(m_impl->rows.fixedPoints.size()) - 1};
}

Status World::setFixedPointTarget(FixedPointId id, const Vec3& target) {
  if (id.index < 0 || id.index >= static_cast<int32_t>(m_impl->rows.fixedPoints.size()))
    return Error{"fixed point target: no fixed point with index " + std::to_string(id.index)};
  if (!target.allFinite()) return Error{"fixed point target: target is not finite"};
  m_impl->rows.fixedPoints[id.index].target = target;
  return {};
}

Vec3 World::fixedPointImpulse(FixedPointId id) const { return m_impl->rows.fixedPoints.at(id.index).lambda; }

Result<AnchorId> World::addAnchor(const AnchorDesc& desc) {
  Impl& w = *m_impl;
  if (!w.validRigid(desc.body)) return Error{"anchor: no rigid body with index " + std::to_string(desc.body.index)};
  if (desc.nodeCount < 1 || desc.nodeCount > 4)
    return Error{"anchor: node count must be 1 to 4, got " + std::to_string(desc.nodeCount)};
  if (!isPositive(desc.maxForce)) return Error{"anchor: max force must be positive, got " + formatNumber(desc.maxForce)};
  AnchorRow row;
  row.body = desc.body.index;
  row.maxForce = desc.maxForce;
  double weightSum = 0.0;
  for (int k = 0; k < desc.nodeCount; ++k) {
    Result<int32_t> n = w.globalNode(desc.deformable, desc.nodes[k], "anchor");
    if (!n) return Error{n.message()};
    if (!std::isfinite(desc.weights[k])) return Error{"anchor: weights must be finite"};
    row.node[k] = *n;
    row.weight[k] = desc.weights[k];
    weightSum += desc.weights[k];
  }
  if (std::abs(weightSum - 1.0) > 1e-6) return Error{"anchor: weights must sum to 1, got " + formatNumber(weightSum)};
  for (int k = desc.nodeCount; k < 4; ++k) {
    row.node[k] = row.node[0];
    row.weight[k] = 0.0;
  }
  const Vec3 com = w.bullet.position(row.body);
  const Quat orientation = w.bullet.orientation(row.body);
  if (desc.localPoint) {
    if (!desc.localPoint->allFinite()) return Error{"anchor: local point is not finite"};
    row.localPoint = *desc.localPoint;
  } else {
    row.localPoint = orientation.conjugate() * (row.deformablePoint(w.nodes.position) - com);
  }
  w.rows.anchors.push_back(row);
  w.directBlocksStale = true;
  return AnchorId{static_cast<int32_t>(w.rows.anchors.size()) - 1};
}

AnchorState World::anchorState(AnchorId id) const {
  const AnchorRow& row = m_impl->rows.anchors.at(id.index);
  AnchorState state;
  state.impulse = row.lambda;
  state.worldPointOnBody = m_impl->bullet.position(row.body) + m_impl->bullet.orientation(row.body) * row.localPoint;
  state.worldPointOnDeformable = row.deformablePoint(m_impl->nodes.position);
  return state;
}

std::vector<ContactReport> World::contacts() const {
  const Impl& w = *m_impl;
  std::vector<ContactReport> reports;
  reports.reserve(w.rows.contacts.size());
  for (const ContactRow& row : w.rows.contacts) {
    ContactReport report;
    const DeformableRecord& body = w.deformableOfNode(row.node[0]);
    report.deformable = DeformableId{static_cast<int32_t>(&body - w.deformables.data())};
    if (row.body >= 0) {
      report.rigid = RigidBodyId{row.body};
    } else {
      const DeformableRecord& other = w.deformableOfNode(row.node[1]);
      report.other = DeformableId{static_cast<int32_t>(&other - w.deformables.data())};
    }
    for (int k = 0; k < 4; ++k)
      if (row.coefficient[k] > 0) report.point += row.coefficient[k] * w.nodes.position[row.node[k]];
    report.normal = row.normal;
    report.gap = row.gap;
    report.normalImpulse = row.lambdaNormal;
    report.frictionImpulse = row.impulse() - row.lambdaNormal * row.normal;
    reports.push_back(report);
  }
  return reports;
}

// ---- The step ---------------------------------------------------------------------------

Status World::step(double h) {
  if (!(std::isfinite(h) && h > 0 && h <= 1.0))
    return Error{"step: time step must be in (0, 1] seconds, got " + formatNumber(h)};
  Impl& w = *m_impl;
  w.timeStep = h;
  StepReport& report = w.report;
  report.rmsDeltaLambda.clear();
  StageClock clock;
  auto timed = [&](Stage stage) { report.stageSeconds[static_cast<size_t>(stage)] = clock.lap(); };

  w.computeUnconstrainedVelocities(h);  // 1. deformable models: unconstrained node velocities
  timed(Stage::Models);
  w.manageSleepOfHeldBodies();          // 2. Bullet: gravity and external forces on rigid bodies
  w.bullet.predictRigidMotion(h);
  timed(Stage::RigidPrediction);
  w.bullet.detectCollisions(h);         // 3. Bullet: rigid-rigid contacts; Tandem: deformable ones
  w.detectDeformableContacts(h);
  timed(Stage::CollisionDetection);
  w.prepareRows(h);                     // 4. Tandem's rows: Jacobians, effective masses, biases
  timed(Stage::Rows);
  w.bullet.solve(h, w.settings.solver.iterations, w);  // 5+6. K × [Bullet iteration, Tandem sweep]
  timed(Stage::Solve);
  w.rememberContacts();
  w.integrateNodes(h);                  // 7. symplectic Euler for nodes; Bullet for rigid bodies;
  w.bullet.integrate(h);                //    then the direct blocks' rows projected back by position
  w.projectDirectBlocks();
  timed(Stage::Integrate);

  report.bulletContactManifolds = w.bullet.manifoldCount();  // 8. report
  report.bulletJoints = w.bullet.jointCount();
  report.totalSeconds = 0.0;
  for (double seconds : report.stageSeconds) report.totalSeconds += seconds;
  w.time += h;
  ++w.steps;
  return w.checkDiverged();
}

const StepReport& World::lastReport() const { return m_impl->report; }
double World::time() const { return m_impl->time; }
int64_t World::stepCount() const { return m_impl->steps; }

Vec3 World::totalLinearMomentum() const {
  Vec3 momentum = Vec3::Zero();
  const NodeArrays& nodes = m_impl->nodes;
  for (size_t i = 0; i < nodes.size(); ++i)
    if (nodes.inverseMass[i] > 0) momentum += nodes.velocity[i] / nodes.inverseMass[i];
  for (int b = 0; b < m_impl->bullet.rigidBodyCount(); ++b)
    momentum += m_impl->bullet.mass(b) * m_impl->bullet.linearVelocity(b);
  return momentum;
}

}  // namespace tandem
