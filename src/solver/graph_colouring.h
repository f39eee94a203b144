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
// thread. // Static, kinematic and sleeping bodies are shared freely: rows only read them. The sort is
// stable, so a colour keeps its rows in the order they were made.
//
// Which arrays: contacts, every step after detection. Fixed points, anchors and grabs keep their
// order: their indices are the public ids, and they are few. Inextensibility and bending rows
// sorted the same way when a deformable was added made a hammock's direct block stop holding a
// box resting on it (Contact.BoxLiftedOffAHammockLeavesTheClothBehind: the box fell through
// with its contacts in place), not yet understood; they keep the order they were made in.
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

// Reusable buffers: colouring a contact array every step allocates nothing once they are grown.
template <class Row>
struct ColouringScratch {
  std::vector<uint32_t> usedColours;  // per node or body: a bit per colour taken
  std::vector<uint8_t> colour;        // per row
  std::vector<Row> sorted;
};

// Sorts `rows` by colour. `resourceCount` bounds the resource ids; `resourcesOf(row, add)`
// calls add(id) for each node or dynamic body the row writes.
template <class Row, class ResourcesOf>
ColourRanges colourRows(std::vector<Row>& rows, size_t resourceCount, ResourcesOf resourcesOf,
                        ColouringScratch<Row>& scratch) {
  static_assert(kColourCount <= 32, "a colour is a bit of a uint32_t");
  scratch.usedColours.assign(resourceCount, 0u);
  scratch.colour.resize(rows.size());
  std::array<int32_t, kColourCount + 1> count{};
  for (size_t r = 0; r < rows.size(); ++r) {
    uint32_t taken = 0;
    resourcesOf(rows[r], [&](size_t id) { taken |= scratch.usedColours[id]; });
    int colour = kColourCount;  // the overflow
    for (int c = 0; c < kColourCount; ++c)
      if (!(taken & (1u << c))) {
        colour = c;
        break;
      }
    if (colour < kColourCount) resourcesOf(rows[r], [&](size_t id) { scratch.usedColours[id] |= 1u << colour; });
    scratch.colour[r] = static_cast<uint8_t>(colour);
    ++count[static_cast<size_t>(colour)];
  }
  ColourRanges ranges;
  for (int c = 0; c <= kColourCount; ++c)
    ranges.start[static_cast<size_t>(c) + 1] = ranges.start[static_cast<size_t>(c)] + count[static_cast<size_t>(c)];
  std::array<int32_t, kColourCount + 1> next{};
  for (int c = 0; c <= kColourCount; ++c) next[static_cast<size_t>(c)] = ranges.start[static_cast<size_t>(c)];
  scratch.sorted.resize(rows.size());
  for (size_t r = 0; r < rows.size(); ++r) scratch.sorted[static_cast<size_t>(next[scratch.colour[r]]++)] = rows[r];
  rows.swap(scratch.sorted);
  return ranges;
}

}  // namespace tandem
