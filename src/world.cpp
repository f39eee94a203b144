#include "world_impl.h"

namespace tandem {

World::World() : m_impl(std::make_unique<Impl>(WorldSettings{})) {}
World::~World() = default;

const WorldSettings& World::settings() const { return m_impl->settings; }

// ---- Ids: queries given a bad id return a neutral value and record the error -------------

namespace {
const std::string kNoName;
}  // namespace

bool World::contains(RigidBodyId id) const { return m_impl->rigidSlots.live(id.index, id.generation); }
bool World::contains(DeformableId id) const { return m_impl->deformableSlots.live(id.index, id.generation); }
bool World::contains(JointId id) const { return m_impl->jointSlots.live(id.index, id.generation); }
bool World::contains(AnchorId id) const { return m_impl->anchorSlots.live(id.index, id.generation); }
bool World::contains(FixedPointId id) const { return m_impl->fixedPointSlots.live(id.index, id.generation); }
bool World::contains(GrabId id) const { return m_impl->grabSlots.live(id.index, id.generation); }

Status World::takeLookupError() const {
  if (m_impl->lookupError.empty()) return {};
  Error error{m_impl->lookupError};
  m_impl->lookupError.clear();
  return error;
}

// ---- Rigid bodies -----------------------------------------------------------------------

int World::rigidBodyCount() const { return m_impl->rigidSlots.liveCount(); }
std::vector<RigidBodyId> World::rigidBodies() const {
  std::vector<RigidBodyId> ids;
  for (int32_t i = 0; i < static_cast<int32_t>(m_impl->rigidSlots.size()); ++i)
    if (m_impl->rigidSlots.liveIndex(i)) ids.push_back(m_impl->rigidId(i));
  return ids;
}
std::optional<RigidBodyId> World::findRigidBody(std::string_view name) const {
  for (size_t i = 0; i < m_impl->rigidNames.size(); ++i)
    if (m_impl->rigidSlots.liveIndex(static_cast<int32_t>(i)) && m_impl->rigidNames[i] == name)
      return m_impl->rigidId(static_cast<int32_t>(i));
  return std::nullopt;
}
const std::string& World::rigidName(RigidBodyId body) const {
  return m_impl->lookup(m_impl->rigidSlots, body) ? m_impl->rigidNames[body.index] : kNoName;
}
Vec3 World::rigidPosition(RigidBodyId body) const {
  return m_impl->lookup(m_impl->rigidSlots, body) ? m_impl->bullet.position(body.index) : Vec3::Zero();
}
Quat World::rigidOrientation(RigidBodyId body) const {
  return m_impl->lookup(m_impl->rigidSlots, body) ? m_impl->bullet.orientation(body.index) : Quat::Identity();
}
Vec3 World::rigidLinearVelocity(RigidBodyId body) const {
  return m_impl->lookup(m_impl->rigidSlots, body) ? m_impl->bullet.linearVelocity(body.index) : Vec3::Zero();
}
Vec3 World::rigidAngularVelocity(RigidBodyId body) const {
  return m_impl->lookup(m_impl->rigidSlots, body) ? m_impl->bullet.angularVelocity(body.index) : Vec3::Zero();
}
double World::rigidMass(RigidBodyId body) const {
  return m_impl->lookup(m_impl->rigidSlots, body) ? m_impl->bullet.mass(body.index) : 0.0;
}
Mat3 World::rigidInertia(RigidBodyId body) const {
  return m_impl->lookup(m_impl->rigidSlots, body) ? m_impl->bullet.inertia(body.index) : Mat3::Zero();
}
bool World::rigidIsAwake(RigidBodyId body) const {
  return m_impl->lookup(m_impl->rigidSlots, body) && m_impl->bullet.isAwake(body.index);
}
double World::rigidContactImpulse(RigidBodyId a, RigidBodyId b) const {
  if (!m_impl->lookup(m_impl->rigidSlots, a) || !m_impl->lookup(m_impl->rigidSlots, b)) return 0.0;
  return m_impl->bullet.contactImpulse(a.index, b.index);
}
Vec3 World::deformableImpulseOnRigid(RigidBodyId body) const {
  return m_impl->lookup(m_impl->rigidSlots, body) ? m_impl->rigid[body.index].impulse : Vec3::Zero();
}
Vec3 World::deformableAngularImpulseOnRigid(RigidBodyId body) const {
  return m_impl->lookup(m_impl->rigidSlots, body) ? m_impl->rigid[body.index].angularImpulse : Vec3::Zero();
}
Vec3 World::deformableForceOnRigid(RigidBodyId body) const {
  const double h = m_impl->timeStep;
  return h > 0 ? Vec3(deformableImpulseOnRigid(body) / h) : Vec3(deformableImpulseOnRigid(body) * 0.0);
}
Vec3 World::deformableTorqueOnRigid(RigidBodyId body) const {
  const double h = m_impl->timeStep;
  return h > 0 ? Vec3(deformableAngularImpulseOnRigid(body) / h) : Vec3(deformableAngularImpulseOnRigid(body) * 0.0);
}

// ---- Deformable bodies ------------------------------------------------------------------

int World::deformableCount() const { return m_impl->deformableSlots.liveCount(); }
std::vector<DeformableId> World::deformableIds() const {
  std::vector<DeformableId> ids;
  for (size_t d = 0; d < m_impl->deformables.size(); ++d)
    if (!m_impl->deformables[d].removed) ids.push_back(m_impl->deformableId(d));
  return ids;
}
std::optional<DeformableId> World::findDeformable(std::string_view name) const {
  for (size_t i = 0; i < m_impl->deformables.size(); ++i)
    if (!m_impl->deformables[i].removed && m_impl->deformables[i].name == name) return m_impl->deformableId(i);
  return std::nullopt;
}
const std::string& World::deformableName(DeformableId body) const {
  return m_impl->lookup(m_impl->deformableSlots, body) ? m_impl->deformables[body.index].name : kNoName;
}

std::span<const Vec3> World::nodePositions(DeformableId body) const {
  if (!m_impl->lookup(m_impl->deformableSlots, body)) return {};
  const DeformableRecord& r = m_impl->deformables[body.index];
  return std::span<const Vec3>(m_impl->nodes.position).subspan(r.firstNode, r.nodeCount);
}
std::span<const Vec3> World::nodeVelocities(DeformableId body) const {
  if (!m_impl->lookup(m_impl->deformableSlots, body)) return {};
  const DeformableRecord& r = m_impl->deformables[body.index];
  return std::span<const Vec3>(m_impl->nodes.velocity).subspan(r.firstNode, r.nodeCount);
}
std::span<const double> World::nodeInverseMasses(DeformableId body) const {
  if (!m_impl->lookup(m_impl->deformableSlots, body)) return {};
  const DeformableRecord& r = m_impl->deformables[body.index];
  return std::span<const double>(m_impl->nodes.inverseMass).subspan(r.firstNode, r.nodeCount);
}
const DeformableMesh& World::restMesh(DeformableId body) const {
  static const DeformableMesh kNoMesh;
  return m_impl->lookup(m_impl->deformableSlots, body) ? m_impl->deformables[body.index].restMesh : kNoMesh;
}

Vec3 World::fixedPointImpulse(FixedPointId id) const {
  const Impl& w = *m_impl;
  if (!w.lookup(w.fixedPointSlots, id)) return Vec3::Zero();
  return w.rows.fixedPoints[w.fixedPointSlots.position(id.index)].stepImpulse;
}

AnchorState World::anchorState(AnchorId id) const {
  const Impl& w = *m_impl;
  if (!w.lookup(w.anchorSlots, id)) return {};
  const AnchorRow& row = w.rows.anchors[w.anchorSlots.position(id.index)];
  AnchorState state;
  state.impulse = row.stepImpulse;
  state.worldPointOnBody = w.bullet.position(row.body) + w.bullet.orientation(row.body) * row.localPoint;
  state.worldPointOnDeformable = row.deformablePoint(w.nodes.position);
  return state;
}

std::vector<ContactReport> World::contacts() const {
  const Impl& w = *m_impl;
  std::vector<ContactReport> reports;
  reports.reserve(w.rows.contacts.size());
  std::vector<bool> holdReported(w.nodes.size(), false);  // see models/implicit_solve.h
  for (const ContactRow& row : w.rows.contacts) {
    ContactReport report;
    const DeformableRecord& body = w.deformableOfNode(row.node[0]);
    report.deformable = w.deformableId(w.deformableIndexOfNode(row.node[0]));
    if (row.body >= 0)
      report.rigid = w.rigidId(row.body);
    else
      report.other = w.deformableId(w.deformableIndexOfNode(row.node[1]));
    for (int k = 0; k < 4; ++k)
      if (row.coefficient[k] > 0) report.point += row.coefficient[k] * w.nodes.position[row.node[k]];
    report.normal = row.normal;
    report.gap = row.gap;
    report.normalImpulse = row.stepNormalImpulse;
    report.frictionImpulse = row.stepFrictionImpulse;
    if (row.isNodeOnRigid() && !holdReported[row.node[0]]) {
      const auto i = static_cast<size_t>(row.node[0] - body.firstNode);
      if (body.supports.holdBody[i] == row.body) {
        const Vec3& hold = body.supports.holdImpulse[i];
        report.normalImpulse += hold.dot(row.normal);
        report.frictionImpulse += hold - hold.dot(row.normal) * row.normal;
        holdReported[row.node[0]] = true;
      }
    }
    reports.push_back(report);
  }
  return reports;
}

// ---- The step ---------------------------------------------------------------------------

Status World::step(double h) {
  if (!(std::isfinite(h) && h > 0 && h <= 1.0))
    return Error{"step: time step must be in (0, 1] seconds, got " + formatNumber(h)};
  Impl& w = *m_impl;
  const int substeps = w.settings.solver.substeps;
  const double substep = h / substeps;
  w.timeStep = h;
  StepReport& report = w.report;
  report.rmsDeltaLambda.clear();
  report.stageSeconds.fill(0.0);
  StageClock clock;
  auto timed = [&](Stage stage) { report.stageSeconds[static_cast<size_t>(stage)] += clock.lap(); };

  w.beginStep();                        // start-of-step positions and poses; impulse sums cleared
  w.computeUnconstrainedVelocities(h);  // 1. deformable models: unconstrained node velocities
  timed(Stage::Models);
  w.manageSleepOfHeldBodies();
  timed(Stage::RigidPrediction);
  w.detectDeformableContacts(h);        // 3. Tandem: deformable contacts, once per step, speculative
  w.spreadModelVelocities(substeps);    //    the models' velocity change is then given out per substep
  timed(Stage::CollisionDetection);
  for (int s = 0; s < substeps; ++s) {  // n substeps of h/n:
    w.beginSubstep(s, substeps);        //   the models' share; moving targets; contact gaps moved on
    w.bullet.predictRigidMotion(substep);  // 2. Bullet: gravity and external forces on rigid bodies
    timed(Stage::RigidPrediction);
    w.bullet.detectCollisions(substep);    // 3. Bullet: rigid-rigid contacts
    timed(Stage::CollisionDetection);
    w.prepareRows(substep);                // 4. Tandem's rows: Jacobians, effective masses, biases
    timed(Stage::Rows);
    w.bullet.solve(substep, w.settings.solver.iterations, w);  // 5+6. K × [Bullet iteration, Tandem sweep]
    w.endSubstepSolve(s + 1 == substeps);
    timed(Stage::Solve);
    w.integrateNodes(substep);             // 7. symplectic Euler for nodes; Bullet for rigid bodies
    w.bullet.integrate(substep);
    timed(Stage::Integrate);
  }
  w.timeStep = h;
  w.projectDirectBlocks();              // 7. then the direct blocks' rows projected back by position,
  w.limitStrainOfUnprojectedRows();     //    the edges no block projected limited to 1 % stretch;
  w.separateCrossingSurfaces(h);        //    last, impact zones where surfaces would have crossed
  timed(Stage::Integrate);

  w.reportViolatedRows();
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
double World::lastTimeStep() const { return m_impl->timeStep; }

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
