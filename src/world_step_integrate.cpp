// World::Impl, stage 7: integration of the nodes and the position passes after the substeps.
// (src/world.cpp runs the stages in order; src/world_impl.h holds the state.)
#include "world_impl.h"

#include <cmath>

namespace tandem {
namespace {

// An anchor to a dynamic body holds its nodes in the position passes only while it is closed to
// within this (m): open further (a scene that starts with an anchor apart), its nodes held where
// they are stood for a rigid attachment at the wrong place, and the passes' reactions on the
// body tore the cloth of scenes/anchors.json apart (diverged at step 9); they move like any node
// then, and the anchor's bias closes the gap.
constexpr double kHeldAnchorGap = 0.01;

}  // namespace

void World::Impl::integrateNodes(double h) {
  for (size_t i = 0; i < nodes.size(); ++i) nodes.position[i] += h * nodes.velocity[i];
  pushOutOfContacts();
  for (FixedPointRow& row : rows.fixedPoints) row.previousTarget = row.target;
  for (GrabRow& row : rows.grabs) row.previousTarget = row.target;
}

void World::Impl::pushOutOfContacts() {
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

void World::Impl::projectDirectBlocks() {
  unprojected.assign(deformables.size(), 0);
  report.blockFactorisations = 0;
  blockPoses.resize(static_cast<size_t>(bullet.rigidBodyCount()));
  for (int b = 0; b < bullet.rigidBodyCount(); ++b) blockPoses[b] = {bullet.position(b), bullet.orientation(b)};
  for (DirectBlock& block : directBlocks) {
    blockBodyMoves.clear();
    const bool projected = block.projectPositions(rows, nodes, blockPoses, blockBodyMoves);
    for (const DirectBlock::BodyMove& move : blockBodyMoves) {
      const double angle = move.rotation.norm();
      Quat orientation = bullet.orientation(move.body);
      if (angle > 0.0) orientation = (Quat(Eigen::AngleAxisd(angle, move.rotation / angle)) * orientation).normalized();
      bullet.setPose(move.body, bullet.position(move.body) + move.translation, orientation);
    }
    report.blockFactorisations += block.takeFactorisationCount();  // the step's last use of the block
    if (projected) continue;
    for (const DirectBlock::NodeRange& range : block.ranges())
      unprojected[deformableIndexOfNode(range.first)] = 1;
  }
}

void World::Impl::limitStrainOfUnprojectedRows() {
  StrainLimitingScratch& scratch = strainScratch;
  scratch.rows.clear();
  scratch.limitedBody.assign(deformables.size(), 0);
  for (size_t r = 0; r < rows.inextensibility.size(); ++r) {
    const InextensibilityRow& row = rows.inextensibility[r];
    const size_t d = deformableIndexOfNode(row.node[0]);
    if ((row.inDirectBlock && !unprojected[d]) || !(std::isinf(row.lambdaMin) || std::isinf(row.lambdaMax))) continue;
    scratch.rows.push_back(static_cast<int32_t>(r));
    scratch.limitedBody[d] = 1;
  }
  if (scratch.rows.empty()) return;
  // Nodes held by fixed points and anchors stay where their rows put them; the rest move by
  // their inverse masses. What a node anchored to a dynamic body would have taken goes to the
  // body (strain_limiting.h), so momentum is kept; a node whose anchor to a dynamic body has a
  // force bound moves like any other (held, it would pull the body past the bound).
  scratch.weight = nodes.inverseMass;
  scratch.heldByBody.assign(nodes.size(), 0);
  auto holdsByBody = [&](const AnchorRow& row) {
    return bullet.isDynamic(row.body) && std::isinf(row.maxForce) &&
           anchorError(row, nodes.position, bullet.position(row.body), bullet.orientation(row.body)).norm() <= kHeldAnchorGap;
  };
  for (const FixedPointRow& row : rows.fixedPoints) scratch.weight[row.node] = 0.0;
  for (const AnchorRow& row : rows.anchors)  // the world's holds first: they take the reaction
    for (int k = 0; k < 4; ++k)
      if (row.weight[k] != 0.0 && !bullet.isDynamic(row.body)) scratch.weight[row.node[k]] = 0.0;
  for (const AnchorRow& row : rows.anchors)
    for (int k = 0; k < 4; ++k)
      if (row.weight[k] != 0.0 && holdsByBody(row) && scratch.weight[row.node[k]] > 0.0) {
        scratch.heldByBody[row.node[k]] = 1;
        scratch.weight[row.node[k]] = 0.0;
      }
  // Every node of a body with such rows near a shape the body touched this step is kept out of it.
  const auto bodyCount = static_cast<size_t>(bullet.rigidBodyCount());
  scratch.shapes.assign(bodyCount, CollisionRigid{});
  scratch.touched.assign(deformables.size() * bodyCount, 0);
  for (const ContactRow& row : rows.contacts)
    if (row.body >= 0) scratch.touched[deformableIndexOfNode(row.node[0]) * bodyCount + static_cast<size_t>(row.body)] = 1;
  scratch.touching.clear();
  for (size_t d = 0; d < deformables.size(); ++d) {
    if (!scratch.limitedBody[d]) continue;
    const DeformableRecord& body = deformables[d];
    // Only nodes near a shape: the passes undo one step's stretch, a few edges' worth.
    double longestEdge = 0.0;
    for (const auto& e : body.restMesh.edges)
      longestEdge = std::max(longestEdge, (body.restMesh.positions[e[1]] - body.restMesh.positions[e[0]]).norm());
    const double reach = body.collision.thickness + 5 * longestEdge;
    for (size_t b = 0; b < bodyCount; ++b) {
      if (!scratch.touched[d * bodyCount + b]) continue;
      CollisionRigid& shape = scratch.shapes[b];
      shape = {rigidShapes[b].get(), bullet.position(int(b)), bullet.orientation(int(b)), Vec3::Zero(), Vec3::Zero(), 0.0, 0.0};
      for (int32_t n = body.firstNode; n < body.firstNode + body.nodeCount; ++n) {
        if (isAnchoredPair(anchoredPairs, n, static_cast<int32_t>(b)))
          continue;  // no contact rows between them (listAnchoredPairs), so no keeping out either
        const Vec3 local = shape.orientation.conjugate() * (nodes.position[n] - shape.position);
        const geometry::ShapeDistance near = geometry::distanceToShape(*shape.shape, local, reach);
        if (near.distance < reach)
          scratch.touching.push_back({n, &shape, body.collision.thickness, !bullet.isDynamic(int(b)), near.distance,
                                      shape.orientation * near.normal});
      }
    }
  }
  // Their faces that contacts found near a round body's core, kept off it.
  scratch.faces.clear();
  for (const ContactRow& row : rows.contacts) {
    if (row.body < 0 || row.isNodeOnRigid() || row.node[1] == row.node[0] || row.node[2] == row.node[0] ||
        !scratch.limitedBody[deformableIndexOfNode(row.node[0])])
      continue;
    const CollisionRigid& shape = scratch.shapes[static_cast<size_t>(row.body)];  // set above: it touched
    const RigidShape& form = shape.shape->shape;
    if (form.type != ShapeType::Sphere && form.type != ShapeType::Capsule) continue;
    scratch.faces.push_back({{row.node[0], row.node[1], row.node[2]}, &shape,
                             form.radius + deformableOfNode(row.node[0]).collision.thickness, row.normal});
  }
  // The sheets projected together too (strain_limiting.h): surfaces without volume whose faces
  // leave some node inside them (a ribbon two nodes wide has none: it is a rope). A dynamic body
  // a sheet touches is moved with it, one more node (after the nodes), if it is a free sphere
  // touching nothing rigid: the projection moves it by translation alone and keeps its contact
  // rows' normals, which a turning box's corners do not keep (a pile of boxes on a hammock was
  // thrown), and a body moved into another would be pushed out again by Bullet. A sheet touching
  // another dynamic body, or anchored to one while it touches a moving body (a cloth hung from a
  // falling body tangled, and the projection threw it: SceneFile.WrittenAndReadBackStepsBitForBit),
  // is left to the passes: the projection would flatten its dent into the body, and the passes'
  // velocity update throw it (docs/solver.md, nineteenth session).
  scratch.sheet.assign(deformables.size(), 0);
  scratch.positions.assign(nodes.position.begin(), nodes.position.end());
  scratch.movingBodies.clear();
  scratch.movingBodyNode.assign(bodyCount, -1);
  scratch.touchesRigid.assign(bodyCount, 0);
  for (const bullet::BulletWorld::ContactPoint& point : bullet.contactPoints())
    for (int32_t b : {point.bodyA, point.bodyB})
      if (b >= 0) scratch.touchesRigid[static_cast<size_t>(b)] = 1;
  auto movable = [&](size_t b) {
    return rigid[b].inverseMass > 0.0 && !rigid[b].isJointed() && !scratch.touchesRigid[b] &&
           rigidShapes[b]->shape.type == ShapeType::Sphere;
  };
  std::vector<char>& anchored = scratch.anchoredToDynamic;
  anchored.assign(deformables.size(), 0);
  for (const AnchorRow& row : rows.anchors)
    if (holdsByBody(row)) anchored[deformableIndexOfNode(row.node[0])] = 1;
  for (size_t d = 0; d < deformables.size(); ++d) {
    bool touchesMovingBody = false, touchesUnmovedBody = false;
    for (size_t b = 0; b < bodyCount; ++b) {
      if (!scratch.touched[d * bodyCount + b] || !bullet.isDynamic(int(b))) continue;
      touchesMovingBody = true;
      touchesUnmovedBody = touchesUnmovedBody || !movable(b);
    }
    scratch.sheet[d] = scratch.limitedBody[d] && deformables[d].hasInteriorSurfaceNodes && !touchesUnmovedBody &&
                       !(anchored[d] && touchesMovingBody);
  }
  for (size_t b = 0; b < bodyCount; ++b) {
    bool touchedBySheet = false;
    for (size_t d = 0; d < deformables.size(); ++d) touchedBySheet = touchedBySheet || (scratch.sheet[d] && scratch.touched[d * bodyCount + b]);
    if (!touchedBySheet || !bullet.isDynamic(int(b))) continue;
    scratch.movingBodyNode[b] = static_cast<int32_t>(scratch.positions.size());
    scratch.movingBodies.push_back({scratch.movingBodyNode[b], &scratch.shapes[b]});
    scratch.positions.push_back(scratch.shapes[b].position);
    scratch.weight.push_back(rigid[b].inverseMass);
  }
  // Their contact rows with the sheets, as gaps linear in the positions (SheetContact): the row's
  // gap at the step's start, moved on by the nodes' and the body's motion over the step.
  scratch.sheetContacts.clear();
  for (const ContactRow& row : rows.contacts) {
    if (row.body < 0 || scratch.movingBodyNode[static_cast<size_t>(row.body)] < 0 || row.coefficient[3] != 0.0 ||
        !scratch.sheet[deformableIndexOfNode(row.node[0])])
      continue;
    SheetContact contact{{row.node[0], row.node[1], row.node[2]}, {row.coefficient[0], row.coefficient[1], row.coefficient[2]},
                         scratch.movingBodyNode[static_cast<size_t>(row.body)], row.normal, row.startGap};
    const RigidPose& start = stepStartPoses[static_cast<size_t>(row.body)];
    const Vec3 turned = (bullet.orientation(row.body) * start.orientation.conjugate()) * row.offset - row.offset;
    contact.offset += row.normal.dot(start.centerOfMass - turned);
    Vec3 moved = start.centerOfMass - bullet.position(row.body) - turned;  // the points' relative motion
    for (int k = 0; k < 3; ++k) {
      contact.offset -= row.normal.dot(row.coefficient[k] * stepStartPositions[row.node[k]]);
      moved += row.coefficient[k] * (nodes.position[row.node[k]] - stepStartPositions[row.node[k]]);
    }
    // The row's normal stands for the surfaces only while the points have moved along it more
    // than across it (a body going through the sheet); a node that slid along the body, or
    // whipped round it, has left the row's reach.
    if ((moved - row.normal * row.normal.dot(moved)).norm() > std::max(std::abs(row.normal.dot(moved)), settings.solver.contactSlop))
      continue;
    scratch.sheetContacts.push_back(contact);
  }
  scratch.edges.clear();
  for (int32_t r : scratch.rows)
    if (LimitedEdge edge; makeLimitedEdge(rows.inextensibility[r], scratch.weight, edge)) {
      for (int k = 0; k < 2; ++k)
        if (scratch.heldByBody[edge.node[k]]) {
          edge.heldByBody = edge.node[k];
          edge.movingMass = 1.0 / scratch.weight[edge.node[1 - k]];
        }
      edge.inSheet = scratch.sheet[deformableIndexOfNode(edge.node[0])];
      scratch.edges.push_back(edge);
    }
  scratch.before = scratch.positions;
  scratch.pushed.assign(nodes.size(), Vec3::Zero());
  scratch.reaction.assign(nodes.size(), Vec3::Zero());
  limitStrain(scratch.edges, scratch.touching, scratch.faces, scratch.weight, scratch.positions, scratch.pushed,
              scratch.reaction, scratch.together, scratch.heldAlong, scratch.sheetContacts,
              settings.solver.contactSlop, scratch.movingBodies);
  for (size_t n = 0; n < nodes.size(); ++n) {
    nodes.velocity[n] += (scratch.positions[n] - scratch.before[n] - scratch.pushed[n]) / timeStep;
    nodes.position[n] = scratch.positions[n];
  }
  // A body the sheets moved keeps the move and takes it as velocity, as the nodes do: its
  // momentum changes by what theirs did, the other way.
  for (const MovingBody& body : scratch.movingBodies) {
    const Vec3 move = scratch.positions[body.node] - scratch.before[body.node];
    if (move.isZero()) continue;
    const auto b = static_cast<int32_t>(body.rigid - scratch.shapes.data());
    bullet.setPose(b, bullet.position(b) + move, bullet.orientation(b));
    bullet.setLinearVelocity(b, bullet.linearVelocity(b) + move / timeStep);
    rigid[b].impulse += move / (timeStep * rigid[b].inverseMass);
  }
  for (AnchorRow& row : rows.anchors)
    for (int k = 0; k < 4; ++k)
      if (row.weight[k] != 0.0 && holdsByBody(row) && scratch.heldByBody[row.node[k]] &&
          !scratch.reaction[row.node[k]].isZero()) {
        giveReactionToBody(row, scratch.reaction[row.node[k]] / timeStep, timeStep);
        scratch.reaction[row.node[k]].setZero();  // given once, to the first anchor of the node
      }
}

// An anchored node's reaction, as an impulse J at the anchor, to its body: the velocity change
// of J (in the body's free directions), and the move of its centre of mass by that velocity
// over the step, as the passes moved the other nodes (so the centre of mass of rope and body
// moves as before the passes: python/tests/test_rope.py). Not the turn: turned as well, the
// landed teapots of rope_wheel.json kept rocking at up to 1 m/s at K = 2 (0.2 m/s without).
// A sleeping body is woken and takes the impulse alone.
void World::Impl::giveReactionToBody(AnchorRow& row, const Vec3& impulse, double h) {
  const Vec3 offset = bullet.orientation(row.body) * row.localPoint;
  RigidSolverState& body = rigid[row.body];
  body.impulse += impulse;
  body.angularImpulse += offset.cross(impulse);
  row.stepImpulse -= impulse;
  if (body.inverseMass == 0.0) {
    bullet.applyImpulse(row.body, impulse, offset);
    return;
  }
  RigidSolverState response = body;
  response.linearVelocity.setZero();
  response.angularVelocity.setZero();
  response.applyGeneralisedImpulse(impulse, offset.cross(impulse));
  bullet.setLinearVelocity(row.body, bullet.linearVelocity(row.body) + response.linearVelocity);
  bullet.setAngularVelocity(row.body, bullet.angularVelocity(row.body) + response.angularVelocity);
  bullet.setPose(row.body, bullet.position(row.body) + h * response.linearVelocity, bullet.orientation(row.body));
}

void World::Impl::separateCrossingSurfaces(double h) {
  const ImpactZoneStats stats = separateByImpactZones(collisionSurfaces(), stepStartPositions, nodes, h, impactScratch);
  report.impactZones = stats.zones;
  report.impactZoneNodes = stats.zoneNodes;
}

}  // namespace tandem
