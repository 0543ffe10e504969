#pragma once
// A list (and stack) of tetrahedron ids, emptied by clear() without freeing, whose append is a
// compare and a store inlined at the call: the lock methods append tens of ids per insertion
// (the locks held, the tetrahedra created), and the slot allocator moves tens of slots per
// insertion through its lists; std::vector::push_back stayed an out-of-line call there
// (docs/performance.md, "Measured choices").
#include <cstddef>
#include <vector>

#include "mesh/tet_store.hpp"

namespace dtlab::engine {

class TetIdList {
 public:
  // Always inlined: GCC had made it a call again.
  [[gnu::always_inline]] void push_back(TetId t) {
    if (size_ == ids_.size()) grow();
    ids_[size_++] = t;
  }
  // The last id, removed (the list must not be empty).
  TetId pop_back() { return ids_[--size_]; }
  [[nodiscard]] TetId back() const { return ids_[size_ - 1]; }
  void clear() { size_ = 0; }
  [[nodiscard]] bool empty() const { return size_ == 0; }
  [[nodiscard]] std::size_t size() const { return size_; }
  [[nodiscard]] const TetId* begin() const { return ids_.data(); }
  [[nodiscard]] const TetId* end() const { return ids_.data() + size_; }

 private:
  [[gnu::noinline]] void grow() { ids_.resize(ids_.empty() ? 64 : 2 * ids_.size()); }

  std::vector<TetId> ids_;  // the first size_ are the list
  std::size_t size_ = 0;
};

}  // namespace dtlab::engine
