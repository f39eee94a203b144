// World::Impl: the world's state and the stages of its step (src/world.cpp runs them,
// src/world_build.cpp fills the state). Internal.
#pragma once

#include <tandem/world.h>

#include "bullet/bullet_world.h"
#include "collision/contact_detection.h"
#include "collision/contact_motion.h"
#include "collision/impact_zones.h"
#include "format.h"
#include "id_slots.h"
#include "models/implicit_solve.h"
#include "models/mass_spring.h"
#include "models/position_based.h"
#include "solver/constraint_rows.h"
#include "solver/direct_block.h"
#include "solver/strain_limiting.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <unordered_map>
#include <unordered_set>

namespace tandem {

inline bool isPositive(double value) { return value > 0 && !std::isnan(value); }  // +inf allowed

// Passes over the contacts no direct block holds, after the blocks, in each iteration.
inline constexpr int kFreeContactPasses = 4;

struct DeformableRecord {
  std::string name;
  int32_t firstNode = 0;
  int32_t nodeCount = 0;
  DeformableMesh restMesh;
  RowSolverKind rowSolver = RowSolverKind::Auto;
  CollisionSettings collision;
  ParadigmSettings paradigm;
  double damping = 0.0;
  std::vector<int32_t> surfaceNodes;                       // global indices
  std::vector<std::array<int32_t, 3>> surfaceTriangles;    // global indices
  std::vector<std::array<int32_t, 2>> surfaceEdges;        // global indices
  std::vector<std::array<int32_t, 2>> paradigmEdges;       // local: edges and shear edges
  bool implicitStep = false;  // FEM, or mass-spring with implicit springs: stepped by `implicit`
  ImplicitBody implicit;
  Supports supports;  // surfaces its nodes rest on, from last step (models/supports.h)
  bool removed = false;  // removed: its nodes stay in the arrays, inert (src/world_edit.cpp)
};

// Last step's impulse of a contact, by feature, for the next step's warm start.
struct ContactImpulse {
  double normal;
  Vec3 friction;
  bool releasedFromBlock;
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

struct World::Impl final : bullet::SolverHooks {
  WorldSettings settings;
  bullet::BulletWorld bullet;
  std::vector<std::string> rigidNames;
  std::vector<double> rigidFriction;  // for Tandem's collision detection
  std::vector<std::unique_ptr<geometry::CollisionShape>> rigidShapes;  // shapes with derived data
  std::vector<RigidSolverState> rigid;
  std::vector<uint32_t> rigidGroup, rigidMask;  // collision filter per rigid body (0, 0 once removed)

  // The slots behind the ids (id_slots.h). A rigid body's and a joint's slot is its index in
  // Bullet's arrays; a deformable's is its record's; anchors and fixed points are stored densely
  // in `rows` and grabs in place (a grab's slot is its row).
  IdSlots rigidSlots{"rigid body"}, deformableSlots{"deformable"}, jointSlots{"joint"}, anchorSlots{"anchor"},
      fixedPointSlots{"fixed point"}, grabSlots{"grab"};
  mutable std::string lookupError;  // the first bad id a query met (World::takeLookupError)
  uint64_t rigidStructureVersion = 0;  // changes as rigid bodies and joints come and go (snapshots check it)
  // This world among all made in the process: a snapshot names the world it came from by this, not
  // by address (a world made after another is gone may sit at the same address).
  const uint64_t serial = nextSerial();
  static uint64_t nextSerial();

  NodeArrays nodes;
  std::vector<DeformableRecord> deformables;
  std::vector<EdgeSpring> springs;
  ConstraintRows rows;
  std::vector<DirectBlock> directBlocks;
  bool directBlocksStale = true;  // rows were added since the blocks were built
  std::vector<char> unprojected;  // per deformable: in a block that could not project this step
  std::vector<Vec3> stepStartPositions;  // node positions before this step moved them
  std::vector<Vec3> stepStartVelocities;  // and their velocities before the models changed them
  std::vector<Vec3> modelVelocityChange;  // per node: what the models add over the step, per substep
  std::vector<RigidPose> stepStartPoses;
  std::vector<CollisionRigid> substepShapes;  // rigid shapes in their pose at a substep's start  // rigid bodies before this step moved them
  struct TargetPath {
    Vec3 from, to;  // where a moving target is at the step's start and end
  };
  std::vector<TargetPath> fixedPointPaths, grabPaths;
  std::unordered_map<uint64_t, ContactImpulse> previousContacts;  // by feature, for warm starting

  StepReport report;
  double time = 0.0;
  int64_t steps = 0;
  double timeStep = 0.0;  // of the step in progress
  double substepLength = 0.0;  // h / n: what the rows are prepared and solved over

  explicit Impl(const WorldSettings& s) : settings(s), bullet(s.gravity) {}

  SolverContext context() {
    return {nodes.velocity, nodes.inverseMass, rigid, substepLength, settings.solver.baumgarte / substepLength};
  }

  // ---- Substeps ---------------------------------------------------------------------------
  // The step's start: positions and poses the substeps' contact gaps are measured from, the
  // moving targets' paths, and the impulse sums the report gives cleared.
  void beginStep() {
    stepStartPositions = nodes.position;  // also the impact zones' start
    for (FixedPointRow& row : rows.fixedPoints) row.stepImpulse.setZero();
    for (GrabRow& row : rows.grabs) row.stepImpulse.setZero();
    for (AnchorRow& row : rows.anchors) row.stepImpulse.setZero();
    for (RigidSolverState& body : rigid) body.impulse = body.angularImpulse = Vec3::Zero();
    bullet.beginStep();
    if (settings.solver.substeps == 1) return;  // what only the substeps read
    stepStartVelocities = nodes.velocity;
    stepStartPoses.resize(static_cast<size_t>(bullet.rigidBodyCount()));
    for (int b = 0; b < bullet.rigidBodyCount(); ++b) stepStartPoses[b] = {bullet.position(b), bullet.orientation(b)};
    fixedPointPaths.clear();
    for (const FixedPointRow& row : rows.fixedPoints) fixedPointPaths.push_back({row.previousTarget, row.target});
    grabPaths.clear();
    for (const GrabRow& row : rows.grabs) grabPaths.push_back({row.previousTarget, row.target});
  }

  // The models ran once over the whole step (v ← v*); with n substeps the nodes go back to their
  // start velocity and receive (v* − v) / n at the start of each substep, as gravity would.
  void spreadModelVelocities(int substeps) {
    if (substeps == 1) return;
    modelVelocityChange.resize(nodes.size());
    for (size_t i = 0; i < nodes.size(); ++i) {
      modelVelocityChange[i] = (nodes.velocity[i] - stepStartVelocities[i]) / substeps;
      nodes.velocity[i] = stepStartVelocities[i];
    }
  }

  // Substep s of n: the models' share of the velocity change, the moving targets at their
  // substep's ends, and the contacts moved on (collision/contact_motion.h).
  void beginSubstep(int substep, int substeps) {
    if (substeps == 1) return;
    for (size_t i = 0; i < nodes.size(); ++i) nodes.velocity[i] += modelVelocityChange[i];
    const double from = static_cast<double>(substep) / substeps, to = static_cast<double>(substep + 1) / substeps;
    for (size_t r = 0; r < rows.fixedPoints.size(); ++r) {
      const TargetPath& path = fixedPointPaths[r];
      rows.fixedPoints[r].previousTarget = path.from + from * (path.to - path.from);
      rows.fixedPoints[r].target = path.from + to * (path.to - path.from);
    }
    for (size_t r = 0; r < rows.grabs.size(); ++r) {
      const TargetPath& path = grabPaths[r];
      rows.grabs[r].previousTarget = path.from + from * (path.to - path.from);
      rows.grabs[r].target = path.from + to * (path.to - path.from);
    }
    if (substep == 0) return;
    substepShapes.resize(static_cast<size_t>(bullet.rigidBodyCount()));
    for (int b = 0; b < bullet.rigidBodyCount(); ++b)
      substepShapes[b] = {rigidShapes[b].get(), bullet.position(b), bullet.orientation(b), Vec3::Zero(), Vec3::Zero(), 0.0, 0.0};
    moveContactsOn(rows.contacts, nodes.position, stepStartPositions, substepShapes, stepStartPoses,
                   [&](int32_t node) { return deformableOfNode(node).collision.thickness; });
  }

  // After a substep's solve: its impulses added to the step's sums; after the last, the
  // contacts remembered for the next step's warm start and models.
  void endSubstepSolve(bool lastSubstep) {
    for (FixedPointRow& row : rows.fixedPoints) row.stepImpulse += row.lambda;
    for (AnchorRow& row : rows.anchors) row.stepImpulse += row.lambda;
    for (GrabRow& row : rows.grabs)
      if (row.active) row.stepImpulse += row.lambda;
    for (ContactRow& row : rows.contacts) {
      row.stepNormalImpulse += row.lambdaNormal;
      row.stepFrictionImpulse += row.impulse() - row.lambdaNormal * row.normal;
    }
    if (lastSubstep) rememberContacts();
  }

  // ---- Stage 1: models -----------------------------------------------------------------
  // Unconstrained node velocities: v* = v + h m⁻¹ (f_internal + f_external), gravity included.
  void computeUnconstrainedVelocities(double h) {
    for (Vec3& f : nodes.force) f.setZero();
    addSpringForces(springs, nodes);
    for (DeformableRecord& body : deformables) {
      body.supports.clearHolds();
      if (body.implicitStep) {
        solveImplicitVelocities(body.implicit, body.supports, nodes, settings.gravity, h);  // gravity included
      } else {
        for (int32_t i = body.firstNode; i < body.firstNode + body.nodeCount; ++i)
          if (nodes.inverseMass[i] != 0.0)
            nodes.velocity[i] += h * (settings.gravity + nodes.inverseMass[i] * nodes.force[i]);
      }
      dampInternalMotion(body, h);
      applyParadigm(body, h);
    }
  }

  // Position-based paradigms turn goals into velocities (mass-spring and FEM bodies are done:
  // their forces are in v* already), after holding their supported nodes (models/supports.h).
  void applyParadigm(DeformableRecord& body, double h) {
    if (body.paradigm.type == ParadigmType::MassSpring || body.paradigm.type == ParadigmType::CorotationalFem) return;
    PositionBasedBody model{body.firstNode,           body.nodeCount,
                            body.restMesh.positions,  body.paradigmEdges,
                            body.restMesh.tetrahedra, body.paradigm.stiffness,
                            body.paradigm.damping,    body.paradigm.iterations,
                            {},                       {},
                            {}};
    // PBD projects its supports as constraints among its own (weighting held nodes in the
    // projections, as shape matching's fit does, blew a jelly resting on a box up); what they
    // pushed is the supports' impulse, (1 − γ) m Δ / h per node.
    if (body.paradigm.type == ParadigmType::PositionBased) {
      std::vector<SupportPlane> planes;
      for (int32_t i = 0; i < body.nodeCount; ++i) {
        const int32_t n = body.firstNode + i;
        if (body.supports.normal[i].isZero() || nodes.inverseMass[n] == 0.0) continue;
        const Vec3& normal = body.supports.normal[i];
        planes.push_back({i, normal, normal.dot(nodes.position[n]) + h * body.supports.targetSpeed(i, h)});
      }
      std::vector<double> push(body.nodeCount, 0.0);
      model.supports = planes;
      model.supportPush = push;
      applyPositionBasedDynamics(model, nodes, h);
      for (const SupportPlane& plane : planes)
        if (push[plane.node] > 0)
          body.supports.recordHold(plane.node, (1.0 - body.paradigm.damping) * push[plane.node] /
                                                   (nodes.inverseMass[body.firstNode + plane.node] * h));
      return;
    }
    constexpr double kHeldWeight = 1000.0;  // how much heavier a held node counts in the fit
    const std::span<const double> inverseMass(nodes.inverseMass.data() + body.firstNode, body.nodeCount);
    body.supports.hold(std::span<Vec3>(nodes.velocity.data() + body.firstNode, body.nodeCount), inverseMass, h);
    std::vector<double> weights(inverseMass.begin(), inverseMass.end());
    double heldMass = 0.0;
    for (int32_t i = 0; i < body.nodeCount; ++i) {
      if (body.supports.holdBody[i] < 0) continue;
      weights[i] /= kHeldWeight;
      heldMass += 1.0 / inverseMass[i];
    }
    model.weightInverseMass = weights;
    const Vec3 before = bodyMomentum(body);
    applyShapeMatching(model, nodes, h);
    // Weighted towards the held nodes, the fit moves the body's mass centre: that momentum came
    // through the held nodes from their supports, so it is theirs, by mass.
    if (heldMass == 0.0) return;
    const Vec3 transmitted = bodyMomentum(body) - before;
    for (int32_t i = 0; i < body.nodeCount; ++i)
      if (body.supports.holdBody[i] >= 0) body.supports.holdImpulse[i] += transmitted / (inverseMass[i] * heldMass);
  }

  Vec3 bodyMomentum(const DeformableRecord& body) const {
    Vec3 momentum = Vec3::Zero();
    for (int32_t i = body.firstNode; i < body.firstNode + body.nodeCount; ++i)
      if (nodes.inverseMass[i] > 0) momentum += nodes.velocity[i] / nodes.inverseMass[i];
    return momentum;
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
  std::vector<CollisionSurface> collisionSurfaces() const {
    std::vector<CollisionSurface> surfaces;
    for (const DeformableRecord& body : deformables) {
      if (!body.collision.enabled) continue;
      surfaces.push_back({body.firstNode, body.nodeCount, body.surfaceNodes, body.surfaceTriangles,
                          body.surfaceEdges, body.restMesh.positions, body.collision.thickness,
                          body.collision.friction, body.collision.selfCollision, body.collision.group,
                          body.collision.mask});
    }
    return surfaces;
  }

  void detectDeformableContacts(double h) {
    const std::vector<CollisionSurface> surfaces = collisionSurfaces();
    std::vector<CollisionRigid> shapes(bullet.rigidBodyCount());
    for (int b = 0; b < bullet.rigidBodyCount(); ++b)
      shapes[b] = {rigidShapes[b].get(),        bullet.position(b),        bullet.orientation(b),
                   bullet.linearVelocity(b),    bullet.angularVelocity(b), rigidFriction[b],
                   bullet.mass(b),              rigidGroup[b],             rigidMask[b]};
    std::unordered_set<uint64_t> anchored;
    for (const AnchorRow& row : rows.anchors)
      for (int k = 0; k < 4; ++k)
        if (row.weight[k] != 0.0) anchored.insert(nodeBodyKey(row.node[k], row.body));
    rows.contacts.clear();
    detectContacts(surfaces, nodes, shapes, anchored, h, rows.contacts);
    for (ContactRow& row : rows.contacts) {
      row.startGap = row.gap;
      row.startOffset = row.offset;
    }
    // Warm start from last step's impulse on the same feature, friction kept in the new plane.
    for (ContactRow& row : rows.contacts) {
      auto previous = previousContacts.find(row.key);
      if (previous == previousContacts.end()) continue;
      row.lambdaNormal = previous->second.normal;
      row.warmFriction = previous->second.friction;
      row.releasedLastStep = previous->second.releasedFromBlock;
    }
    rows.colourContacts(nodes.size(), static_cast<size_t>(bullet.rigidBodyCount()),
                        [&](int32_t body) { return bullet.isDynamic(body); });
  }

  void rememberContacts() {
    previousContacts.clear();
    for (const ContactRow& row : rows.contacts)
      previousContacts[row.key] = {row.lambdaNormal, row.impulse() - row.lambdaNormal * row.normal, row.releasedFromBlock};
    addHoldImpulsesToSupports();
    rememberSupports();
  }

  // The supports carried their holds' impulses (models/supports.h): on the report of the
  // bodies' impulse from deformables.
  void addHoldImpulsesToSupports() {
    for (const DeformableRecord& body : deformables)
      for (size_t i = 0; i < body.supports.holdBody.size(); ++i)
        if (body.supports.holdBody[i] >= 0) rigid[body.supports.holdBody[i]].impulse -= body.supports.holdImpulse[i];
  }

  // The static and kinematic surfaces the nodes touched or neared, with the gap left at the
  // step's end, for the next step's models (models/supports.h).
  void rememberSupports() {
    for (DeformableRecord& body : deformables) body.supports.reset(body.firstNode, body.nodeCount);
    const SolverContext ctx = context();
    for (const ContactRow& row : rows.contacts) {
      if (!row.isNodeOnRigid() || rigid[row.body].inverseMass != 0.0) continue;
      const double surfaceSpeed = row.normal.dot(rigid[row.body].velocityAt(row.offset));
      const double gapAtEnd = row.gap + substepLength * row.normal.dot(contactRelativeVelocity(row, ctx));
      DeformableRecord& body = deformables[deformableIndexOfNode(row.node[0])];
      body.supports.add(row.node[0], row.body, row.normal, gapAtEnd, surfaceSpeed);
    }
  }

  // ---- Stage 4: rows ---------------------------------------------------------------------
  void prepareRows(double h) {
    substepLength = h;
    if (directBlocksStale) buildDirectBlocks();
    bullet.loadRigidProperties(rigid);
    rows.prepare(nodes, rigid, settings.gravity, h, settings.solver.baumgarte / h, settings.solver.contactSlop);
    bool anyRows = false;
    for (ContactRow& row : rows.contacts) row.inDirectBlock = row.frictionInBlock = false;  // decided per substep
    for (DirectBlock& block : directBlocks) {
      block.addContacts(rows, rigid, settings.solver.contactSlop);
      anyRows |= block.scalarRowCount() > 0;
    }
    std::vector<NodePairStiffness> elastic;  // h D + h² K_e of the implicit bodies, for their blocks
    if (anyRows)
      for (const DeformableRecord& body : deformables)
        if (body.implicitStep) addImplicitStiffness(body.implicit, nodes, h, elastic);
    for (DirectBlock& block : directBlocks) block.prepare(rows, nodes, rigid, h, elastic);
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
      const auto deformable = static_cast<int32_t>(deformableIndexOfNode(row.node[0]));
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
      // Ropes (no faces, no tetrahedra) are chains: their block's factorisation costs time linear
      // in their length, so they are direct at any length. Surfaces and solids fill in.
      bool forced = false, allowed = true, elastic = false, chains = true;
      for (size_t member = 0; member < deformables.size(); ++member) {
        if (root(static_cast<int32_t>(member)) != static_cast<int32_t>(d)) continue;
        const DeformableRecord& record = deformables[member];
        forced |= record.rowSolver == RowSolverKind::Direct;
        allowed &= record.rowSolver != RowSolverKind::Iterative;
        elastic |= record.implicitStep;
        chains &= record.restMesh.triangles.empty() && record.restMesh.tetrahedra.empty();
        ranges.push_back({record.firstNode, record.nodeCount});
      }
      if (!allowed) continue;
      DirectBlock block(std::move(ranges), chains);
      block.collectRows(rows);
      if (!elastic && (block.scalarRowCount() == 0 || (!forced && !chains && block.scalarRowCount() > kAutoDirectRowLimit)))
        continue;
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
    for (const GrabRow& row : rows.grabs)  // a grabbed body is awake
      if (row.active && row.onRigid()) {
        bullet.wake(row.body);
        bullet.restartSleepTimer(row.body);
      }
    for (const AnchorRow& row : rows.anchors) manage(row.body, row.node[0]);
    for (const ContactRow& row : rows.contacts)  // last step's
      if (row.body >= 0 && row.lambdaNormal > 0) manage(row.body, row.node[0]);
  }

  size_t deformableIndexOfNode(int32_t node) const {
    return static_cast<size_t>(&deformableOfNode(node) - deformables.data());
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
    for (DirectBlock& block : directBlocks) {
      block.solve(rows, ctx, stats);
      block.solveFriction(rows, ctx, settings.solver.friction, stats);
    }
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
    for (GrabRow& row : rows.grabs) row.previousTarget = row.target;
  }

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
  // Blocks that cannot (they hold a dynamic body) leave their edges to strain limiting.
  void projectDirectBlocks() {
    unprojected.assign(deformables.size(), 0);
    for (DirectBlock& block : directBlocks) {
      if (block.projectPositions(rows, nodes)) continue;
      for (const DirectBlock::NodeRange& range : block.ranges())
        unprojected[deformableIndexOfNode(range.first)] = 1;
    }
  }

  // Inextensible edges no block projected brought back within 1 % by position, nodes kept out
  // of the shapes they touched (solver/strain_limiting.h).
  void limitStrainOfUnprojectedRows() {
    std::vector<int32_t> limitedRows;
    std::vector<char> limited(deformables.size(), 0);
    for (size_t r = 0; r < rows.inextensibility.size(); ++r) {
      const InextensibilityRow& row = rows.inextensibility[r];
      const size_t d = deformableIndexOfNode(row.node[0]);
      if ((row.inDirectBlock && !unprojected[d]) || !(std::isinf(row.lambdaMin) || std::isinf(row.lambdaMax))) continue;
      limitedRows.push_back(static_cast<int32_t>(r));
      limited[d] = 1;
    }
    if (limitedRows.empty()) return;
    // Nodes held to the world (fixed points, anchors to static or kinematic bodies) stay where
    // their rows put them; the rest move by their inverse masses, so momentum is kept (a node
    // anchored to a dynamic body that moves is pulled back by its anchor's bias next step).
    std::vector<double> weight = nodes.inverseMass;
    for (const FixedPointRow& row : rows.fixedPoints) weight[row.node] = 0.0;
    for (const AnchorRow& row : rows.anchors)
      for (int k = 0; k < 4; ++k)
        if (row.weight[k] != 0.0 && !bullet.isDynamic(row.body)) weight[row.node[k]] = 0.0;
    // Every node of a body with such rows near a shape the body touched this step is kept out of it.
    std::vector<CollisionRigid> shapes(bullet.rigidBodyCount());
    std::vector<std::vector<char>> touched(deformables.size(), std::vector<char>(shapes.size(), 0));
    for (const ContactRow& row : rows.contacts)
      if (row.body >= 0) touched[deformableIndexOfNode(row.node[0])][row.body] = 1;
    std::vector<NodeOnShape> touching;
    for (size_t d = 0; d < deformables.size(); ++d) {
      if (!limited[d]) continue;
      const DeformableRecord& body = deformables[d];
      // Only nodes near a shape: the passes undo one step's stretch, a few edges' worth.
      double longestEdge = 0.0;
      for (const auto& e : body.restMesh.edges)
        longestEdge = std::max(longestEdge, (body.restMesh.positions[e[1]] - body.restMesh.positions[e[0]]).norm());
      const double reach = body.collision.thickness + 5 * longestEdge;
      for (size_t b = 0; b < shapes.size(); ++b) {
        if (!touched[d][b]) continue;
        shapes[b] = {rigidShapes[b].get(), bullet.position(int(b)), bullet.orientation(int(b)), Vec3::Zero(),
                     Vec3::Zero(), 0.0, 0.0};
        for (int32_t n = body.firstNode; n < body.firstNode + body.nodeCount; ++n) {
          const Vec3 local = shapes[b].orientation.conjugate() * (nodes.position[n] - shapes[b].position);
          if (geometry::distanceToShape(*shapes[b].shape, local, reach).distance < reach)
            touching.push_back({n, &shapes[b], body.collision.thickness});
        }
      }
    }
    const std::vector<Vec3> before = nodes.position;
    std::vector<Vec3> pushed(nodes.size(), Vec3::Zero());
    limitStrain(rows.inextensibility, limitedRows, touching, nodes.position, weight, pushed);
    for (size_t n = 0; n < nodes.size(); ++n) nodes.velocity[n] += (nodes.position[n] - before[n] - pushed[n]) / timeStep;
  }

  // No surface may have passed through another or itself on its way from the step's start
  // (collision/impact_zones.h).
  void separateCrossingSurfaces(double h) {
    const ImpactZoneStats stats = separateByImpactZones(collisionSurfaces(), stepStartPositions, nodes, h);
    report.impactZones = stats.zones;
    report.impactZoneNodes = stats.zoneNodes;
  }

  // Rows left violated beyond the report's thresholds (report.h): the worst of each kind per
  // deformable, named. Nothing is allocated while every row holds.
  void reportViolatedRows() {
    report.violations.clear();
    for (size_t d = 0; d < deformables.size(); ++d) {
      const DeformableRecord& body = deformables[d];
      const auto inBody = [&](int32_t node) { return node >= body.firstNode && node < body.firstNode + body.nodeCount; };
      RowViolation worstAnchor{RowViolation::Kind::AnchorGap, -1, kAnchorGapWarning, {}};
      for (size_t a = 0; a < rows.anchors.size(); ++a) {
        const AnchorRow& row = rows.anchors[a];
        if (!inBody(row.node[0])) continue;
        const double gap = (row.deformablePoint(nodes.position) -
                            (bullet.position(row.body) + bullet.orientation(row.body) * row.localPoint)).norm();
        if (!(gap <= worstAnchor.value)) worstAnchor = {RowViolation::Kind::AnchorGap, static_cast<int>(a), gap, {}};
      }
      if (worstAnchor.index >= 0) {
        const AnchorRow& row = rows.anchors[worstAnchor.index];
        worstAnchor.message = "anchor " + std::to_string(worstAnchor.index) + " of deformable '" + body.name +
                              "' to rigid body '" + rigidNames[row.body] + "' is " + formatNumber(worstAnchor.value) +
                              " m apart";
        report.violations.push_back(std::move(worstAnchor));
      }
      RowViolation worstEdge{RowViolation::Kind::EdgeStretch, -1, kEdgeStretchWarning, {}};
      int edge = 0;
      for (const InextensibilityRow& row : rows.inextensibility) {
        if (!inBody(row.node[0])) continue;
        const double strain = (nodes.position[row.node[1]] - nodes.position[row.node[0]]).norm() / row.restLength - 1.0;
        if (!(strain <= worstEdge.value)) worstEdge = {RowViolation::Kind::EdgeStretch, edge, strain, {}};
        ++edge;
      }
      if (worstEdge.index >= 0) {
        worstEdge.message = "inextensible edge " + std::to_string(worstEdge.index) + " of deformable '" + body.name +
                            "' is stretched " + formatNumber(100.0 * worstEdge.value) + " %";
        report.violations.push_back(std::move(worstEdge));
      }
    }
  }

  // A non-finite or absurdly fast state means the step diverged: say which body, and stop.
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
  bool validRigid(RigidBodyId id) const { return rigidSlots.live(id.index, id.generation); }
  bool validDeformable(DeformableId id) const { return deformableSlots.live(id.index, id.generation); }
  RigidBodyId rigidId(int32_t index) const { return {index, rigidSlots.generation(index)}; }
  DeformableId deformableId(size_t record) const {
    return {static_cast<int32_t>(record), deformableSlots.generation(static_cast<int32_t>(record))};
  }
  // For queries: true if the id is live; else the error is recorded for takeLookupError.
  template <class Id>
  bool lookup(const IdSlots& slots, Id id) const {
    if (slots.live(id.index, id.generation)) return true;
    if (lookupError.empty()) lookupError = slots.check(id.index, id.generation).message();
    return false;
  }
  // A point of a deformable with weights on up to four of its nodes, checked (the count, each
  // node in range, finite weights summing to 1) and in global indices; unused entries repeat
  // the first node with weight 0.
  struct BarycentricPoint {
    std::array<int32_t, 4> node{};
    std::array<double, 4> weight{};
  };
  Result<BarycentricPoint> barycentricPoint(DeformableId body, const std::array<int32_t, 4>& localNodes,
                                            const std::array<double, 4>& weights, int count,
                                            const char* who) const {
    if (count < 1 || count > 4)
      return Error{std::string(who) + ": node count must be 1 to 4, got " + std::to_string(count)};
    BarycentricPoint point;
    double sum = 0.0;
    for (int k = 0; k < count; ++k) {
      Result<int32_t> node = globalNode(body, localNodes[k], who);
      if (!node) return Error{node.message()};
      if (!std::isfinite(weights[k])) return Error{std::string(who) + ": weights must be finite"};
      point.node[k] = *node;
      point.weight[k] = weights[k];
      sum += weights[k];
    }
    if (std::abs(sum - 1.0) > 1e-6) return Error{std::string(who) + ": weights must sum to 1, got " + formatNumber(sum)};
    for (int k = count; k < 4; ++k) point.node[k] = point.node[0];
    return point;
  }

  Result<int32_t> globalNode(DeformableId body, int32_t node, const char* who) const {
    if (!validDeformable(body))
      return Error{std::string(who) + ": " + deformableSlots.check(body.index, body.generation).message()};
    const DeformableRecord& record = deformables[body.index];
    if (node < 0 || node >= record.nodeCount)
      return Error{std::string(who) + ": node " + std::to_string(node) + " is out of range for deformable '" +
                   record.name + "' (" + std::to_string(record.nodeCount) + " nodes)"};
    return record.firstNode + node;
  }
};

}  // namespace tandem
