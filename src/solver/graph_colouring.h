// Graph colouring of the sweep's rows: the layout the parallel sweep builds on.
//
// Rows of one colour share no node and no dynamic rigid body, so the rows of a colour can be
// solved in any order, or split over any number of threads, with the same result; colours run
// one after another. Each row array is kept sorted by colour, every colour a contiguous range
// of it (Box2D v3's constraint graph: colours as ranges, an overflow for what fits none).
//
// Greedy, in the array's order: each row takes the lowest colour that none of its nodes or
// bodies has yet (one bit per colour per node or body); a row that finds none of the
// kColourCount colours free goes to the overflow, the last range, solved in order by one
// thread. Static, kinematic and sleeping bodies are shared freely: rows only read them. The sort is
// stable, so a colour keeps its rows in the order they were made.
//
// Which arrays: contacts, sorted every step after detection. Fixed points, anchors and grabs keep
// their order: their indices are the public ids, and they are few. Inextensibility rows keep the
// order they were made in, which the direct blocks and strain limiting read (the array sorted by
// colour changed where a box landed in a hammock: docs/solver.md, sixth session); the sweep goes
// through the swept ones in colour order by an index list, coloured again whenever the direct
// blocks are built (colourIndices). Bending rows are not coloured yet (constraint_rows.h).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace tandem {

constexpr int kColourCount = 24;

// Colour c's rows are [start[c], start[c + 1]); colour kColourCount is the overflow.
struct ColourRanges {
  std::array<int32_t, kColourCount + 2> start{};
  int32_t begin(int colour) const { return start[static_cast<size_t>(colour)]; }
  int32_t end(int colour) const { return start[static_cast<size_t>(colour) + 1]; }
  int32_t overflowCount() const { return end(kColourCount) - begin(kColourCount); }
  int coloursUsed() const {
    int used = 0;
    for (int c = 0; c < kColourCount; ++c) used += end(c) > begin(c) ? 1 : 0;
    return used;
  }
};

// Reusable buffers: colouring allocates nothing once they are grown.
struct ColouringScratch {
  std::vector<uint32_t> usedColours;  // per node or body: a bit per colour taken
  std::vector<uint8_t> colour;        // per row
};

// The lowest colour that none of the row's resources has taken, then taken for them all; the
// overflow, kColourCount, when every colour is.
template <class Row, class ResourcesOf>
int takeColour(const Row& row, ResourcesOf& resourcesOf, std::vector<uint32_t>& usedColours) {
  uint32_t taken = 0;
  resourcesOf(row, [&](size_t id) { taken |= usedColours[id]; });
  for (int c = 0; c < kColourCount; ++c)
    if (!(taken & (1u << c))) {
      resourcesOf(row, [&](size_t id) { usedColours[id] |= 1u << c; });
      return c;
    }
  return kColourCount;
}

// The colouring as an index list: `order` gets the indices of the rows for which `included(row)`
// holds, grouped by colour, each colour in the rows' order (a counting sort); the rows stay where
// they are. `resourceCount` bounds the resource ids; `resourcesOf(row, add)` calls add(id) for
// each node or dynamic body the row writes.
template <class Row, class Included, class ResourcesOf>
ColourRanges colourIndices(const std::vector<Row>& rows, Included included, size_t resourceCount,
                           ResourcesOf resourcesOf, std::vector<int32_t>& order, ColouringScratch& scratch) {
  static_assert(kColourCount <= 32, "a colour is a bit of a uint32_t");
  constexpr uint8_t kLeftOut = kColourCount + 1;
  scratch.usedColours.assign(resourceCount, 0u);
  scratch.colour.resize(rows.size());
  std::array<int32_t, kColourCount + 1> count{};
  for (size_t r = 0; r < rows.size(); ++r) {
    if (!included(rows[r])) {
      scratch.colour[r] = kLeftOut;
      continue;
    }
    const int colour = takeColour(rows[r], resourcesOf, scratch.usedColours);
    scratch.colour[r] = static_cast<uint8_t>(colour);
    ++count[static_cast<size_t>(colour)];
  }
  ColourRanges ranges;
  for (int c = 0; c <= kColourCount; ++c)
    ranges.start[static_cast<size_t>(c) + 1] = ranges.start[static_cast<size_t>(c)] + count[static_cast<size_t>(c)];
  std::array<int32_t, kColourCount + 1> next{};
  for (int c = 0; c <= kColourCount; ++c) next[static_cast<size_t>(c)] = ranges.start[static_cast<size_t>(c)];
  order.resize(static_cast<size_t>(ranges.end(kColourCount)));
  for (size_t r = 0; r < rows.size(); ++r)
    if (scratch.colour[r] != kLeftOut) order[static_cast<size_t>(next[scratch.colour[r]]++)] = static_cast<int32_t>(r);
  return ranges;
}

// Sorts `rows` themselves by colour (colourIndices over all of them, then the rows put in that
// order; `sorted` and `order` are buffers).
template <class Row, class ResourcesOf>
ColourRanges colourRows(std::vector<Row>& rows, size_t resourceCount, ResourcesOf resourcesOf,
                        ColouringScratch& scratch, std::vector<int32_t>& order, std::vector<Row>& sorted) {
  const ColourRanges ranges =
      colourIndices(rows, [](const Row&) { return true; }, resourceCount, resourcesOf, order, scratch);
  sorted.resize(rows.size());
  for (size_t i = 0; i < rows.size(); ++i) sorted[i] = rows[static_cast<size_t>(order[i])];
  rows.swap(sorted);
  return ranges;
}

}  // namespace tandem
