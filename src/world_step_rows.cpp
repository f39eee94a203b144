// World::Impl, stage 4 and 5: the rows prepared, the direct blocks built, and the interleaved solve
// Bullet calls back into. (src/world.cpp runs the stages in order; src/world_impl.h holds the
// state.)
#include "world_impl.h"

namespace tandem {

void World::Impl::prepareRows(double h) {
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
  std::vector<NodePairStiffness>& elastic = implicitStiffness;  // h D + h² K_e of the implicit bodies
  elastic.clear();
  if (anyRows)
    for (const DeformableRecord& body : deformables)
      if (body.implicitStep && body.inDirectBlock) addImplicitStiffness(body.implicit, nodes, h, elastic);
  for (DirectBlock& block : directBlocks) block.prepare(rows, nodes, rigid, h, elastic);
  report.rowCounts = rows.countRows();
}

void World::Impl::buildDirectBlocks() {
  directBlocks.clear();
  for (DeformableRecord& record : deformables) record.inDirectBlock = false;
  const auto count = static_cast<int32_t>(deformables.size());
  std::vector<int32_t> group(deformables.size());
  for (int32_t d = 0; d < count; ++d) group[d] = d;
  auto root = [&](int32_t d) {
    while (group[d] != d) d = group[d] = group[group[d]];
    return d;
  };
  auto membersOf = [&](int32_t d) {
    std::vector<int32_t> members;
    for (int32_t member = 0; member < count; ++member)
      if (root(member) == d) members.push_back(member);
    return members;
  };
  auto isChain = [&](int32_t d) {
    return deformables[d].restMesh.triangles.empty() && deformables[d].restMesh.tetrahedra.empty();
  };
  enum class Role : char { Swept, Direct, Free };
  // The members' node ranges; with their roles known, only the direct ones are tied.
  auto rangesOf = [&](const std::vector<int32_t>& members, const std::vector<Role>& roles) {
    std::vector<DirectBlock::NodeRange> ranges;
    for (int32_t member : members)
      ranges.push_back({deformables[member].firstNode, deformables[member].nodeCount, isChain(member),
                        roles.empty() || roles[member] == Role::Direct});
    return ranges;
  };
  // Deformables anchored to one dynamic body are one group.
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
  // Which of those groups are solved directly; which have no rows at all (free nodes).
  std::vector<Role> role(deformables.size(), Role::Swept);
  for (int32_t d = 0; d < count; ++d) {
    if (root(d) != d) continue;
    // Ropes (no faces, no tetrahedra) are chains: their block's factorisation costs time linear
    // in their length, so they are direct at any length. Surfaces and solids fill in.
    bool forced = false, allowed = true, elastic = false, chains = true;
    const std::vector<int32_t> members = membersOf(d);
    for (int32_t member : members) {
      const DeformableRecord& record = deformables[member];
      forced |= record.rowSolver == RowSolverKind::Direct;
      allowed &= record.rowSolver != RowSolverKind::Iterative;
      elastic |= record.implicitStep;
      chains &= isChain(member);
    }
    if (!allowed) continue;
    DirectBlock block(rangesOf(members, {}));
    block.collectRows(rows);
    const int32_t rowCount = block.scalarRowCount();
    // An elastic body's model carries what rests on it (models/supports.h), so without rows of
    // its own it is swept, not free nodes for another block to take.
    const Role groupRole = (forced && elastic) || (rowCount > 0 && (forced || chains || rowCount <= kAutoDirectRowLimit))
                               ? Role::Direct
                               : (rowCount == 0 && !elastic ? Role::Free : Role::Swept);
    for (int32_t member : members) role[member] = groupRole;
  }
  // Direct groups touching one dynamic body at the step's start are one block, with the bodies
  // of free nodes touching it: solved apart, in turns, each held the body up alone and they never
  // agreed within K iterations (a bar resting on four jellies, when they were blocks, rocked and
  // slid on them at 0.4 mm/s, docs/solver.md).
  for (size_t first = 0, end; first < bodyContacts.size(); first = end) {
    int32_t direct = -1;
    for (end = first; end < bodyContacts.size() && bodyContacts[end].first == bodyContacts[first].first; ++end)
      if (direct < 0 && role[bodyContacts[end].second] == Role::Direct) direct = bodyContacts[end].second;
    if (direct < 0) continue;
    for (size_t i = first; i < end; ++i)
      if (role[bodyContacts[i].second] != Role::Swept) group[root(bodyContacts[i].second)] = root(direct);
  }
  for (int32_t d = 0; d < count; ++d) {
    if (root(d) != d) continue;
    const std::vector<int32_t> members = membersOf(d);
    if (std::none_of(members.begin(), members.end(), [&](int32_t m) { return role[m] == Role::Direct; })) continue;
    DirectBlock block(rangesOf(members, role));
    block.collectRows(rows);
    block.claimRows(rows);
    directBlocks.push_back(std::move(block));
    for (int32_t member : members) deformables[member].inDirectBlock = true;
  }
  rows.colourSweptEdges(nodes.size());
  directBlocksStale = false;
}

void World::Impl::afterSetup() {
  bullet.loadRigidVelocities(rigid);
  sweepStartVelocity = nodes.velocity;
  SolverContext ctx = context();
  if (settings.solver.warmStart)
    rows.warmStart(ctx);
  else
    rows.clearImpulses();
  for (DirectBlock& block : directBlocks) block.startImpulses(rows, ctx);
  bullet.storeRigidVelocities(rigid);
}

void World::Impl::afterIteration(int iteration) {
  bullet.loadRigidVelocities(rigid);
  SolverContext ctx = context();
  ctx.iteration = iteration;
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

}  // namespace tandem
