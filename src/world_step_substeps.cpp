// World::Impl: the step's start and its substeps' starts and ends: start-of-step state, the models'
// velocity change given out per substep, moving targets, impulse sums. (src/world.cpp runs the
// stages in order; src/world_impl.h holds the state.)
#include "world_impl.h"

namespace tandem {

void World::Impl::beginStep() {
  stepStartPositions = nodes.position;  // also the impact zones' start
  for (FixedPointRow& row : rows.fixedPoints) row.stepImpulse.setZero();
  for (GrabRow& row : rows.grabs) row.stepImpulse.setZero();
  for (AnchorRow& row : rows.anchors) row.stepImpulse.setZero();
  for (RigidSolverState& body : rigid) body.impulse = body.angularImpulse = Vec3::Zero();
  bullet.beginStep();
  stepStartPoses.resize(static_cast<size_t>(bullet.rigidBodyCount()));  // also the sheets' contacts' start
  for (int b = 0; b < bullet.rigidBodyCount(); ++b) stepStartPoses[b] = {bullet.position(b), bullet.orientation(b)};
  if (settings.solver.substeps == 1) return;  // what only the substeps read
  stepStartVelocities = nodes.velocity;
  fixedPointPaths.clear();
  for (const FixedPointRow& row : rows.fixedPoints) fixedPointPaths.push_back({row.previousTarget, row.target});
  grabPaths.clear();
  for (const GrabRow& row : rows.grabs) grabPaths.push_back({row.previousTarget, row.target});
}

void World::Impl::spreadModelVelocities(int substeps) {
  if (substeps == 1) return;
  modelVelocityChange.resize(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) {
    modelVelocityChange[i] = (nodes.velocity[i] - stepStartVelocities[i]) / substeps;
    nodes.velocity[i] = stepStartVelocities[i];
  }
}

void World::Impl::beginSubstep(int substep, int substeps) {
  if (substeps == 1) return;
  giveMovingSupportsTheirReactions(1.0 / substeps);
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

void World::Impl::endSubstepSolve(bool lastSubstep) {
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

}  // namespace tandem
