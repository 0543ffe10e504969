#pragma once
// A set of tetrahedron ids for the span of one insertion: open addressing with linear probing,
// emptied in O(1) by bumping a generation. The undo log asks it once per write, so a linear scan
// of the log (quadratic in the insertion's size) is not an option.
#include <cstdint>
#include <vector>

#include "dtlab/engine/tet_mesh.hpp"

namespace dtlab::engine {

class InsertionIdSet {
 public:
  // True when t was not in the set (and is now).
  bool insert(TetId t) {
    if (2 * (count_ + 1) > slots_.size()) grow();
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = spread(t) & mask;; i = (i + 1) & mask) {
      Slot& slot = slots_[i];
      if (slot.generation != generation_) {
        slot = {t, generation_};
        ++count_;
        return true;
      }
      if (slot.tet == t) return false;
    }
  }
  void clear() {
    count_ = 0;
    if (++generation_ == 0) {  // wrapped: no stale slot may look current
      for (Slot& slot : slots_) slot.generation = 0;
      generation_ = 1;
    }
  }

 private:
  struct Slot {
    TetId tet = 0;
    std::uint32_t generation = 0;
  };
  static std::size_t spread(TetId t) { return (t * 0x9E3779B1u) >> 7; }
  void grow() {
    std::vector<Slot> old;
    old.swap(slots_);
    slots_.assign(old.empty() ? 256 : 2 * old.size(), Slot{});
    const std::uint32_t current = generation_;
    count_ = 0;
    generation_ = 1;
    for (const Slot& slot : old) {
      if (slot.generation == current) insert(slot.tet);
    }
  }

  std::vector<Slot> slots_;
  std::size_t count_ = 0;
  std::uint32_t generation_ = 1;
};

}  // namespace dtlab::engine
