// The sweep's layout for the parallel step (src/solver/graph_colouring.h): a cloth's edges
// coloured as an index list or sorted by colour, so that no two rows of one colour share a node.
#include "solver/constraint_rows.h"

#include <tandem/mesh.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace tandem {
namespace {

ConstraintRows clothEdges(int side) {
  const DeformableMesh mesh = *makeClothGrid(Vec3::Zero(), {1, 0, 0}, {0, 0, 1}, side, side, 0.1);
  ConstraintRows rows;
  for (const auto* edges : {&mesh.edges, &mesh.shearEdges})
    for (const auto& e : *edges) {
      InextensibilityRow row;
      row.node = {e[0], e[1]};
      rows.inextensibility.push_back(row);
    }
  return rows;
}

TEST(GraphColouring, SweptEdgesOfAColourShareNoNodeAndKeepTheirOrder) {
  const int side = 51;
  ConstraintRows rows = clothEdges(side);
  // Every third edge is held by a direct block: it is left out of the sweep's list.
  for (size_t r = 0; r < rows.inextensibility.size(); r += 3) rows.inextensibility[r].inDirectBlock = true;
  rows.colourSweptEdges(static_cast<size_t>(side * side));

  std::vector<int32_t> expected;
  for (size_t r = 0; r < rows.inextensibility.size(); ++r)
    if (!rows.inextensibility[r].inDirectBlock) expected.push_back(static_cast<int32_t>(r));
  std::vector<int32_t> listed = rows.sweptEdges;
  std::sort(listed.begin(), listed.end());
  EXPECT_EQ(listed, expected) << "each swept edge once, no held one";

  const ColourRanges& colours = rows.sweptEdgeColours;
  EXPECT_EQ(colours.end(kColourCount), static_cast<int32_t>(rows.sweptEdges.size()));
  EXPECT_EQ(colours.overflowCount(), 0) << "a grid's edges fit the colours";
  // A node's swept edges each need a colour of their own: at least its degree's worth.
  std::vector<int> degree(static_cast<size_t>(side * side), 0);
  for (int32_t r : expected)
    for (int32_t node : rows.inextensibility[static_cast<size_t>(r)].node) ++degree[static_cast<size_t>(node)];
  EXPECT_GE(colours.coloursUsed(), *std::max_element(degree.begin(), degree.end()));
  for (int c = 0; c < kColourCount; ++c) {
    std::vector<char> seen(static_cast<size_t>(side * side), 0);
    for (int32_t i = colours.begin(c); i < colours.end(c); ++i) {
      const InextensibilityRow& row = rows.inextensibility[static_cast<size_t>(rows.sweptEdges[static_cast<size_t>(i)])];
      for (int32_t node : row.node) {
        EXPECT_FALSE(seen[static_cast<size_t>(node)]) << "colour " << c << " writes node " << node << " twice";
        seen[static_cast<size_t>(node)] = 1;
      }
      if (i > colours.begin(c)) {
        EXPECT_LT(rows.sweptEdges[static_cast<size_t>(i) - 1], rows.sweptEdges[static_cast<size_t>(i)]);
      }
    }
  }
}

// colourRows (the contacts' every step) sorts the rows themselves by the same colours.
TEST(GraphColouring, RowsSortedByColourShareNoNodeWithinAColour) {
  const int side = 21;
  ConstraintRows rows = clothEdges(side);
  const auto nodesOf = [](const InextensibilityRow& row, auto add) {
    for (int32_t node : row.node) add(static_cast<size_t>(node));
  };
  std::vector<InextensibilityRow> sorted = rows.inextensibility;
  ColouringScratch scratch;
  std::vector<int32_t> order;
  std::vector<InextensibilityRow> buffer;
  const ColourRanges colours = colourRows(sorted, static_cast<size_t>(side * side), nodesOf, scratch, order, buffer);
  ASSERT_EQ(sorted.size(), rows.inextensibility.size());
  EXPECT_EQ(colours.end(kColourCount), static_cast<int32_t>(sorted.size()));
  for (size_t i = 0; i < sorted.size(); ++i)  // row i of the sorted array is row order[i] of the original
    EXPECT_EQ(sorted[i].node, rows.inextensibility[static_cast<size_t>(order[i])].node);
  std::vector<int32_t> all = order;
  std::sort(all.begin(), all.end());
  for (size_t i = 0; i < all.size(); ++i) ASSERT_EQ(all[i], static_cast<int32_t>(i)) << "each row once";
  for (int c = 0; c < kColourCount; ++c) {
    std::vector<char> seen(static_cast<size_t>(side * side), 0);
    for (int32_t i = colours.begin(c); i < colours.end(c); ++i)
      for (int32_t node : sorted[static_cast<size_t>(i)].node) {
        EXPECT_FALSE(seen[static_cast<size_t>(node)]) << "colour " << c << " writes node " << node << " twice";
        seen[static_cast<size_t>(node)] = 1;
      }
  }
}

}  // namespace
}  // namespace tandem
