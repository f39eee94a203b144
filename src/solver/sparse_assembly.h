#pragma once

#include <Eigen/SparseCore>

#include <cassert>
#include <span>
#include <vector>

namespace tandem {

// A sparse matrix in compressed columns from triplets, as Eigen's setFromTriplets builds it
// (duplicates summed in the order given, each column's rows in order, explicit zeros kept), or
// only its lower triangle (of a symmetric matrix: all a Lower LDLᵀ reads). Each triplet's place
// among the values is kept, so while the triplets' positions stay the same from one assembly to
// the next (a block's released rows, a step whose contacts are the same, an elastic body's
// stiffness) assembly is one pass over their values, and nothing is allocated.
class SparseAssembly {
 public:
  enum class Part { Whole, LowerTriangle };
  explicit SparseAssembly(Part part) : m_part(part) {}

  // The values alone of triplets at the positions last assembled, in the same order (the caller
  // knows they are the same): one pass, no positions compared and no triplets built.
  void assignValues(std::span<const double> values, Eigen::SparseMatrix<double>& matrix) const {
    assert(values.size() == m_slot.size());
    double* value = matrix.valuePtr();
    for (size_t e = 0; e < values.size(); ++e) {
      const int slot = m_slot[e];
      if (slot < 0) continue;
      value[slot] = m_first[e] ? values[e] : value[slot] + values[e];
    }
  }

  // Writes `matrix` (rows × columns); returns whether its pattern was rebuilt.
  bool assemble(std::span<const Eigen::Triplet<double>> entries, Eigen::Index rows, Eigen::Index columns,
                Eigen::SparseMatrix<double>& matrix) {
    const bool same = rows == m_rows && columns == m_columns && samePositions(entries);
    if (!same) placeEntries(entries, rows, columns, matrix);
    double* value = matrix.valuePtr();
    for (size_t e = 0; e < entries.size(); ++e) {
      const int slot = m_slot[e];
      if (slot < 0) continue;
      value[slot] = m_first[e] ? entries[e].value() : value[slot] + entries[e].value();
    }
    return !same;
  }

 private:
  Part m_part;
  Eigen::Index m_rows = -1, m_columns = -1;
  std::vector<int> m_row, m_col;  // the positions of the entries last placed
  std::vector<int> m_slot;        // per entry: its index among the values, or −1 if left out
  std::vector<char> m_first;      // per entry: the first of its slot's, which sets the value
  std::vector<int> m_count, m_byRow, m_byColumn;  // scratch of placeEntries

  bool samePositions(std::span<const Eigen::Triplet<double>> entries) const {
    if (entries.size() != m_row.size()) return false;
    for (size_t e = 0; e < entries.size(); ++e)
      if (entries[e].row() != m_row[e] || entries[e].col() != m_col[e]) return false;
    return true;
  }

  // Two stable counting sorts (by row, then by column) put each column's entries in row order,
  // duplicates side by side in the order given.
  void placeEntries(std::span<const Eigen::Triplet<double>> entries, Eigen::Index rows, Eigen::Index columns,
                    Eigen::SparseMatrix<double>& matrix) {
    m_rows = rows;
    m_columns = columns;
    m_row.resize(entries.size());
    m_col.resize(entries.size());
    m_slot.assign(entries.size(), -1);
    m_first.assign(entries.size(), 0);
    auto countingSort = [&](const std::vector<int>& from, std::vector<int>& to, const std::vector<int>& key, Eigen::Index n) {
      m_count.assign(static_cast<size_t>(n) + 1, 0);
      for (int e : from) ++m_count[static_cast<size_t>(key[static_cast<size_t>(e)]) + 1];
      for (size_t i = 0; i < static_cast<size_t>(n); ++i) m_count[i + 1] += m_count[i];
      to.resize(from.size());
      for (int e : from) to[static_cast<size_t>(m_count[static_cast<size_t>(key[static_cast<size_t>(e)])]++)] = e;
    };
    m_byColumn.clear();
    for (size_t e = 0; e < entries.size(); ++e) {
      m_row[e] = entries[e].row();
      m_col[e] = entries[e].col();
      if (m_part == Part::Whole || m_row[e] >= m_col[e]) m_byColumn.push_back(static_cast<int>(e));
    }
    countingSort(m_byColumn, m_byRow, m_row, rows);
    countingSort(m_byRow, m_byColumn, m_col, columns);

    matrix.resize(rows, columns);
    int* outer = matrix.outerIndexPtr();
    int slots = 0;
    for (size_t k = 0; k < m_byColumn.size(); ++k) {
      const auto e = static_cast<size_t>(m_byColumn[k]);
      const bool repeat = k > 0 && m_row[e] == m_row[static_cast<size_t>(m_byColumn[k - 1])] &&
                          m_col[e] == m_col[static_cast<size_t>(m_byColumn[k - 1])];
      if (!repeat) ++slots;
      m_slot[e] = slots - 1;
      m_first[e] = repeat ? 0 : 1;
    }
    matrix.resizeNonZeros(slots);
    int* inner = matrix.innerIndexPtr();
    std::fill(outer, outer + columns + 1, 0);
    for (size_t k = 0; k < m_byColumn.size(); ++k) {
      const auto e = static_cast<size_t>(m_byColumn[k]);
      if (!m_first[e]) continue;
      inner[m_slot[e]] = m_row[e];
      ++outer[m_col[e] + 1];
    }
    for (Eigen::Index j = 0; j < columns; ++j) outer[j + 1] += outer[j];
  }
};

}  // namespace tandem
