// All of Tandem's rows, in contiguous arrays by type, and the three things the solver does
// with them: prepare (Jacobians, effective masses, biases, bounds), warm start, and sweep.
#pragma once

#include <tandem/report.h>

#include "constraints/anchor.h"
#include "constraints/bending.h"
#include "constraints/contact.h"
#include "constraints/fixed_point.h"
#include "constraints/grab.h"
#include "constraints/inextensibility.h"
#include "solver/graph_colouring.h"
#include "solver/solver_state.h"
#include "solver/swept_edge_solve.h"

#include <vector>

namespace tandem {

struct ConstraintRows {
  std::vector<FixedPointRow> fixedPoints;
  std::vector<AnchorRow> anchors;
  std::vector<InextensibilityRow> inextensibility;
  std::vector<BendingRow> bending;
  std::vector<ContactRow> contacts;  // found anew every step
  std::vector<GrabRow> grabs;        // inactive ones are released slots

  // Contacts sorted by colour (solver/graph_colouring.h): a colour's contacts share no node or
  // dynamic body.
  ColourRanges contactColours;

  // After contact detection, every step. `isDynamic(body)`: whether a body's velocity is written.
  template <class IsDynamic>
  void colourContacts(size_t nodeCount, size_t bodyCount, IsDynamic isDynamic) {
    contactColours = colourRows(
        contacts, nodeCount + bodyCount,
        [&](const ContactRow& row, auto add) {
          for (int k = 0; k < 4; ++k)
            if (row.coefficient[k] != 0.0) add(static_cast<size_t>(row.node[k]));
          if (row.body >= 0 && isDynamic(row.body)) add(nodeCount + static_cast<size_t>(row.body));
        },
        m_colouring, m_contactOrder, m_sortedContacts);
  }

  // The swept inextensibility rows (those no direct block holds) as an index list sorted by
  // colour: a colour's edges share no node. Built with the direct blocks, which decide which
  // edges are swept (the rows do not change between). Bending rows are swept in the order they
  // were made: sorted the same way, a 6 m/s ball dropped on a pinned cloth gained energy
  // 76-fold (docs/solver.md, tenth session).
  std::vector<int32_t> sweptEdges;
  ColourRanges sweptEdgeColours;

  void colourSweptEdges(size_t nodeCount) {
    sweptEdgeColours = colourIndices(
        inextensibility, [](const InextensibilityRow& row) { return !row.inDirectBlock; }, nodeCount,
        [](const InextensibilityRow& row, auto add) {
          for (int32_t node : row.node) add(static_cast<size_t>(node));
        },
        sweptEdges, m_colouring);
  }

  // Scalar rows per type (a fixed point or an anchor is three; friction two per contact).
  std::array<int, static_cast<size_t>(RowType::Count)> countRows() const {
    int friction = 0;
    for (const ContactRow& row : contacts) friction += row.friction > 0 ? 2 : 0;
    int grabRows = 0;
    for (const GrabRow& row : grabs) grabRows += row.active ? 3 : 0;
    return {3 * static_cast<int>(fixedPoints.size()), 3 * static_cast<int>(anchors.size()),
            static_cast<int>(inextensibility.size()), static_cast<int>(bending.size()),
            static_cast<int>(contacts.size()), friction, grabRows};
  }

  void prepare(const NodeArrays& nodes, std::span<const RigidSolverState> rigid, const Vec3& gravity,
               double timeStep, double biasRate, double contactSlop) {
    for (FixedPointRow& row : fixedPoints) prepareFixedPoint(row, nodes, timeStep, biasRate);
    for (AnchorRow& row : anchors) prepareAnchor(row, nodes, rigid[row.body], timeStep, biasRate);
    for (InextensibilityRow& row : inextensibility) prepareInextensibility(row, nodes, timeStep, biasRate);
    for (BendingRow& row : bending) prepareBending(row, nodes, timeStep, biasRate);
    for (ContactRow& row : contacts)
      prepareContact(row, nodes.velocity, nodes.inverseMass, rigid, gravity, timeStep, biasRate, contactSlop);
    for (GrabRow& row : grabs)
      if (row.active) prepareGrab(row, nodes, rigid, timeStep);
  }

  // Rows in a direct block are not warm started here: the block is exact in one sweep, and its
  // response to an impulse (H⁻¹ Jᵀ) is not the M⁻¹ Jᵀ a warm start would apply. Its anchors to
  // dynamic bodies are, by the block itself (DirectBlock::startImpulses).
  void warmStart(SolverContext& ctx) const {
    for (const FixedPointRow& row : fixedPoints)
      if (!row.inDirectBlock) warmStartFixedPoint(row, ctx);
    for (const AnchorRow& row : anchors)
      if (!row.inDirectBlock) warmStartAnchor(row, ctx);
    for (const InextensibilityRow& row : inextensibility)
      if (!row.inDirectBlock) warmStartInextensibility(row, ctx);
    for (const BendingRow& row : bending) warmStartBending(row, ctx);
    for (const ContactRow& row : contacts) warmStartContact(row, ctx);  // a block's contacts come in at 0
    for (const GrabRow& row : grabs)
      if (row.active) warmStartGrab(row, ctx);
  }

  void clearImpulses() {
    for (FixedPointRow& row : fixedPoints) row.lambda.setZero();
    for (AnchorRow& row : anchors) row.lambda.setZero();
    for (InextensibilityRow& row : inextensibility) row.lambda = 0.0;
    for (BendingRow& row : bending) row.lambda = 0.0;
    for (ContactRow& row : contacts) {
      row.lambdaNormal = 0.0;
      row.lambdaTangent.setZero();
    }
    for (GrabRow& row : grabs) row.lambda.setZero();
  }

  // One projected Gauss-Seidel sweep over every row not in a direct block (each swept edge with
  // its geometric stiffness, constraints/inextensibility.h), the swept equality edges solved
  // together first in a (sub)step's first sweeps (solver/swept_edge_solve.h). The fixed points
  // come after the edges and bending rows, so that a sweep leaves its pinned nodes at their
  // targets' velocity: solved first, the edges after them pulled them along, and a cloth pinned
  // along its sides sagged its pins by 0.7–1.4 cm, which the strain-limiting passes (holding
  // pinned nodes where they are) kept, its edges 8–16 % long
  // (World.SweptClothPinnedAlongItsSidesHoldsItsPins).
  void sweep(SolverContext& ctx, FrictionModel friction, SweepStats& stats) {
    for (GrabRow& row : grabs)
      if (row.active) solveGrab(row, ctx, stats);
    if (sweepSolvesSweptEdges(ctx.iteration, ctx.iterations))
      solveSweptEdgesTogether(inextensibility, sweptEdges, ctx, m_sweptEdgeSolve);
    for (int32_t r : sweptEdges) solveSweptEdge(inextensibility[static_cast<size_t>(r)], ctx, stats);
    for (BendingRow& row : bending) solveBending(row, ctx, stats);
    for (FixedPointRow& row : fixedPoints)
      if (!row.inDirectBlock) solveFixedPoint(row, ctx, stats);
    for (AnchorRow& row : anchors)
      if (!row.inDirectBlock) solveAnchor(row, ctx, stats);
    for (ContactRow& row : contacts)
      if (!row.inDirectBlock) solveContactNormal(row, ctx, stats);
    for (ContactRow& row : contacts)
      if (!row.frictionInBlock) solveContactFriction(row, friction, ctx, stats);
  }

  // The contacts no direct block holds, once more after the blocks: a block knows nothing of
  // them (cloth on cloth links two blocks), and surfaces must not end a sweep interpenetrating.
  // (Friction is not repeated here: the blocks' projection would keep the rigid side of a
  // second friction impulse and drop the cloth's, feeding energy into a body resting on cloth.)
  void sweepFreeContacts(SolverContext& ctx, SweepStats& stats, bool betweenDeformablesOnly = false) {
    for (ContactRow& row : contacts)
      if (!row.inDirectBlock && !(betweenDeformablesOnly && row.body >= 0)) solveContactNormal(row, ctx, stats);
  }

 private:
  SweptEdgeSolveScratch m_sweptEdgeSolve;
  ColouringScratch m_colouring;
  std::vector<int32_t> m_contactOrder;
  std::vector<ContactRow> m_sortedContacts;
};

}  // namespace tandem
