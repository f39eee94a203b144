// The swept edges solved together: preconditioned conjugate gradients over a step's first
// sweeps, before the Gauss-Seidel pass over the same rows.
//
// Why. The inextensible edges no direct block holds (a cloth of thousands of rows) are swept by
// projected Gauss-Seidel, which carries a correction about one edge per sweep: a 51 × 51 cloth
// hanging over a sphere is 25 edges from its support to its hem, so after K = 4 sweeps its
// skirt still falls about 4 % further than its edges allow, every step, and the strain-limiting
// passes take that off by position (100–400 of them a step while it drapes; docs/solver.md,
// fifteenth session), feeding the difference back as velocity: a curtain hanging straight from
// rest moved at 0.04 m/s RMS. Over-relaxing the sweep carried corrections further but left a
// hanging curtain three times as agitated (its overshoot is what the next sweeps must smooth).
//
// What. The swept edge rows that are bilateral and unbounded (both sides of the row limited,
// no force bound: a plain equality) are one linear system in their impulses,
//
//   A Δλ = r,   A = J W Jᵀ (W = M⁻¹ of the nodes),   rᵢ = −(Jᵢ v + bᵢ),
//
// symmetric and positive semi-definite (definite unless rows are redundant, where conjugate
// gradients still converge in the range of A). In the first sweeps of each (sub)step
// (sweepSolvesSweptEdges), kEdgeSolveIterations steps of conjugate gradients preconditioned by a
// two-level cycle (a Gauss-Seidel pass over the rows, each row's K = wᵢ + wⱼ the diagonal whose
// inverse it keeps as its effective mass; the coarse correction over patches of uniform membrane
// stress, solver/swept_edge_coarse.h; a pass back) solve it from Δλ = 0 against the velocities
// as the sweep finds them, each iteration a product with A (Jᵀ p onto the nodes, then J back)
// and a cycle; then λ += Δλ and v += W Jᵀ Δλ. Conjugate gradients reduce the error in A's
// energy norm monotonically, over the whole sheet at once (the error after k steps is bounded by
// a Chebyshev polynomial in A's condition number), so they do not overshoot as over-relaxation
// does; the Gauss-Seidel pass that follows in the same sweep (with each edge's geometric
// stiffness) smooths what they leave and takes the bounded and one-sided rows. Every impulse is
// internal (Σ Jᵀ Δλ = 0 over an edge), so momentum is kept.
//
// Measured (`build/bench/gauntlet_study 2:1 4:1`, `tandem run scenes/cloth_sphere.json`): the
// draped 51 × 51 cloth takes 5,500 strain-limiting passes in its first 100 steps instead of
// 12,200 and costs 5.6 instead of 8.5 ms per step (4.3 instead of 5.1 over its 10 s); the
// 101 × 101 cloth 53 instead of 103 ms, its worst stretch after contact 6.8 % instead of 10.4 %
// (201 × 201: 25 % instead of 46 %); a 31 × 31 curtain pinned along its top edge hangs still
// (3·10⁻⁶ m/s RMS over its second and third second, against 0.038;
// World.SweptCurtainHangsStill). Ten iterations in the first two sweeps: ten in every sweep cost
// more for fewer passes (7.9 against 7.0 ms over the first 100 steps), twenty in the first only
// as much for more (7.8 ms), five in each of four left the curtain moving at 5·10⁻⁴ m/s; ten in
// the first sweep only is cheaper at rest (4.05 against 4.3 ms over the 10 s) but not at the
// impact (101 × 101: 64 against 52 ms, 7.9 against 6.8 % stretch). Those were with Jacobi's
// preconditioner, which carries a correction a few edges per iteration; with the two-level
// cycle (eighteenth session), three iterations: the curtain still hangs still, the 101 × 101
// cloth 4.4 % stretched (44 ms), the 201 × 201 8.2 % (357 ms), the 51 × 51 as before.
#pragma once

#include "constraints/inextensibility.h"
#include "solver/solver_state.h"
#include "solver/swept_edge_coarse.h"

#include <cmath>
#include <span>
#include <vector>

namespace tandem {

inline constexpr int kEdgeSolveSweeps = 2;       // the first sweeps of a (sub)step that run it, at most
inline constexpr int kEdgeSolveIterations = 3;   // conjugate-gradient steps in each
inline constexpr double kEdgeSolveTolerance = 1e-4;  // stop early when |r| falls by this factor

// Working memory, kept between steps so that the solve allocates nothing once grown.
struct SweptEdgeSolveScratch {
  // The equality rows among the swept edges, as the iterations read them: row index, nodes,
  // direction n (J = [−nᵀ nᵀ]), the nodes' inverse masses and the row's effective mass.
  struct Edge {
    int32_t row;
    int32_t node[2];
    Vec3 n;
    Vec3 response[2];  // W n at each end: its move per unit impulse along n
    double effectiveMass;
  };
  std::vector<Edge> edges;
  // Rows of up to four nodes after the edges (a sheet's projection has its contacts with a moving
  // body: up to three nodes of the sheet and the body's centre as a fourth): Jᵀ = jₖ at each
  // node, W jₖ its response; an unused node's j is zero.
  struct Star {
    int32_t node[4];
    Vec3 j[4];
    Vec3 response[4];
    double effectiveMass;
  };
  std::vector<Star> stars;
  std::vector<double> residual, preconditioned, direction, product, impulse;  // per row: the edges', then the stars'
  size_t rowCount() const { return edges.size() + stars.size(); }
  std::vector<Vec3> onNodes;  // W Jᵀ of a row vector, per node
  std::vector<std::array<int32_t, 2>> edgeNodes;  // the edges' nodes and directions, for the coarse level
  std::vector<Vec3> directions;
  SweptEdgeCoarseLevel coarse;
  std::vector<Vec3> smoothedOnNodes;  // W Jᵀ z of the preconditioner's z, per node
  std::vector<int32_t> rowNodes;      // the nodes the rows touch, each once (solveSweptEdgeSystem's)
  std::vector<char> touched;          // per node: scratch of finding them
};

// s.rowNodes: the nodes the rows touch, each once (what the products and the preconditioner
// clear); `nodeCount` bounds their indices.
inline void listSweptEdgeNodes(SweptEdgeSolveScratch& s, size_t nodeCount) {
  s.touched.assign(nodeCount, 0);
  s.rowNodes.clear();
  auto touch = [&](int32_t node) {
    if (!s.touched[static_cast<size_t>(node)]) s.rowNodes.push_back(node);
    s.touched[static_cast<size_t>(node)] = 1;
  };
  for (const SweptEdgeSolveScratch::Edge& e : s.edges) touch(e.node[0]), touch(e.node[1]);
  for (const SweptEdgeSolveScratch::Star& star : s.stars)
    for (int32_t node : star.node) touch(node);
}

// z = B r, the symmetric two-level cycle from z = 0: a Gauss-Seidel pass over the edges, the
// coarse correction of what it left, a pass back (Jacobi alone if the coarse factorisation
// failed). y = W Jᵀ z on the nodes, so that A z is read an edge at a time. Needs s.edges, the
// coarse level built for them, smoothedOnNodes sized to the nodes and the nodes listed
// (listSweptEdgeNodes).
inline void preconditionSweptEdges(SweptEdgeSolveScratch& s, const std::vector<double>& r, std::vector<double>& z) {
  const size_t n = s.edges.size(), m = s.rowCount();
  if (!s.coarse.factor.ready) {
    for (size_t i = 0; i < n; ++i) z[i] = s.edges[i].effectiveMass * r[i];
    for (size_t i = n; i < m; ++i) z[i] = s.stars[i - n].effectiveMass * r[i];
    return;
  }
  std::vector<Vec3>& y = s.smoothedOnNodes;
  for (int32_t node : s.rowNodes) y[node] = Vec3::Zero();
  // The edges' rows and the stars' (rows n to m), each in loops of their own: the edges' are the
  // cloth's hot path.
  auto addEdge = [&](size_t i, double delta) {
    const SweptEdgeSolveScratch::Edge& e = s.edges[i];
    z[i] += delta;
    y[e.node[0]] -= delta * e.response[0];
    y[e.node[1]] += delta * e.response[1];
  };
  auto unmetEdge = [&](size_t i) {
    const SweptEdgeSolveScratch::Edge& e = s.edges[i];
    return r[i] - e.n.dot(y[e.node[1]] - y[e.node[0]]);
  };
  auto addStar = [&](size_t i, double delta) {
    const SweptEdgeSolveScratch::Star& star = s.stars[i - n];
    z[i] += delta;
    for (int k = 0; k < 4; ++k) y[star.node[k]] += delta * star.response[k];
  };
  auto unmetStar = [&](size_t i) {
    const SweptEdgeSolveScratch::Star& star = s.stars[i - n];
    double met = 0.0;
    for (int k = 0; k < 4; ++k) met += star.j[k].dot(y[star.node[k]]);
    return r[i] - met;
  };
  std::fill(z.begin(), z.begin() + static_cast<std::ptrdiff_t>(m), 0.0);
  for (size_t i = 0; i < n; ++i) addEdge(i, unmetEdge(i) * s.edges[i].effectiveMass);
  for (size_t i = n; i < m; ++i) addStar(i, unmetStar(i) * s.stars[i - n].effectiveMass);
  // The coarse correction P A_c⁻¹ Pᵀ of what the pass left (the edges' rows only: the stars have
  // no coarse part), each edge's residual restricted as it is read and its correction added as
  // it is prolonged.
  SweptEdgeCoarseLevel& c = s.coarse;
  c.rhs.setZero();
  for (size_t i = 0; i < n; ++i) c.rhs.segment<3>(3 * c.aggregateOfEdge[i]) += unmetEdge(i) * c.basisOfEdge[i];
  c.solution = c.factor.ldlt->solve(c.rhs);
  for (size_t i = 0; i < n; ++i) addEdge(i, c.basisOfEdge[i].dot(c.solution.segment<3>(3 * c.aggregateOfEdge[i])));
  for (size_t i = m; i-- > n;) addStar(i, unmetStar(i) * s.stars[i - n].effectiveMass);
  for (size_t i = n; i-- > 0;) addEdge(i, unmetEdge(i) * s.edges[i].effectiveMass);
}

// The coarse level for s.edges: its patches made when the edges change, its matrix for their
// current directions and the nodes' weights `inverseMass`, kept while it still fits them
// (sweptEdgeCoarseFits).
inline void prepareSweptEdgeCoarse(SweptEdgeSolveScratch& s, std::span<const double> inverseMass,
                                   std::span<const Vec3> heldAlong = {}) {
  const size_t n = s.edges.size();
  s.edgeNodes.resize(n);
  s.directions.resize(n);
  for (size_t i = 0; i < n; ++i) {
    s.edgeNodes[i] = {s.edges[i].node[0], s.edges[i].node[1]};
    s.directions[i] = s.edges[i].n;
  }
  if (s.edgeNodes != s.coarse.edgeNodes) aggregateSweptEdges(s.edgeNodes, s.coarse);
  if (!sweptEdgeCoarseFits(s.directions, inverseMass, heldAlong, s.coarse))
    buildSweptEdgeCoarse(s.directions, inverseMass, heldAlong, s.coarse);
}

// A Δλ = r for the edges s.edges (A = J W Jᵀ) from Δλ = 0 into s.impulse, r given in
// s.residual: `iterations` steps of conjugate gradients preconditioned by the two-level cycle
// (their coarse level prepared), fewer once |r| has fallen by `tolerance`. `nodeCount` bounds the
// nodes' indices.
inline void solveSweptEdgeSystem(SweptEdgeSolveScratch& s, size_t nodeCount, int iterations,
                                 double tolerance = kEdgeSolveTolerance) {
  const size_t edges = s.edges.size(), n = s.rowCount();
  if (s.smoothedOnNodes.size() < nodeCount) s.smoothedOnNodes.resize(nodeCount);
  if (s.onNodes.size() < nodeCount) s.onNodes.resize(nodeCount);
  s.residual.resize(n);
  s.preconditioned.resize(n);
  s.direction.resize(n);
  s.product.resize(n);
  s.impulse.assign(n, 0.0);
  listSweptEdgeNodes(s, nodeCount);
  // out = J W Jᵀ x over the rows.
  auto multiply = [&](const std::vector<double>& x, std::vector<double>& out) {
    for (int32_t node : s.rowNodes) s.onNodes[node] = Vec3::Zero();
    for (size_t i = 0; i < edges; ++i) {
      const SweptEdgeSolveScratch::Edge& e = s.edges[i];
      s.onNodes[e.node[0]] -= x[i] * e.response[0];
      s.onNodes[e.node[1]] += x[i] * e.response[1];
    }
    for (size_t i = edges; i < n; ++i)
      for (int k = 0; k < 4; ++k) s.onNodes[s.stars[i - edges].node[k]] += x[i] * s.stars[i - edges].response[k];
    for (size_t i = 0; i < edges; ++i) {
      const SweptEdgeSolveScratch::Edge& e = s.edges[i];
      out[i] = e.n.dot(s.onNodes[e.node[1]] - s.onNodes[e.node[0]]);
    }
    for (size_t i = edges; i < n; ++i) {
      out[i] = 0.0;
      for (int k = 0; k < 4; ++k) out[i] += s.stars[i - edges].j[k].dot(s.onNodes[s.stars[i - edges].node[k]]);
    }
  };
  double rz = 0.0, start = 0.0;
  for (size_t i = 0; i < n; ++i) start += s.residual[i] * s.residual[i];
  preconditionSweptEdges(s, s.residual, s.preconditioned);
  for (size_t i = 0; i < n; ++i) {
    s.direction[i] = s.preconditioned[i];
    rz += s.residual[i] * s.preconditioned[i];
  }
  for (int iteration = 0; iteration < iterations && rz > 0.0; ++iteration) {
    multiply(s.direction, s.product);
    double curvature = 0.0;
    for (size_t i = 0; i < n; ++i) curvature += s.direction[i] * s.product[i];
    if (curvature <= 0.0) break;  // a direction in A's null space: nothing left to solve there
    const double alpha = rz / curvature;
    double next = 0.0, left = 0.0;
    for (size_t i = 0; i < n; ++i) {
      s.impulse[i] += alpha * s.direction[i];
      s.residual[i] -= alpha * s.product[i];
      left += s.residual[i] * s.residual[i];
    }
    if (left <= tolerance * tolerance * start || iteration + 1 == iterations) break;
    preconditionSweptEdges(s, s.residual, s.preconditioned);
    for (size_t i = 0; i < n; ++i) next += s.residual[i] * s.preconditioned[i];
    const double beta = next / rz;
    rz = next;
    for (size_t i = 0; i < n; ++i) s.direction[i] = s.preconditioned[i] + beta * s.direction[i];
  }
}

// Whether sweep `iteration` (from 0) of a (sub)step of K = `iterations` sweeps runs the solve: the
// first kEdgeSolveSweeps, but never the last of two or more. Three conjugate-gradient steps leave
// an error over the sheet that only a Gauss-Seidel sweep after them smooths: at K = 2 with the
// solve in both sweeps, a 31 × 31 cloth pinned along its edges bounced at 0.5 m/s RMS for ever,
// with it in the first only it hangs at 0.007 m/s after 4 s (docs/solver.md, twentieth session).
inline bool sweepSolvesSweptEdges(int iteration, int iterations) {
  return iteration < std::max(1, std::min(kEdgeSolveSweeps, iterations - 1));
}

inline void solveSweptEdgesTogether(std::span<InextensibilityRow> rows, std::span<const int32_t> swept,
                                    SolverContext& ctx, SweptEdgeSolveScratch& s) {
  // The rows' Jacobians, masses and bounds are set once per (sub)step, so the list made in its
  // first sweep serves the next.
  if (ctx.iteration == 0) {
    s.edges.clear();
    s.stars.clear();
    for (int32_t e : swept) {
      const InextensibilityRow& row = rows[static_cast<size_t>(e)];
      if (row.effectiveMass == 0.0 || !std::isinf(row.stepLambdaMin) || !std::isinf(row.stepLambdaMax)) continue;
      s.edges.push_back({e,
                         {row.node[0], row.node[1]},
                         row.jacobian[1],
                         {ctx.inverseMass[row.node[0]] * row.jacobian[1], ctx.inverseMass[row.node[1]] * row.jacobian[1]},
                         row.effectiveMass});
    }
  }
  const size_t n = s.edges.size();
  if (n == 0) return;
  // The coarse level: its patches made when the edges change, its matrix when they no longer fit it.
  if (ctx.iteration == 0) prepareSweptEdgeCoarse(s, ctx.inverseMass);
  s.residual.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const SweptEdgeSolveScratch::Edge& e = s.edges[i];
    s.residual[i] = -(rows[static_cast<size_t>(e.row)].bias + e.n.dot(ctx.velocity[e.node[1]] - ctx.velocity[e.node[0]]));
  }
  solveSweptEdgeSystem(s, ctx.velocity.size(), kEdgeSolveIterations);
  for (size_t i = 0; i < n; ++i) {
    const SweptEdgeSolveScratch::Edge& e = s.edges[i];
    rows[static_cast<size_t>(e.row)].lambda += s.impulse[i];
    ctx.velocity[e.node[0]] -= s.impulse[i] * e.response[0];
    ctx.velocity[e.node[1]] += s.impulse[i] * e.response[1];
  }
}

}  // namespace tandem
