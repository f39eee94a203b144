// The slots behind one kind of id (world.h: "Ids and what a bad id gets"): each slot is live or
// free, carries a generation, and says where its thing is stored (its position in a dense
// array, which moves when things before it are erased). Internal.
#pragma once

#include <tandem/types.h>

#include <cstdint>
#include <string>
#include <vector>

namespace tandem {

class IdSlots {
 public:
  explicit IdSlots(const char* kind) : m_kind(kind) {}

  struct Taken {
    int32_t index;
    uint32_t generation;
  };

  // A slot for a thing stored at `position`: the lowest free slot when `reuse` (its generation
  // one higher than the last), else a new one.
  Taken add(int32_t position, bool reuse) {
    if (reuse)
      for (size_t i = 0; i < m_slots.size(); ++i)
        if (!m_slots[i].live) {
          m_slots[i].live = true;
          m_slots[i].position = position;
          return {static_cast<int32_t>(i), m_slots[i].generation};
        }
    m_slots.push_back({position, 0, true});
    return {static_cast<int32_t>(m_slots.size()) - 1, 0};
  }

  // A slot taken at a given index (for kinds whose slot is their storage index): it must be free
  // or new.
  Taken addAt(int32_t index) {
    if (index >= static_cast<int32_t>(m_slots.size())) m_slots.resize(static_cast<size_t>(index) + 1, {-1, 0, false});
    m_slots[index].live = true;
    m_slots[index].position = index;
    return {index, m_slots[index].generation};
  }

  // The lowest free slot's index, or -1.
  int32_t firstFree() const {
    for (size_t i = 0; i < m_slots.size(); ++i)
      if (!m_slots[i].live) return static_cast<int32_t>(i);
    return -1;
  }

  bool live(int32_t index, uint32_t generation) const {
    return index >= 0 && index < static_cast<int32_t>(m_slots.size()) && m_slots[index].live &&
           m_slots[index].generation == generation;
  }
  bool liveIndex(int32_t index) const {
    return index >= 0 && index < static_cast<int32_t>(m_slots.size()) && m_slots[index].live;
  }
  // ok, or what is wrong with the id, named ("anchor 3 (generation 0) was removed").
  Status check(int32_t index, uint32_t generation) const {
    const std::string name = std::string(m_kind) + " " + std::to_string(index);
    if (index < 0 || index >= static_cast<int32_t>(m_slots.size()))
      return Error{name + ": no such " + m_kind + " (the world has " + std::to_string(m_slots.size()) + (m_slots.size() == 1 ? " slot)" : " slots)")};
    const Slot& slot = m_slots[index];
    if (slot.generation == generation && slot.live) return {};
    if (generation < slot.generation)
      return Error{name + " (generation " + std::to_string(generation) + ") was removed" +
                   (slot.live ? " (its slot now holds generation " + std::to_string(slot.generation) + ")" : "")};
    return Error{name + ": generation " + std::to_string(generation) + " was never made (the slot is at generation " +
                 std::to_string(slot.generation) + ")"};
  }

  int32_t position(int32_t index) const { return m_slots[index].position; }
  uint32_t generation(int32_t index) const { return m_slots[index].generation; }
  size_t size() const { return m_slots.size(); }
  int liveCount() const {
    int count = 0;
    for (const Slot& slot : m_slots) count += slot.live ? 1 : 0;
    return count;
  }
  // The live slot holding `position`, or -1.
  int32_t slotAt(int32_t position) const {
    for (size_t i = 0; i < m_slots.size(); ++i)
      if (m_slots[i].live && m_slots[i].position == position) return static_cast<int32_t>(i);
    return -1;
  }

  // Frees a slot; its next occupant gets the next generation. With `erased`, the thing's storage
  // position was erased from its dense array: the things after it moved down one.
  void remove(int32_t index, bool erased) {
    Slot& slot = m_slots[index];
    const int32_t position = slot.position;
    slot.live = false;
    ++slot.generation;
    slot.position = -1;
    if (!erased) return;
    for (Slot& other : m_slots)
      if (other.live && other.position > position) --other.position;
  }

 private:
  struct Slot {
    int32_t position = -1;
    uint32_t generation = 0;
    bool live = false;
  };
  const char* m_kind;
  std::vector<Slot> m_slots;
};

}  // namespace tandem
