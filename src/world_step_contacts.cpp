// World::Impl, stage 3: deformable contacts found once per step, remembered for warm starting and
// the supports; sleep of the bodies deformables hold. (src/world.cpp runs the stages in order;
// src/world_impl.h holds the state.)
#include "world_impl.h"

namespace tandem {

std::span<const CollisionSurface> World::Impl::collisionSurfaces() {
  std::vector<CollisionSurface>& surfaces = surfaceScratch;
  surfaces.clear();
  for (const DeformableRecord& body : deformables) {
    if (!body.collision.enabled) continue;
    surfaces.push_back({body.firstNode, body.nodeCount, body.surfaceNodes, body.surfaceTriangles,
                        body.surfaceEdges, body.restMesh.positions, body.collision.thickness,
                        body.collision.friction, body.collision.selfCollision, body.collision.group,
                        body.collision.mask});
  }
  return surfaces;
}

// The node-body pairs that do not collide: a node anchored to a body, and the nodes one edge away
// from it (as Bullet leaves out the contacts of bodies a joint links). An anchor holds its point
// on the body's surface, so its face's neighbours lie within the sheet's thickness of the body:
// their contacts with it pushed a flag's hem out of its weight's capsule, against the anchor's
// hold on the face beside them, and stretched the hem 15 → 40 % (scenes/anchors.json).
void World::Impl::listAnchoredPairs() {
  anchoredPairs.clear();
  for (const AnchorRow& row : rows.anchors)
    for (int k = 0; k < 4; ++k)
      if (row.weight[k] != 0.0) anchoredPairs.push_back(nodeBodyKey(row.node[k], row.body));
  std::sort(anchoredPairs.begin(), anchoredPairs.end());
  // A node's keys are contiguous in the sorted list, from nodeBodyKey(node, 0) up.
  auto bodiesHolding = [&](int32_t node, auto visit) {
    const uint64_t first = nodeBodyKey(node, 0), end = nodeBodyKey(node + 1, 0);
    for (auto it = std::lower_bound(anchoredPairs.begin(), anchoredPairs.end(), first); it != anchoredPairs.end() && *it < end; ++it)
      visit(static_cast<int32_t>(*it - first));
  };
  anchoredNeighbours.clear();
  anchoredDeformables.assign(deformables.size(), 0);
  for (const AnchorRow& row : rows.anchors) anchoredDeformables[deformableIndexOfNode(row.node[0])] = 1;
  for (size_t d = 0; d < deformables.size(); ++d) {
    if (!anchoredDeformables[d]) continue;
    const DeformableRecord& body = deformables[d];
    for (const auto* edges : {&body.restMesh.edges, &body.restMesh.shearEdges})
      for (const auto& e : *edges) {
        const int32_t a = body.firstNode + e[0], b = body.firstNode + e[1];
        bodiesHolding(a, [&](int32_t rigidBody) { anchoredNeighbours.push_back(nodeBodyKey(b, rigidBody)); });
        bodiesHolding(b, [&](int32_t rigidBody) { anchoredNeighbours.push_back(nodeBodyKey(a, rigidBody)); });
      }
  }
  anchoredPairs.insert(anchoredPairs.end(), anchoredNeighbours.begin(), anchoredNeighbours.end());
  std::sort(anchoredPairs.begin(), anchoredPairs.end());
  anchoredPairs.erase(std::unique(anchoredPairs.begin(), anchoredPairs.end()), anchoredPairs.end());
}

void World::Impl::detectDeformableContacts(double h) {
  const std::span<const CollisionSurface> surfaces = collisionSurfaces();
  std::vector<CollisionRigid>& shapes = contactShapes;
  shapes.resize(static_cast<size_t>(bullet.rigidBodyCount()));
  for (int b = 0; b < bullet.rigidBodyCount(); ++b)
    shapes[b] = {rigidShapes[b].get(),        bullet.position(b),        bullet.orientation(b),
                 bullet.linearVelocity(b),    bullet.angularVelocity(b), rigidFriction[b],
                 bullet.mass(b),              rigidGroup[b],             rigidMask[b]};
  listAnchoredPairs();
  rows.contacts.clear();
  detectContacts(surfaces, nodes, shapes, anchoredPairs, h, rows.contacts, contactScratch);
  for (ContactRow& row : rows.contacts) {
    row.startGap = row.gap;
    row.startOffset = row.offset;
  }
  // Warm start from last step's impulse on the same feature, friction kept in the new plane.
  for (ContactRow& row : rows.contacts) {
    const ContactImpulse* previous = previousContact(row.key);
    if (!previous) continue;
    row.lambdaNormal = previous->normal;
    row.warmFriction = previous->friction;
    row.releasedLastStep = previous->releasedFromBlock;
  }
  // A node its model held on a support carries that load there too: it bounds the friction of
  // its contact with that body (its first, where one node touches the body at several points).
  supportAssigned.assign(nodes.size(), 0);
  for (ContactRow& row : rows.contacts) {
    if (!row.isNodeOnRigid() || supportAssigned[row.node[0]]) continue;
    const DeformableRecord& body = deformables[deformableIndexOfNode(row.node[0])];
    const auto i = static_cast<size_t>(row.node[0] - body.firstNode);
    if (body.supports.holdBody.size() <= i || body.supports.holdBody[i] != row.body) continue;
    // What the hold spent of its cone along the surface is not the row's to spend again.
    const Vec3& hold = body.supports.holdImpulse[i];
    const double pushing = hold.dot(row.normal);
    const double spent = row.friction > 0.0 ? (hold - pushing * row.normal).norm() / row.friction : 0.0;
    row.supportImpulse = std::max(0.0, pushing - spent) / settings.solver.substeps;
    supportAssigned[row.node[0]] = 1;
  }
  noteBodyContacts();
  rows.colourContacts(nodes.size(), static_cast<size_t>(bullet.rigidBodyCount()),
                      [&](int32_t body) { return bullet.isDynamic(body); });
}

void World::Impl::noteBodyContacts() {
  std::vector<std::pair<int32_t, int32_t>>& pairs = bodyContactsScratch;
  pairs.clear();
  for (const ContactRow& row : rows.contacts) {
    const bool touching = row.gap <= settings.solver.contactSlop || row.lambdaNormal > 0.0;
    if (row.body >= 0 && touching && bullet.isDynamic(row.body))
      pairs.emplace_back(row.body, static_cast<int32_t>(deformableIndexOfNode(row.node[0])));
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  if (pairs == bodyContacts) return;
  std::swap(bodyContacts, pairs);
  directBlocksStale = true;
}

const ContactImpulse* World::Impl::previousContact(uint64_t key) const {
  const auto beforeEntry = [](uint64_t k, const std::pair<uint64_t, ContactImpulse>& entry) { return k < entry.first; };
  const auto after = std::upper_bound(previousContacts.begin(), previousContacts.end(), key, beforeEntry);
  if (after == previousContacts.begin() || std::prev(after)->first != key) return nullptr;
  return &std::prev(after)->second;  // the last of equal keys, as a map assigned in row order kept
}

void World::Impl::setPreviousContacts() {
  // By key, equal keys in row order (std::stable_sort would allocate its buffer), sorted as
  // (key, row) pairs side by side rather than rows reached through an index.
  std::vector<std::pair<uint64_t, uint32_t>>& order = previousContactOrder;
  order.resize(rows.contacts.size());
  for (uint32_t i = 0; i < order.size(); ++i) order[i] = {rows.contacts[i].key, i};
  std::sort(order.begin(), order.end());
  previousContacts.clear();
  for (const auto& [key, i] : order) {
    const ContactRow& row = rows.contacts[i];
    previousContacts.push_back(
        {row.key, {row.lambdaNormal, row.impulse() - row.lambdaNormal * row.normal, row.releasedFromBlock}});
  }
}

void World::Impl::rememberContacts() {
  setPreviousContacts();
  addHoldImpulsesToSupports();
  rememberSupports();
}

void World::Impl::addHoldImpulsesToSupports() {
  for (const DeformableRecord& body : deformables)
    for (size_t i = 0; i < body.supports.holdBody.size(); ++i)
      if (body.supports.holdBody[i] >= 0) rigid[body.supports.holdBody[i]].impulse -= body.supports.holdImpulse[i];
}

void World::Impl::rememberSupports() {
  for (DeformableRecord& body : deformables) body.supports.reset(body.firstNode, body.nodeCount);
  const SolverContext ctx = context();
  for (const ContactRow& row : rows.contacts) {
    if (!row.isNodeOnRigid()) continue;
    const Vec3 surfaceVelocity = rigid[row.body].velocityAt(row.offset);
    const double surfaceSpeed = row.normal.dot(surfaceVelocity);
    const Vec3 relative = contactRelativeVelocity(row, ctx);
    const double gapAtEnd = row.gap + substepLength * row.normal.dot(relative);
    DeformableRecord& body = deformables[deformableIndexOfNode(row.node[0])];
    if (rigid[row.body].inverseMass == 0.0) {
      // Its friction is the implicit solve's, but not where a direct block solves the body's rows
      // (its contacts' friction there is the block's, in the same metric).
      if (!body.supports.add(row.node[0], row.body, row.normal, gapAtEnd, surfaceSpeed) || !body.implicitStep ||
          body.inDirectBlock || row.friction <= 0.0)
        continue;
      // The step's push on the node: its hold's (in holdImpulse until the next models stage) and its row's.
      const auto i = static_cast<size_t>(row.node[0] - body.firstNode);
      const bool held = i < body.supports.holdBody.size() && body.supports.holdBody[i] == row.body;
      const Vec3 hold = held ? body.supports.holdImpulse[i] : Vec3::Zero();
      const double holdPush = hold.dot(row.normal);
      body.supports.addFriction(row.node[0], row.friction, surfaceVelocity - surfaceSpeed * row.normal,
                                relative - relative.dot(row.normal) * row.normal, row.stepNormalImpulse + holdPush,
                                hold - holdPush * row.normal, held && body.supports.holdSlid[i]);
      continue;
    }
    // A dynamic body is a moving support of the swept implicit bodies that pressed on it last step.
    if (!body.implicitStep || body.inDirectBlock || rigid[row.body].isJointed() ||
        row.lambdaNormal + row.supportImpulse <= 0.0)
      continue;
    body.supports.addMoving(row.node[0], row.body, row.normal, gapAtEnd, surfaceSpeed, row.offset);
  }
}

void World::Impl::manageSleepOfHeldBodies() {
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

}  // namespace tandem
