// The coarse level of the swept edges' solve: a two-level preconditioner for the conjugate
// gradients of solver/swept_edge_solve.h.
//
// Why. The swept edges' system A Δλ = r (A = J W Jᵀ over the inextensible edges of a sheet) is a
// Laplacian in disguise: its condition number grows as the square of the sheet's width in edges,
// and Jacobi-preconditioned conjugate gradients carry a correction a few edges per iteration. A
// 101 × 101 cloth draped on a sphere was left 6.8 % stretched after ten iterations, a 201 × 201
// 25 %, and the strain-limiting passes took the rest by position (docs/solver.md).
//
// What. The errors that iterations over single edges leave are smooth tension fields: impulses
// that vary slowly over the sheet. Within a patch of the sheet such a field is close to a uniform
// membrane stress σ (2 × 2, symmetric, in the patch's plane), under which an edge along the unit
// direction n carries λ = nᵀ σ n. So the nodes are grouped into patches (aggregates: a node and
// its neighbours, then those groups grouped again the same way; about 40 nodes each on a grid),
// each patch gets the three stresses of its plane as coarse unknowns (σ₁₁, σ₂₂, σ₁₂ in the frame
// of the patch's two principal edge directions), and P maps them to the edges:
// P(e, (a, k)) = qₖ(nₑ) for an edge e of patch a, q = ((n·t₁)², (n·t₂)², 2 (n·t₁)(n·t₂)). The
// coarse matrix is Galerkin's, A_c = Pᵀ A P, assembled through the nodes (A = J W Jᵀ, so
// A_c = Σ_nodes w Gᵀ G with G = Jᵀ P at the node) by solver/sparse_assembly.h (one pass over the
// values while the patches stay) and factorised by sparse LDLᵀ whenever it is built: in a
// (sub)step whose edges no longer fit the level kept from an earlier one (sweptEdgeCoarseFits;
// Eigen's numeric factorisation allocates its working copy of the matrix: one small allocation a
// build). The preconditioner is the symmetric two-level cycle (solver/swept_edge_solve.h): a
// Gauss-Seidel pass over the edges, the coarse correction P A_c⁻¹ Pᵀ of what it left, a pass
// back; symmetric and positive definite, so conjugate gradients apply. On a 61 × 61 sheet hanging from one row it cuts the iterations to a part in
// 10⁶ to a third of Jacobi's (154 against 458; tests/test_swept_edge_coarse.cpp): patches of
// uniform stress interpolate a smooth field piecewise, so the coarse level is not exact there.
//
// Measured (`GAUNTLET_ONLY=cloth build/bench/gauntlet_study 4:1`, three iterations of the cycle
// against ten of Jacobi's; docs/solver.md, eighteenth session): worst stretch after contact on
// the sphere 51 × 51 2.6 % either way (what is left there is not the edges' solve), 101 × 101
// 4.4 % against 6.8 % (44 against 52 ms per step), 201 × 201 8.2 % against 25 % (357 against
// 400 ms). The additive B = D⁻¹ + P A_c⁻¹ Pᵀ did as well in the scenes with eight iterations
// but not on the sheet above (489 iterations against Jacobi's 458); two iterations of the cycle
// left a hanging curtain moving (World.SweptCurtainHangsStill); patches of five nodes (one round
// of aggregation) cost more for no less stretch.
#pragma once

#include "solver/solver_state.h"
#include "solver/sparse_assembly.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace tandem {

struct SweptEdgeCoarseLevel {
  // The aggregation, made again when the swept edges change.
  std::vector<std::array<int32_t, 2>> edgeNodes;  // what it was made for
  std::vector<int32_t> aggregateOfEdge;
  int32_t aggregateCount = 0;
  // Per node of the edges, the patches whose edges touch it (slots), and each edge's slots.
  std::vector<int32_t> slotAggregate, slotNode;
  std::vector<std::array<int32_t, 2>> slotOfEdge;
  std::vector<std::array<int32_t, 2>> slotPairs;  // slots at the same node, each pair once (s ≤ t)
  // Per build (kept while it fits the edges: sweptEdgeCoarseFits)
  std::vector<Mat3> spread;                // per patch: Σ n nᵀ over its edges
  std::vector<std::array<Vec3, 2>> frame;  // per patch: t₁, t₂
  std::vector<Vec3> basisOfEdge;           // q(nₑ) in its patch's frame
  std::vector<Mat3> slotImage;             // G = Jᵀ P at the slot's node, for the slot's patch
  std::vector<Eigen::Triplet<double>> entries;  // A_c's lower triangle, its blocks in the slot pairs' order
  std::vector<double> values;                   // their values alone, once placed
  bool entriesPlaced = false;                   // assembled once with these patches
  SparseAssembly assembly{SparseAssembly::Part::LowerTriangle};  // of entries into matrix
  // A_c (its lower triangle) and its factorisation. A copy (a world's snapshot) factorises the
  // copied matrix again, which gives the same factors: the level is kept from step to step
  // (sweptEdgeCoarseFits), so a restored world must go on with the one the original had.
  struct Factor {
    Eigen::SparseMatrix<double> matrix;
    std::unique_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>> ldlt =
        std::make_unique<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>();
    bool analysed = false;
    bool ready = false;  // factorised
    void factorise(bool newPattern) {
      if (newPattern || !analysed) {
        ldlt->analyzePattern(matrix);
        analysed = true;
      }
      ldlt->factorize(matrix);
      ready = ldlt->info() == Eigen::Success;
    }
    Factor() = default;
    Factor(const Factor& other) : matrix(other.matrix) {
      if (other.ready) factorise(true);
    }
    Factor& operator=(const Factor& other) {
      if (this != &other) *this = Factor(other);
      return *this;
    }
    Factor(Factor&&) = default;
    Factor& operator=(Factor&&) = default;
  } factor;
  Eigen::VectorXd rhs, solution;
  // What the factorisation was built for: each edge's direction, and each slot node's weight and
  // held direction (sweptEdgeCoarseFits).
  std::vector<Vec3> builtDirection;
  std::vector<double> builtWeight;
  std::vector<Vec3> builtHeldAlong;
};

namespace swept_edge_coarse_detail {

// Greedy aggregation of a graph in compressed rows: a vertex whose neighbours are all free takes
// them; vertices left over join a neighbouring group; isolated ones are their own.
inline int32_t aggregate(const std::vector<int32_t>& start, const std::vector<int32_t>& adjacent,
                         std::vector<int32_t>& group) {
  const auto count = static_cast<int32_t>(start.size()) - 1;
  group.assign(static_cast<size_t>(count), -1);
  int32_t groups = 0;
  for (int32_t v = 0; v < count; ++v) {
    if (group[v] >= 0) continue;
    bool free = true;
    for (int32_t k = start[v]; k < start[v + 1] && free; ++k) free = group[adjacent[k]] < 0;
    if (!free) continue;
    group[v] = groups;
    for (int32_t k = start[v]; k < start[v + 1]; ++k) group[adjacent[k]] = groups;
    ++groups;
  }
  for (int32_t v = 0; v < count; ++v) {
    if (group[v] >= 0) continue;
    for (int32_t k = start[v]; k < start[v + 1] && group[v] < 0; ++k)
      if (group[adjacent[k]] >= 0) group[v] = group[adjacent[k]];
    if (group[v] < 0) group[v] = groups++;
  }
  return groups;
}

// The graph of `group`'s groups, from a graph of its vertices.
inline void groupGraph(const std::vector<int32_t>& start, const std::vector<int32_t>& adjacent,
                       const std::vector<int32_t>& group, int32_t groups, std::vector<int32_t>& groupStart,
                       std::vector<int32_t>& groupAdjacent) {
  std::vector<std::pair<int32_t, int32_t>> links;
  const auto count = static_cast<int32_t>(start.size()) - 1;
  for (int32_t v = 0; v < count; ++v)
    for (int32_t k = start[v]; k < start[v + 1]; ++k)
      if (group[v] != group[adjacent[k]]) links.emplace_back(group[v], group[adjacent[k]]);
  std::sort(links.begin(), links.end());
  links.erase(std::unique(links.begin(), links.end()), links.end());
  groupStart.assign(static_cast<size_t>(groups) + 1, 0);
  for (const auto& link : links) ++groupStart[link.first + 1];
  for (int32_t g = 0; g < groups; ++g) groupStart[g + 1] += groupStart[g];
  groupAdjacent.resize(links.size());
  for (size_t k = 0; k < links.size(); ++k) groupAdjacent[k] = links[k].second;
}

}  // namespace swept_edge_coarse_detail

// Patches for the edges (each given as its two nodes), and the slots the assembly reads.
inline void aggregateSweptEdges(const std::vector<std::array<int32_t, 2>>& edgeNodes, SweptEdgeCoarseLevel& c) {
  using namespace swept_edge_coarse_detail;
  c.edgeNodes = edgeNodes;
  // The edges' nodes, numbered locally.
  std::vector<int32_t> nodes;
  for (const auto& e : edgeNodes) nodes.insert(nodes.end(), {e[0], e[1]});
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  auto local = [&](int32_t node) {
    return static_cast<int32_t>(std::lower_bound(nodes.begin(), nodes.end(), node) - nodes.begin());
  };
  const auto nodeCount = static_cast<int32_t>(nodes.size());
  std::vector<int32_t> start(static_cast<size_t>(nodeCount) + 1, 0), adjacent(2 * edgeNodes.size());
  for (const auto& e : edgeNodes) {
    ++start[local(e[0]) + 1];
    ++start[local(e[1]) + 1];
  }
  for (int32_t v = 0; v < nodeCount; ++v) start[v + 1] += start[v];
  std::vector<int32_t> fill(start.begin(), start.end() - 1);
  for (const auto& e : edgeNodes) {
    const int32_t a = local(e[0]), b = local(e[1]);
    adjacent[fill[a]++] = b;
    adjacent[fill[b]++] = a;
  }
  // Two rounds: a node and its neighbours, then such groups and their neighbouring groups.
  std::vector<int32_t> first, second, groupStart, groupAdjacent;
  const int32_t firstCount = aggregate(start, adjacent, first);
  groupGraph(start, adjacent, first, firstCount, groupStart, groupAdjacent);
  c.aggregateCount = aggregate(groupStart, groupAdjacent, second);
  std::vector<int32_t> patchOfNode(static_cast<size_t>(nodeCount));
  for (int32_t v = 0; v < nodeCount; ++v) patchOfNode[v] = second[first[v]];
  // Each edge belongs to its first node's patch.
  c.aggregateOfEdge.resize(edgeNodes.size());
  for (size_t e = 0; e < edgeNodes.size(); ++e) c.aggregateOfEdge[e] = patchOfNode[local(edgeNodes[e][0])];
  // Slots: the distinct (node, patch) pairs the edges make.
  std::vector<std::array<int32_t, 3>> pairs;  // (local node, patch, edge * 2 + end)
  for (size_t e = 0; e < edgeNodes.size(); ++e)
    for (int end = 0; end < 2; ++end)
      pairs.push_back({local(edgeNodes[e][end]), c.aggregateOfEdge[e], static_cast<int32_t>(2 * e) + end});
  std::sort(pairs.begin(), pairs.end());
  c.slotAggregate.clear();
  c.slotNode.clear();
  c.slotOfEdge.assign(edgeNodes.size(), {0, 0});
  for (size_t k = 0; k < pairs.size(); ++k) {
    if (k == 0 || pairs[k][0] != pairs[k - 1][0] || pairs[k][1] != pairs[k - 1][1]) {
      c.slotAggregate.push_back(pairs[k][1]);
      c.slotNode.push_back(nodes[pairs[k][0]]);
    }
    c.slotOfEdge[pairs[k][2] / 2][pairs[k][2] % 2] = static_cast<int32_t>(c.slotAggregate.size()) - 1;
  }
  c.slotPairs.clear();
  for (size_t s = 0; s < c.slotNode.size();) {
    size_t end = s;
    while (end < c.slotNode.size() && c.slotNode[end] == c.slotNode[s]) ++end;
    for (size_t a = s; a < end; ++a)
      for (size_t b = a; b < end; ++b) c.slotPairs.push_back({static_cast<int32_t>(a), static_cast<int32_t>(b)});
    s = end;
  }
  c.factor.analysed = false;
  c.factor.ready = false;
  c.entriesPlaced = false;
}

// The coarse matrix for the edges' current directions, factorised. `direction[e]` is edge e's n,
// `inverseMass` the nodes' w (indexed by global node).
inline void buildSweptEdgeCoarse(const std::vector<Vec3>& direction, std::span<const double> inverseMass,
                                 std::span<const Vec3> heldAlong, SweptEdgeCoarseLevel& c) {
  const size_t edges = direction.size();
  // Each patch's plane: the two largest principal directions of its edges' n nᵀ.
  std::vector<Mat3>& spread = c.spread;
  spread.assign(static_cast<size_t>(c.aggregateCount), Mat3::Zero());
  for (size_t e = 0; e < edges; ++e) spread[c.aggregateOfEdge[e]] += direction[e] * direction[e].transpose();
  std::vector<std::array<Vec3, 2>>& frame = c.frame;
  frame.resize(spread.size());
  for (size_t a = 0; a < spread.size(); ++a) {
    Eigen::SelfAdjointEigenSolver<Mat3> eigen(spread[a]);
    frame[a] = {eigen.eigenvectors().col(2), eigen.eigenvectors().col(1)};
  }
  c.basisOfEdge.resize(edges);
  c.slotImage.assign(c.slotAggregate.size(), Mat3::Zero());
  for (size_t e = 0; e < edges; ++e) {
    const auto& [t1, t2] = frame[c.aggregateOfEdge[e]];
    const double a = direction[e].dot(t1), b = direction[e].dot(t2);
    c.basisOfEdge[e] = Vec3(a * a, b * b, 2 * a * b);
    const Mat3 image = direction[e] * c.basisOfEdge[e].transpose();  // Jᵀ of the edge's columns at node 1
    c.slotImage[c.slotOfEdge[e][0]] -= image;
    c.slotImage[c.slotOfEdge[e][1]] += image;
  }
  // A_c = Σ over nodes of w Gᵀ G, block by block, its lower triangle (all LDLᵀ reads); its
  // pattern stays while the patches do, so after the first assembly with them only the values
  // are written, in the same order.
  const int32_t size = 3 * c.aggregateCount;
  const bool placed = c.entriesPlaced;
  c.entries.clear();
  c.values.clear();
  auto add = [&](int32_t row, int32_t column, double value) {
    if (row < column) return;
    if (placed)
      c.values.push_back(value);
    else
      c.entries.emplace_back(row, column, value);
  };
  for (const auto& [s, t] : c.slotPairs) {
    const auto node = static_cast<size_t>(c.slotNode[s]);
    Mat3 block = c.slotImage[s].transpose() * c.slotImage[t];
    if (node < heldAlong.size() && !heldAlong[node].isZero())  // W = w (I − s sᵀ)
      block -= (c.slotImage[s].transpose() * heldAlong[node]) * (heldAlong[node].transpose() * c.slotImage[t]);
    block *= inverseMass[node];
    const int32_t rows = 3 * c.slotAggregate[s], columns = 3 * c.slotAggregate[t];
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) {
        add(rows + i, columns + j, block(i, j));
        if (rows != columns) add(columns + j, rows + i, block(i, j));
      }
  }
  for (int32_t k = 0; k < size; ++k) add(k, k, 0.0);  // every diagonal entry present
  Eigen::SparseMatrix<double>& matrix = c.factor.matrix;
  bool newPattern = false;
  if (placed) {
    c.assembly.assignValues(c.values, matrix);
  } else {
    newPattern = c.assembly.assemble(c.entries, size, size, matrix);
    c.entriesPlaced = true;
  }
  // A column no edge of its patch uses (a sheet with two edge directions has no shear) is kept
  // apart with a unit diagonal; every other gets a part in 10⁹ of the largest as regularisation.
  double largest = 0.0;
  for (int32_t k = 0; k < size; ++k) largest = std::max(largest, matrix.coeff(k, k));
  for (int32_t k = 0; k < size; ++k) {
    double& diagonal = matrix.coeffRef(k, k);
    diagonal = diagonal > 1e-12 * largest ? diagonal + 1e-9 * largest : 1.0;
  }
  c.factor.factorise(newPattern);
  c.rhs.resize(size);
  c.solution.resize(size);
  c.builtDirection = direction;
  c.builtWeight.resize(c.slotNode.size());
  c.builtHeldAlong.resize(c.slotNode.size());
  for (size_t k = 0; k < c.slotNode.size(); ++k) {
    const auto node = static_cast<size_t>(c.slotNode[k]);
    c.builtWeight[k] = inverseMass[node];
    c.builtHeldAlong[k] = node < heldAlong.size() ? heldAlong[node] : Vec3::Zero();
  }
}

// How far (|n − n₀|, about the angle in radians) the edges may turn in the root mean square, or
// a node's held direction change, before the coarse level built for n₀ is built again. It is a
// preconditioner: a level a few degrees out of date slows the conjugate gradients a little and
// changes nothing they converge to, and at rest a sheet's edges turn by far less from step to
// step, so the level (its patches' planes, the Galerkin product and its factorisation: a tenth of
// the paper's cloth's step when built in every step) is kept. Measured: docs/performance.md and
// docs/solver.md, twenty-sixth session.
inline constexpr double kSweptEdgeCoarseKeptTurn = 0.05;

// Whether the level, factorised, was built for these edges' directions (their root mean square
// turn since), weights (exactly) and held directions within kSweptEdgeCoarseKeptTurn.
inline bool sweptEdgeCoarseFits(const std::vector<Vec3>& direction, std::span<const double> inverseMass,
                                std::span<const Vec3> heldAlong, const SweptEdgeCoarseLevel& c) {
  if (!c.factor.ready || direction.size() != c.builtDirection.size()) return false;
  constexpr double turn2 = kSweptEdgeCoarseKeptTurn * kSweptEdgeCoarseKeptTurn;
  double turned2 = 0.0;
  for (size_t e = 0; e < direction.size(); ++e) turned2 += (direction[e] - c.builtDirection[e]).squaredNorm();
  if (turned2 > turn2 * static_cast<double>(direction.size())) return false;
  for (size_t k = 0; k < c.slotNode.size(); ++k) {
    const auto node = static_cast<size_t>(c.slotNode[k]);
    const Vec3 held = node < heldAlong.size() ? heldAlong[node] : Vec3::Zero();
    if (inverseMass[node] != c.builtWeight[k] || (held - c.builtHeldAlong[k]).squaredNorm() > turn2) return false;
  }
  return true;
}

}  // namespace tandem
