// The swept edges' coarse level (src/solver/swept_edge_coarse.h) and the two-level cycle of
// their solve (src/solver/swept_edge_solve.h): the coarse matrix is Galerkin's
// Pᵀ A P of the edges' system, the two-level cycle is symmetric and positive, and it cuts the
// conjugate gradients' iterations on a wide sheet to a third of Jacobi's.
#include "solver/swept_edge_solve.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <random>

namespace tandem {
namespace {

// A side × side sheet of nodes (spacing 1 cm, bent a little out of its plane so that every edge
// direction differs), its structural edges but those between two pinned nodes (as the solve
// leaves them out), and every node's inverse mass (the first row pinned).
struct Sheet {
  std::vector<Vec3> position;
  std::vector<double> inverseMass;
  std::vector<std::array<int32_t, 2>> edges;
  std::vector<Vec3> direction;

  explicit Sheet(int side, uint32_t seed = 7) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> jitter(-0.0002, 0.0002), mass(0.5, 2.0);
    for (int r = 0; r < side; ++r)
      for (int c = 0; c < side; ++c) {
        position.emplace_back(0.01 * c + jitter(random), 0.02 * std::sin(0.1 * c) + jitter(random), 0.01 * r);
        inverseMass.push_back(r == 0 ? 0.0 : 1.0 / (1e-4 * mass(random)));
      }
    for (int r = 0; r < side; ++r)
      for (int c = 0; c < side; ++c) {
        const int32_t n = r * side + c;
        if (c + 1 < side && r > 0) edges.push_back({n, n + 1});  // none between two pinned nodes
        if (r + 1 < side) edges.push_back({n, n + side});
      }
    for (const auto& e : edges) direction.push_back((position[e[1]] - position[e[0]]).normalized());
  }

  // A = J W Jᵀ, (A x)ₑ = nₑ · (y[j] − y[i]) with y = W Jᵀ x.
  std::vector<double> multiply(const std::vector<double>& x) const {
    std::vector<Vec3> y(position.size(), Vec3::Zero());
    for (size_t e = 0; e < edges.size(); ++e) {
      y[edges[e][0]] -= x[e] * inverseMass[edges[e][0]] * direction[e];
      y[edges[e][1]] += x[e] * inverseMass[edges[e][1]] * direction[e];
    }
    std::vector<double> out(edges.size());
    for (size_t e = 0; e < edges.size(); ++e) out[e] = direction[e].dot(y[edges[e][1]] - y[edges[e][0]]);
    return out;
  }
  double diagonal(size_t e) const { return inverseMass[edges[e][0]] + inverseMass[edges[e][1]]; }

  // The swept edges' solve's working memory for its edges, with their coarse level (patches and
  // factorised matrix), as solveSweptEdgesTogether prepares it.
  void prepare(SweptEdgeSolveScratch& s) const {
    for (size_t e = 0; e < edges.size(); ++e)
      s.edges.push_back({static_cast<int32_t>(e),
                         {edges[e][0], edges[e][1]},
                         direction[e],
                         {inverseMass[edges[e][0]] * direction[e], inverseMass[edges[e][1]] * direction[e]},
                         1.0 / diagonal(e)});
    s.smoothedOnNodes.assign(position.size(), Vec3::Zero());
    listSweptEdgeNodes(s, position.size());
    aggregateSweptEdges(edges, s.coarse);
    buildSweptEdgeCoarse(direction, inverseMass, {}, s.coarse);
  }
};

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i) sum += a[i] * b[i];
  return sum;
}

TEST(SweptEdgeCoarse, MatrixIsTheGalerkinProductOfTheEdgeSystem) {
  const Sheet sheet(9);
  SweptEdgeSolveScratch scratch;
  sheet.prepare(scratch);
  const SweptEdgeCoarseLevel& coarse = scratch.coarse;
  ASSERT_TRUE(coarse.factor.ready);
  ASSERT_GT(coarse.aggregateCount, 1);
  ASSERT_LT(coarse.aggregateCount, static_cast<int32_t>(sheet.position.size()) / 4);  // patches, not nodes
  const auto edges = static_cast<Eigen::Index>(sheet.edges.size());
  const Eigen::Index size = 3 * coarse.aggregateCount;
  Eigen::MatrixXd a(edges, edges), p = Eigen::MatrixXd::Zero(edges, size);
  for (Eigen::Index e = 0; e < edges; ++e) {
    std::vector<double> unit(sheet.edges.size(), 0.0);
    unit[e] = 1.0;
    const std::vector<double> column = sheet.multiply(unit);
    for (Eigen::Index f = 0; f < edges; ++f) a(f, e) = column[f];
    p.block<1, 3>(e, 3 * coarse.aggregateOfEdge[e]) = coarse.basisOfEdge[e].transpose();
  }
  const Eigen::MatrixXd galerkin = p.transpose() * a * p;
  const Eigen::SparseMatrix<double> whole = coarse.factor.matrix.selfadjointView<Eigen::Lower>();  // its lower triangle stored
  const Eigen::MatrixXd built(whole);
  const double largest = galerkin.diagonal().maxCoeff();
  for (Eigen::Index i = 0; i < size; ++i)
    for (Eigen::Index j = 0; j < size; ++j) {
      if (i != j) {
        EXPECT_NEAR(built(i, j), galerkin(i, j), 1e-12 * largest) << i << ", " << j;
      } else if (galerkin(i, i) > 1e-12 * largest) {  // regularised by a part in 10⁹
        EXPECT_NEAR(built(i, i), galerkin(i, i), 2e-9 * largest) << i;
      } else {
        EXPECT_EQ(built(i, i), 1.0) << i;  // a stress no edge of the patch carries, kept apart
      }
    }
}

// z = B r: Jacobi's D⁻¹ r, or the two-level cycle of the swept edges' solve.
std::vector<double> precondition(const Sheet& sheet, SweptEdgeSolveScratch& scratch, const std::vector<double>& r,
                                 bool twoLevel) {
  std::vector<double> z(r.size(), 0.0);
  if (twoLevel) {
    preconditionSweptEdges(scratch, r, z);
    return z;
  }
  for (size_t e = 0; e < r.size(); ++e) z[e] = r[e] / sheet.diagonal(e);
  return z;
}

TEST(SweptEdgeCoarse, PreconditionerIsSymmetricAndPositive) {
  const Sheet sheet(15);
  SweptEdgeSolveScratch scratch;
  sheet.prepare(scratch);
  std::mt19937 random(3);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<double> r1(sheet.edges.size()), r2(sheet.edges.size());
    for (size_t e = 0; e < r1.size(); ++e) {
      r1[e] = normal(random);
      r2[e] = normal(random);
    }
    const std::vector<double> z1 = precondition(sheet, scratch, r1, true), z2 = precondition(sheet, scratch, r2, true);
    EXPECT_NEAR(dot(r2, z1), dot(r1, z2), 1e-9 * std::sqrt(dot(r1, z1) * dot(r2, z2)));
    EXPECT_GT(dot(r1, z1), 0.0);
  }
}

// Preconditioned conjugate gradients on A x = b from 0: iterations until |r| < 10⁻⁶ |b|.
int iterationsToConverge(const Sheet& sheet, SweptEdgeSolveScratch& scratch, const std::vector<double>& b,
                         bool twoLevel) {
  std::vector<double> x(b.size(), 0.0), r = b, z = precondition(sheet, scratch, r, twoLevel), d = z;
  double rz = dot(r, z);
  const double target = 1e-12 * dot(b, b);
  for (int iteration = 1; iteration <= 5000; ++iteration) {
    const std::vector<double> ad = sheet.multiply(d);
    const double alpha = rz / dot(d, ad);
    for (size_t i = 0; i < x.size(); ++i) {
      x[i] += alpha * d[i];
      r[i] -= alpha * ad[i];
    }
    if (dot(r, r) < target) return iteration;
    z = precondition(sheet, scratch, r, twoLevel);
    const double next = dot(r, z);
    for (size_t i = 0; i < d.size(); ++i) d[i] = z[i] + next / rz * d[i];
    rz = next;
  }
  return 5000;
}

TEST(SweptEdgeCoarse, CutsTheConjugateGradientIterationsOnAWideSheet) {
  // A sheet hanging from its first row (along +z, its plane's direction away from that row), each
  // node pulled by its weight over one step: the impulses its edges need are the smooth tension
  // field single-edge iterations carry slowly, about one edge per iteration.
  const Sheet sheet(61);
  SweptEdgeSolveScratch scratch;
  sheet.prepare(scratch);
  std::vector<Vec3> velocity(sheet.position.size(), Vec3::Zero());
  for (size_t n = 0; n < velocity.size(); ++n)
    if (sheet.inverseMass[n] > 0) velocity[n] = Vec3(0, 0, 9.81 * 0.02);
  std::vector<double> b(sheet.edges.size());
  for (size_t e = 0; e < b.size(); ++e)
    b[e] = -sheet.direction[e].dot(velocity[sheet.edges[e][1]] - velocity[sheet.edges[e][0]]);
  const int jacobi = iterationsToConverge(sheet, scratch, b, false);
  const int twoLevel = iterationsToConverge(sheet, scratch, b, true);
  EXPECT_LT(twoLevel * 2.5, jacobi) << "two-level " << twoLevel << ", Jacobi " << jacobi;  // 154 against 458
}

}  // namespace
}  // namespace tandem
