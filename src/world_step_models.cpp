// World::Impl, stage 1: the deformable models' unconstrained velocities, their paradigms and
// damping. (src/world.cpp runs the stages in order; src/world_impl.h holds the state.)
#include "world_impl.h"

#include <numeric>

namespace tandem {

void World::Impl::computeUnconstrainedVelocities(double h) {
  for (Vec3& f : nodes.force) f.setZero();
  addSpringForces(springs, nodes);
  for (DeformableRecord& body : deformables) body.supports.clearHolds();
  solveImplicitBodies(h);
  report.modelIterations = 0;
  report.modelsConverged = true;
  for (const DeformableRecord& body : deformables)
    if (body.implicitStep) {
      report.modelIterations = std::max(report.modelIterations, body.implicit.lastIterations);
      report.modelsConverged &= body.implicit.lastConverged;
    }
  for (DeformableRecord& body : deformables) {
    if (!body.implicitStep)
      for (int32_t i = body.firstNode; i < body.firstNode + body.nodeCount; ++i)
        if (nodes.inverseMass[i] != 0.0)
          nodes.velocity[i] += h * (settings.gravity + nodes.inverseMass[i] * nodes.force[i]);
    dampInternalMotion(body, h);
    applyParadigm(body, h);
  }
}

// The implicit bodies, each solved alone or with those it shares a moving support with (a bar on
// two jellies), that support moving with them (models/supports.h).
void World::Impl::solveImplicitBodies(double h) {
  const size_t count = deformables.size();
  // Group the bodies by their moving supports: a union over the rigid bodies they rest on.
  std::vector<int32_t>& group = implicitGroup;
  group.resize(count);
  std::iota(group.begin(), group.end(), 0);
  auto root = [&](int32_t d) {
    while (group[d] != d) d = group[d] = group[group[d]];
    return d;
  };
  std::vector<int32_t>& firstOnBody = implicitGroupOfRigid;
  firstOnBody.assign(rigid.size(), -1);
  for (size_t d = 0; d < count; ++d) {
    const DeformableRecord& body = deformables[d];
    if (!body.implicitStep) continue;
    for (size_t i = 0; i < body.supports.moves.size(); ++i) {
      const int32_t support = body.supports.body[i];
      if (!body.supports.moves[i] || support < 0 || static_cast<size_t>(support) >= rigid.size()) continue;
      int32_t& other = firstOnBody[support];
      if (other < 0)
        other = static_cast<int32_t>(d);
      else
        group[root(static_cast<int32_t>(d))] = root(other);
    }
  }
  movingSupportRecords.resize(rigid.size());
  for (size_t d = 0; d < count; ++d) {
    if (!deformables[d].implicitStep || root(static_cast<int32_t>(d)) != static_cast<int32_t>(d)) continue;
    implicitBodies.clear();
    implicitSupports.clear();
    movingSupports.clear();
    for (size_t e = d; e < count; ++e) {
      if (!deformables[e].implicitStep || root(static_cast<int32_t>(e)) != static_cast<int32_t>(d)) continue;
      implicitBodies.push_back(&deformables[e].implicit);
      implicitSupports.push_back(&deformables[e].supports);
    }
    // Each moving support of the group, with what else acted on it last step: its momentum's
    // change less gravity's and the holds' (nothing if it was not a moving support then).
    for (size_t b = 0; b < rigid.size(); ++b) {
      if (firstOnBody[b] < 0 || root(firstOnBody[b]) != static_cast<int32_t>(d)) continue;
      const auto index = static_cast<int>(b);
      MovingSupportRecord& record = movingSupportRecords[b];
      // Asleep or made still since last step: its nodes are not held this step.
      if (!bullet.isDynamic(index) || !bullet.isAwake(index) || rigid[b].inverseMass == 0.0 ||
          rigid[b].inverseInertia.determinant() <= 0.0) {
        record.valid = false;
        continue;
      }
      MovingSupport support{index, bullet.mass(index), rigid[b].inverseInertia.inverse()};
      const Vec3 linear = bullet.linearVelocity(index), angular = bullet.angularVelocity(index);
      if (record.valid) {
        support.otherImpulse = support.mass * (linear - record.linearVelocity - h * settings.gravity) - record.impulse;
        support.otherAngularImpulse = support.inertia * (angular - record.angularVelocity) - record.angularImpulse;
      }
      record = {true, linear, angular, Vec3::Zero(), Vec3::Zero()};
      movingSupports.push_back(support);
    }
    solveImplicitVelocities(implicitBodies, implicitSupports, movingSupports, nodes, settings.gravity, h,
                            implicitScratch);  // gravity included
    // What the moving supports gave the held nodes, they take back (given out per substep).
    for (const Supports* supports : implicitSupports)
      for (size_t i = 0; i < supports->holdBody.size(); ++i)
        if (supports->holdBody[i] >= 0 && supports->moves[i]) {
          MovingSupportRecord& record = movingSupportRecords[supports->holdBody[i]];
          record.impulse -= supports->holdImpulse[i];
          record.angularImpulse -= supports->offset[i].cross(supports->holdImpulse[i]);
        }
  }
  for (size_t b = 0; b < rigid.size(); ++b)
    if (firstOnBody[b] < 0) movingSupportRecords[b].valid = false;
  if (settings.solver.substeps == 1) giveMovingSupportsTheirReactions(1.0);
}

void World::Impl::giveMovingSupportsTheirReactions(double fraction) {
  for (size_t b = 0; b < movingSupportRecords.size(); ++b) {
    const MovingSupportRecord& record = movingSupportRecords[b];
    if (!record.valid) continue;
    bullet.applyImpulse(static_cast<int>(b), fraction * record.impulse, Vec3::Zero());
    bullet.applyAngularImpulse(static_cast<int>(b), fraction * record.angularImpulse);
  }
}

void World::Impl::applyParadigm(DeformableRecord& body, double h) {
  if (body.paradigm.type == ParadigmType::MassSpring || body.paradigm.type == ParadigmType::CorotationalFem) return;
  PositionBasedScratch& scratch = paradigmScratch;
  PositionBasedBody model{body.firstNode,           body.nodeCount,
                          body.restMesh.positions,  body.paradigmEdges,
                          body.restMesh.tetrahedra, &body.paradigmRest,
                          body.paradigm.stiffness,  body.paradigm.damping,
                          body.paradigm.iterations, {},
                          {},                       {}};
  // PBD projects its supports as constraints among its own (weighting held nodes in the
  // projections, as shape matching's fit does, blew a jelly resting on a box up); what they
  // pushed is the supports' impulse, (1 − γ) m Δ / h per node.
  if (body.paradigm.type == ParadigmType::PositionBased) {
    std::vector<SupportPlane>& planes = scratch.supports;
    planes.clear();
    for (int32_t i = 0; i < body.nodeCount; ++i) {
      const int32_t n = body.firstNode + i;
      if (body.supports.normal[i].isZero() || nodes.inverseMass[n] == 0.0) continue;
      const Vec3& normal = body.supports.normal[i];
      planes.push_back({i, normal, normal.dot(nodes.position[n]) + h * body.supports.targetSpeed(i, h)});
    }
    std::vector<double>& push = scratch.supportPush;
    push.assign(static_cast<size_t>(body.nodeCount), 0.0);
    model.supports = planes;
    model.supportPush = push;
    applyPositionBasedDynamics(model, nodes, h, scratch);
    for (const SupportPlane& plane : planes)
      if (push[plane.node] > 0)
        body.supports.recordHold(plane.node, (1.0 - body.paradigm.damping) * push[plane.node] /
                                                 (nodes.inverseMass[body.firstNode + plane.node] * h));
    return;
  }
  constexpr double kHeldWeight = 1000.0;  // how much heavier a held node counts in the fit
  const std::span<const double> inverseMass(nodes.inverseMass.data() + body.firstNode, body.nodeCount);
  body.supports.hold(std::span<Vec3>(nodes.velocity.data() + body.firstNode, body.nodeCount), inverseMass, h);
  std::vector<double>& weights = scratch.weightInverseMass;
  weights.assign(inverseMass.begin(), inverseMass.end());
  double heldMass = 0.0;
  for (int32_t i = 0; i < body.nodeCount; ++i) {
    if (body.supports.holdBody[i] < 0) continue;
    weights[i] /= kHeldWeight;
    heldMass += 1.0 / inverseMass[i];
  }
  model.weightInverseMass = weights;
  const Vec3 before = bodyMomentum(body);
  applyShapeMatching(model, nodes, h, scratch);
  // Weighted towards the held nodes, the fit moves the body's mass centre: that momentum came
  // through the held nodes from their supports, so it is theirs, by mass. Along each support's
  // normal; along the surface it would be a friction with no bound (a shape-matched cube held on
  // a 40° slope with μ = 0.5), so that part goes back to the whole body, and the contacts'
  // friction, bounded by μ (λₙ + hold) (constraints/contact.h), decides whether it slides.
  if (heldMass == 0.0) return;
  const Vec3 transmitted = bodyMomentum(body) - before;
  Vec3 alongSurfaces = Vec3::Zero();
  double bodyMass = 0.0;
  for (int32_t i = 0; i < body.nodeCount; ++i) {
    if (inverseMass[i] == 0.0) continue;
    bodyMass += 1.0 / inverseMass[i];
    if (body.supports.holdBody[i] < 0) continue;
    const Vec3 share = transmitted / (inverseMass[i] * heldMass);
    const Vec3& normal = body.supports.normal[i];
    body.supports.holdImpulse[i] += share.dot(normal) * normal;
    alongSurfaces += share - share.dot(normal) * normal;
  }
  for (int32_t i = 0; i < body.nodeCount; ++i)
    if (inverseMass[i] != 0.0) nodes.velocity[body.firstNode + i] -= alongSurfaces / bodyMass;
}

Vec3 World::Impl::bodyMomentum(const DeformableRecord& body) const {
  Vec3 momentum = Vec3::Zero();
  for (int32_t i = body.firstNode; i < body.firstNode + body.nodeCount; ++i)
    if (nodes.inverseMass[i] > 0) momentum += nodes.velocity[i] / nodes.inverseMass[i];
  return momentum;
}

void World::Impl::dampInternalMotion(const DeformableRecord& body, double h) {
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

}  // namespace tandem
