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
  std::vector<NodePairStiffness> elastic;  // h D + h² K_e of the implicit bodies, for their blocks
  if (anyRows)
    for (const DeformableRecord& body : deformables)
      if (body.implicitStep) addImplicitStiffness(body.implicit, nodes, h, elastic);
  for (DirectBlock& block : directBlocks) block.prepare(rows, nodes, rigid, h, elastic);
  report.rowCounts = rows.countRows();
}

void World::Impl::buildDirectBlocks() {
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

void World::Impl::afterSetup() {
  bullet.loadRigidVelocities(rigid);
  SolverContext ctx = context();
  if (settings.solver.warmStart)
    rows.warmStart(ctx);
  else
    rows.clearImpulses();
  for (const DirectBlock& block : directBlocks) block.clearImpulses(rows);
  bullet.storeRigidVelocities(rigid);
}

void World::Impl::afterIteration(int) {
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

}  // namespace tandem
