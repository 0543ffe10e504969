#pragma once
// An append-only list of tetrahedron ids, emptied by clear() without freeing, whose append is a
// compare and a store inlined at the call: the lock methods append tens of ids per insertion
// (the locks held, the tetrahedra created), and std::vector::push_back stayed an out-of-line
// call there (5.6 % of the samples of optimistic-detect on one thread).
#include <cstddef>
#include <vector>

#include "dtlab/engine/tet_mesh.hpp"

namespace dtlab::engine {

class TetIdList {
 public:
  void push_back(TetId t) {
    if (size_ == ids_.size()) grow();
    ids_[size_++] = t;
  }
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
