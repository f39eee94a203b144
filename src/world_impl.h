// World::Impl: the world's state, and its step's stages declared (src/world.cpp runs them in
// order, src/world_step_*.cpp define them, one module per stage; src/world_build.cpp fills the
// state). Internal.
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

// A rigid body as a moving support of implicit bodies (models/supports.h): its velocity before
// this step's holds and what they gave it (impulse, and angular impulse about its centre of
// mass), so that the next step's solve knows what else acted on it over the step.
struct MovingSupportRecord {
  bool valid = false;  // a moving support this step, not set or pushed from outside since
  Vec3 linearVelocity, angularVelocity, impulse, angularImpulse;
};

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
  PositionBasedRest paradigmRest;                           // PBD: of paradigmEdges and the tetrahedra
  bool implicitStep = false;  // FEM, or mass-spring with implicit springs: stepped by `implicit`
  ImplicitBody implicit;
  Supports supports;  // surfaces its nodes rest on, from last step (models/supports.h)
  bool removed = false;  // removed: its nodes stay in the arrays, inert (src/world_edit.cpp)
  bool inDirectBlock = false;  // its nodes are one of the direct blocks' (set by buildDirectBlocks)
  // A surface without tetrahedra with a node that no boundary edge reaches (a sheet, not a
  // ribbon): its limited edges are projected together (solver/strain_limiting.h).
  bool hasInteriorSurfaceNodes = false;
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
  // Pairs (dynamic rigid body, deformable) in touch at the step's start, sorted: blocks whose
  // deformables touch one body are solved as one (buildDirectBlocks); when the pairs change,
  // the blocks are built again.
  std::vector<std::pair<int32_t, int32_t>> bodyContacts, bodyContactsScratch;
  std::vector<char> unprojected;  // per deformable: in a block that could not project this step
  std::vector<NodePairStiffness> implicitStiffness;  // scratch of prepareRows: h D + h² K_e for the blocks
  std::vector<Vec3> stepStartPositions;  // node positions before this step moved them
  std::vector<Vec3> stepStartVelocities;  // and their velocities before the models changed them
  std::vector<Vec3> modelVelocityChange;  // per node: what the models add over the step, per substep
  std::vector<RigidPose> stepStartPoses;       // rigid bodies before this step moved them
  std::vector<CollisionRigid> substepShapes;  // rigid shapes in their pose at a substep's start
  struct TargetPath {
    Vec3 from, to;  // where a moving target is at the step's start and end
  };
  std::vector<TargetPath> fixedPointPaths, grabPaths;
  // Last step's contact impulses by feature, for warm starting: sorted by key (the last of equal
  // keys counts), kept in place so that the step allocates nothing once grown.
  std::vector<std::pair<uint64_t, ContactImpulse>> previousContacts;
  std::vector<std::pair<uint64_t, uint32_t>> previousContactOrder;  // scratch of setPreviousContacts
  const ContactImpulse* previousContact(uint64_t key) const;
  void setPreviousContacts();  // from this step's rows
  std::vector<char> supportAssigned;  // per node: scratch of detectDeformableContacts
  // Scratch of limitStrainOfUnprojectedRows, kept so that the step allocates nothing once grown.
  struct StrainLimitingScratch {
    std::vector<int32_t> rows;           // the rows limited
    std::vector<LimitedEdge> edges;      // theirs that can move, as the passes read them
    std::vector<char> limitedBody;       // per deformable: has some
    std::vector<double> weight;          // per node: its inverse mass in the passes, 0 if held
    std::vector<CollisionRigid> shapes;  // per rigid body touched: its shape where it is
    std::vector<char> touched;           // per deformable × rigid body
    std::vector<NodeOnShape> touching;   // nodes kept out of those shapes
    std::vector<FaceOnCore> faces;       // faces kept off round bodies' cores
    std::vector<char> heldByBody;        // per node: anchored to a dynamic body
    std::vector<Vec3> before, pushed;    // per node
    std::vector<Vec3> reaction;          // per node held by a body: −Σ m Δx of its edges' other ends
    SweptEdgeSolveScratch together;      // of the edges' projection together
    std::vector<Vec3> heldAlong;         // per node: the normal of the still shape it touches, or zero
    std::vector<char> sheet;             // per deformable: its edges are projected together
    std::vector<MovingBody> movingBodies;  // dynamic bodies the sheets touch, moved with them
    std::vector<int32_t> movingBodyNode;   // per rigid body: its index among `positions`, or −1
    std::vector<char> touchesRigid;        // per rigid body: in a contact with another
    std::vector<char> anchoredToDynamic;   // per deformable
    std::vector<SheetContact> sheetContacts;  // the step's contacts between those and the sheets
    std::vector<Vec3> positions;         // the nodes', then those bodies' centres
  } strainScratch;
  PositionBasedScratch paradigmScratch;  // of applyParadigm
  ImplicitSolveScratch implicitScratch;  // of solveImplicitVelocities
  // Scratch of solveImplicitBodies: the groups (union-find over deformables, and per rigid body
  // the first deformable resting on it), one group's bodies, their supports and moving supports.
  std::vector<int32_t> implicitGroup, implicitGroupOfRigid;
  std::vector<ImplicitBody*> implicitBodies;
  std::vector<Supports*> implicitSupports;
  std::vector<MovingSupport> movingSupports;
  std::vector<MovingSupportRecord> movingSupportRecords;  // per rigid body
  // A body set or pushed from outside the step: what acted on it last step says nothing of the next.
  void forgetMovingSupport(int32_t body) {
    if (body >= 0 && static_cast<size_t>(body) < movingSupportRecords.size()) movingSupportRecords[body].valid = false;
  }
  std::vector<Vec3> sweepStartVelocity;  // the nodes' velocities before the warm start

  StepReport report;
  double time = 0.0;
  int64_t steps = 0;
  double timeStep = 0.0;  // of the step in progress
  double substepLength = 0.0;  // h / n: what the rows are prepared and solved over

  explicit Impl(const WorldSettings& s) : settings(s), bullet(s.gravity) {}

  SolverContext context() {
    SolverContext ctx{nodes.velocity,
                      nodes.inverseMass,
                      rigid,
                      substepLength,
                      settings.solver.baumgarte / substepLength,
                      sweepStartVelocity};
    ctx.iterations = settings.solver.iterations;
    return ctx;
  }

  // ---- Substeps ---------------------------------------------------------------------------
  // The step's start: positions and poses the substeps' contact gaps are measured from, the
  // moving targets' paths, and the impulse sums the report gives cleared.
  void beginStep();

  // The models ran once over the whole step (v ← v*); with n substeps the nodes go back to their
  // start velocity and receive (v* − v) / n at the start of each substep, as gravity would.
  void spreadModelVelocities(int substeps);

  // Substep s of n: the models' share of the velocity change, the moving targets at their
  // substep's ends, and the contacts moved on (collision/contact_motion.h).
  void beginSubstep(int substep, int substeps);

  // After a substep's solve: its impulses added to the step's sums; after the last, the
  // contacts remembered for the next step's warm start and models.
  void endSubstepSolve(bool lastSubstep);

  // ---- Stage 1: models -----------------------------------------------------------------
  // Unconstrained node velocities: v* = v + h m⁻¹ (f_internal + f_external), gravity included.
  void computeUnconstrainedVelocities(double h);
  // The implicit bodies' solves, grouped by the dynamic bodies resting on them (models/supports.h),
  // and those bodies' reactions, given out per substep.
  void solveImplicitBodies(double h);
  void giveMovingSupportsTheirReactions(double fraction);

  // Position-based paradigms turn goals into velocities (mass-spring and FEM bodies are done:
  // their forces are in v* already), after holding their supported nodes (models/supports.h).
  void applyParadigm(DeformableRecord& body, double h);

  Vec3 bodyMomentum(const DeformableRecord& body) const;

  // v ← v − min(c h, 1) (v − v̄), v̄ the body's mass-weighted mean velocity over its free nodes.
  void dampInternalMotion(const DeformableRecord& body, double h);

  // ---- Stage 3: deformable contacts ---------------------------------------------------------
  // The deformables' collision surfaces, in `surfaceScratch` (valid until the next call).
  std::span<const CollisionSurface> collisionSurfaces();
  std::vector<CollisionSurface> surfaceScratch;
  std::vector<CollisionRigid> contactShapes;  // scratch of detectDeformableContacts: per rigid body
  std::vector<uint64_t> anchoredPairs;        // its nodeBodyKey's of pairs that do not collide, sorted
  std::vector<uint64_t> anchoredNeighbours;   // listAnchoredPairs' scratch: the anchored nodes' neighbours' pairs
  std::vector<char> anchoredDeformables;      // and per deformable, whether it has an anchor
  ContactDetectionScratch contactScratch;
  ImpactZoneScratch impactScratch;  // of separateByImpactZones

  void detectDeformableContacts(double h);
  void listAnchoredPairs();

  void noteBodyContacts();
  void rememberContacts();

  // The supports carried their holds' impulses (models/supports.h): on the report of the
  // bodies' impulse from deformables.
  void addHoldImpulsesToSupports();

  // The static and kinematic surfaces the nodes touched or neared, with the gap left at the
  // step's end, for the next step's models (models/supports.h).
  void rememberSupports();

  // ---- Stage 4: rows ---------------------------------------------------------------------
  void prepareRows(double h);

  // One block per group of deformables tied together through dynamic rigid bodies by anchors
  // (union-find over deformables), so that a body shared by several of them is solved with
  // all of them at once.
  void buildDirectBlocks();

  // Bullet's islands know nothing of anchors and of Tandem's contacts, so Tandem decides sleep
  // for bodies that deformables hold or carry (anchored, or pushed by a contact last step): an
  // awake one does not fall asleep on its own (it keeps carrying, and reporting, its load); a
  // sleeping one (put to sleep on purpose) is immovable to Tandem's rows and wakes when any node
  // of such a deformable moves faster than the body's sleeping threshold.
  void manageSleepOfHeldBodies();

  size_t deformableIndexOfNode(int32_t node) const {
    return static_cast<size_t>(&deformableOfNode(node) - deformables.data());
  }
  const DeformableRecord& deformableOfNode(int32_t node) const {
    auto after = std::upper_bound(deformables.begin(), deformables.end(), node,
                                  [](int32_t n, const DeformableRecord& record) { return n < record.firstNode; });
    return *(after - 1);
  }

  // ---- Stage 5: interleaved solve (called from inside Bullet's solver) -------------------
  void afterSetup() override;

  // Bounded rows by projected Gauss-Seidel first, then each direct block exactly, so that a
  // sweep ends with the bilateral rows satisfied, then the contacts no block holds.
  void afterIteration(int) override;

  // ---- Stage 7: integrate ----------------------------------------------------------------
  void integrateNodes(double h);

  // Split-impulse style: a contact found penetrating beyond the slop moves its deformable side
  // out by a fraction of the excess, without touching velocities, so resting contacts do not
  // bounce. Each node moves in proportion to its share of the contact's inverse mass.
  void pushOutOfContacts();

  // Post-stabilisation (Cline and Pai 2003): velocity-level rows leave a drift of order
  // h² v² / L (a cloth corner whipping round at 60 rad/s stretches its edges by half in a step);
  // each block projects its nodes back onto its rows with the step's own factorisation.
  // Blocks that cannot (a dynamic body touches their contacts) leave their edges to strain
  // limiting; the bodies their anchors hold move with them.
  void projectDirectBlocks();
  std::vector<DirectBlock::BodyMove> blockBodyMoves;  // scratch of projectDirectBlocks
  std::vector<RigidPose> blockPoses;                  // and the bodies' poses it starts from

  // Inextensible edges no block projected brought back within 1 % by position, nodes kept out
  // of the shapes they touched (solver/strain_limiting.h).
  void giveReactionToBody(AnchorRow& row, const Vec3& impulse, double h);
  void limitStrainOfUnprojectedRows();

  // No surface may have passed through another or itself on its way from the step's start
  // (collision/impact_zones.h).
  void separateCrossingSurfaces(double h);

  // Rows left violated beyond the report's thresholds (report.h): the worst of each kind per
  // deformable, named. Nothing is allocated while every row holds.
  void reportViolatedRows();

  // A non-finite or absurdly fast state means the step diverged: say which body, and stop.
  Status checkDiverged() const;

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
