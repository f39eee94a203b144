// A direct block's sparse matrices are assembled with kept places (src/solver/sparse_assembly.h):
// the result must be Eigen's setFromTriplets to the bit (the golden hashes rest on it), the lower
// triangle must factorise as the whole matrix does, and a reassembly with the same positions must
// equal a fresh one.
#include "solver/sparse_assembly.h"

#include <Eigen/SparseCholesky>
#include <gtest/gtest.h>

#include <cstring>
#include <random>

namespace tandem {
namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;
using Sparse = Eigen::SparseMatrix<double>;

// A symmetric, diagonally dominant pattern of `size` unknowns with repeated entries (as a block's
// stiffness repeats an edge's node pairs), some of them explicit zeros.
Triplets symmetricTriplets(int size, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> index(0, size - 1);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Triplets entries;
  for (int i = 0; i < size; ++i) entries.emplace_back(i, i, 4.0 * size);
  for (int k = 0; k < 6 * size; ++k) {
    const int i = index(random), j = index(random);
    const double v = k % 7 == 0 ? 0.0 : value(random);
    entries.emplace_back(i, j, v);
    entries.emplace_back(j, i, v);
  }
  return entries;
}

void expectSameBits(const Sparse& a, const Sparse& b) {
  ASSERT_EQ(a.rows(), b.rows());
  ASSERT_EQ(a.cols(), b.cols());
  ASSERT_TRUE(a.isCompressed());
  ASSERT_TRUE(b.isCompressed());
  ASSERT_EQ(a.nonZeros(), b.nonZeros());
  for (Eigen::Index j = 0; j <= a.cols(); ++j) EXPECT_EQ(a.outerIndexPtr()[j], b.outerIndexPtr()[j]) << "column " << j;
  for (Eigen::Index k = 0; k < a.nonZeros(); ++k) EXPECT_EQ(a.innerIndexPtr()[k], b.innerIndexPtr()[k]) << "entry " << k;
  EXPECT_EQ(0, std::memcmp(a.valuePtr(), b.valuePtr(), sizeof(double) * static_cast<size_t>(a.nonZeros())));
}

Sparse eigenAssembly(const Triplets& entries, Eigen::Index rows, Eigen::Index columns) {
  Sparse matrix(rows, columns);
  matrix.setFromTriplets(entries.begin(), entries.end());
  matrix.makeCompressed();
  return matrix;
}

TEST(SparseAssembly, WholeMatrixIsEigensToTheBit) {
  const Triplets entries = symmetricTriplets(60, 1);
  SparseAssembly assembly(SparseAssembly::Part::Whole);
  Sparse matrix;
  EXPECT_TRUE(assembly.assemble(entries, 60, 60, matrix));
  expectSameBits(matrix, eigenAssembly(entries, 60, 60));
}

TEST(SparseAssembly, RectangularMatrixIsEigensToTheBit) {
  Triplets entries;  // a Jᵀ: 40 degrees of freedom × 25 rows, a few entries per row, repeated
  std::mt19937 random(2);
  std::uniform_int_distribution<int> dof(0, 39);
  std::uniform_real_distribution<double> value(-2.0, 2.0);
  for (int r = 0; r < 25; ++r)
    for (int k = 0; k < 6; ++k) entries.emplace_back(dof(random), r, value(random));
  entries.emplace_back(entries.front().row(), entries.front().col(), 0.25);
  SparseAssembly assembly(SparseAssembly::Part::Whole);
  Sparse matrix;
  assembly.assemble(entries, 40, 25, matrix);
  expectSameBits(matrix, eigenAssembly(entries, 40, 25));
}

TEST(SparseAssembly, LowerTriangleFactorisesAsTheWholeMatrix) {
  const int size = 80;
  const Triplets entries = symmetricTriplets(size, 3);
  SparseAssembly assembly(SparseAssembly::Part::LowerTriangle);
  Sparse lower;
  assembly.assemble(entries, size, size, lower);
  Triplets lowerEntries;
  for (const auto& t : entries)
    if (t.row() >= t.col()) lowerEntries.push_back(t);
  expectSameBits(lower, eigenAssembly(lowerEntries, size, size));
  for (int k = 0; k < lower.outerSize(); ++k)
    for (Sparse::InnerIterator it(lower, k); it; ++it) EXPECT_GE(it.row(), it.col());

  // A Lower LDLᵀ of the lower triangle and of the whole matrix: the same factor, the same solution.
  Eigen::SimplicialLDLT<Sparse> fromLower(lower), fromWhole(eigenAssembly(entries, size, size));
  ASSERT_EQ(fromLower.info(), Eigen::Success);
  ASSERT_EQ(fromWhole.info(), Eigen::Success);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(size, -1.0, 2.0);
  const Eigen::VectorXd x = fromLower.solve(b);
  EXPECT_EQ(0, std::memcmp(x.data(), fromWhole.solve(b).eval().data(), sizeof(double) * size));
  EXPECT_LT((eigenAssembly(entries, size, size) * x - b).norm(), 1e-12 * b.norm());
}

TEST(SparseAssembly, SamePositionsReassembleTheValuesOnly) {
  const int size = 50;
  Triplets entries = symmetricTriplets(size, 4);
  SparseAssembly assembly(SparseAssembly::Part::LowerTriangle);
  Sparse matrix;
  ASSERT_TRUE(assembly.assemble(entries, size, size, matrix));
  // New values at the same positions (a block's next step, a released row's zeros): no new
  // pattern, and the values are what a fresh assembly gives.
  for (size_t e = 0; e < entries.size(); ++e)
    entries[e] = Eigen::Triplet<double>(entries[e].row(), entries[e].col(), entries[e].value() * 0.5 + (e % 3 == 0 ? 1.0 : 0.0));
  EXPECT_FALSE(assembly.assemble(entries, size, size, matrix));
  SparseAssembly fresh(SparseAssembly::Part::LowerTriangle);
  Sparse expected;
  fresh.assemble(entries, size, size, expected);
  expectSameBits(matrix, expected);
  // One position moved: the pattern is placed again.
  entries.emplace_back(size - 1, 0, 1.0);
  EXPECT_TRUE(assembly.assemble(entries, size, size, matrix));
  fresh.assemble(entries, size, size, expected);
  expectSameBits(matrix, expected);
  // A different size with the same triplets: placed again.
  EXPECT_TRUE(assembly.assemble(entries, size + 1, size + 1, matrix));
  EXPECT_EQ(matrix.rows(), size + 1);
}

TEST(SparseAssembly, NoTripletsIsAnEmptyMatrix) {
  SparseAssembly assembly(SparseAssembly::Part::Whole);
  Sparse matrix;
  assembly.assemble({}, 3, 4, matrix);
  EXPECT_EQ(matrix.rows(), 3);
  EXPECT_EQ(matrix.cols(), 4);
  EXPECT_EQ(matrix.nonZeros(), 0);
}

}  // namespace
}  // namespace tandem
