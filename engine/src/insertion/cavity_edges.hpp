#pragma once
// The pairing of a cavity's boundary edges (TetReplacement::replace_cavity): each edge of the
// cavity's boundary lies on two boundary faces, and the two new tetrahedra on them share the face
// made of p and that edge. A hash table keyed by the edge's two vertex ids, emptied in O(1) by an
// epoch, whose common path has no data-dependent branch: which end of an edge is smaller, and
// whether it is met for the first or the second time, are as unpredictable as a coin, and a
// mispredicted branch per edge cost more than the rest of the table. Written as conditions, GCC 12
// branched on both (about a quarter of the replacement's samples sat on those branches); so they
// are masks.
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "mesh/tet_store.hpp"

namespace dtlab::engine {

class CavityEdges {
  struct Entry;

 public:
  // One cavity's pairing: a view of the table, by value, so that its fields stay in registers
  // while the caller writes the mesh (through references the compiler cannot tell apart from the
  // table's own members; kept as members, they were reloaded before every probe).
  class Pass {
   public:
    // New face `self` lies on edge xy. Returns the face met on xy before (and marks the edge
    // paired), or `self` when xy is new. A third face on a paired edge sets third_face().
    FaceRef pair(VertexId x, VertexId y, FaceRef self) {
      // The smaller end first, by a mask (std::min and std::max became a branch).
      const VertexId lo = y ^ ((x ^ y) & all_ones_if(x < y));
      const VertexId hi = x ^ y ^ lo;
      const std::uint64_t key = (static_cast<std::uint64_t>(lo) << 32) | hi;
      std::size_t i = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ULL) >> shift_);
      // Past other edges' entries (rare at this load): the one branch, predictable.
      while (holds_other_edge(entries_[i], key)) i = (i + 1) & mask_;
      Entry& e = entries_[i];
      // Masks, all ones or zero: whether xy was met before, and whether it is paired already.
      // Both are coin flips; as masks, not conditions, the compiler cannot branch on them.
      const std::uint32_t seen = all_ones_if(e.epoch == epoch_);
      const std::uint32_t paired = seen & all_ones_if(e.ref == kPaired);
      third_ |= paired;
      const std::uint32_t take = seen & ~paired;
      const FaceRef partner = (e.ref & take) | (self & ~take);
      distinct_ += ~seen & 1U;
      e.key = key;
      e.epoch = epoch_;
      e.ref = (kPaired & seen) | (self & ~seen);
      return partner;
    }
    // Whether some edge lay on a third face (the boundary is no sphere).
    [[nodiscard]] bool third_face() const { return third_ != 0; }
    // The edges entered in this pass.
    [[nodiscard]] std::size_t size() const { return distinct_; }

   private:
    friend class CavityEdges;
    Pass(Entry* entries, std::size_t mask, int shift, std::uint32_t epoch)
        : entries_(entries), mask_(mask), shift_(shift), epoch_(epoch) {}
    Entry* entries_;
    std::size_t mask_;
    int shift_;  // log2(table size) top bits
    std::uint32_t epoch_;
    std::size_t distinct_ = 0;
    std::uint32_t third_ = 0;  // a mask: all ones once an edge met a third face

    static std::uint32_t all_ones_if(bool b) { return 0U - static_cast<std::uint32_t>(b); }
    // Whether entry e is this pass's and another edge's: one test of a mask, not two branches.
    [[nodiscard]] bool holds_other_edge(const Entry& e, std::uint64_t key) const {
      const std::uint64_t current = 0ULL - static_cast<std::uint64_t>(e.epoch == epoch_);
      return ((e.key ^ key) & current) != 0;
    }
  };

  // Empties the table for a cavity with at most `entries` edge entries (3 per boundary face) and
  // starts its pass. The table in use is the smallest that keeps the load at most 1/4 (each edge
  // is entered twice: 1/8 in edges), within the memory kept, so one huge cavity does not spread
  // every later small one over a large table. The pass is valid until the next begin().
  Pass begin(std::size_t entries) {
    std::size_t used = kMinimumSize;
    while (used < 4 * entries) used *= 2;
    if (entries_.size() < used) entries_.resize(used);
    used_ = used;
    if (++epoch_ == 0) {  // wrapped: entries of an old epoch could look current
      for (Entry& e : entries_) e.epoch = 0;
      epoch_ = 1;
    }
    return Pass(entries_.data(), used - 1, 64 - __builtin_ctzll(used), epoch_);
  }

  // Entries in use now, and kept allocated (for tests).
  [[nodiscard]] std::size_t used_capacity() const { return used_; }
  [[nodiscard]] std::size_t allocated_capacity() const { return entries_.size(); }

 private:
  static constexpr FaceRef kPaired = 0xFFFFFFFFu;
  static constexpr std::size_t kMinimumSize = 256;
  struct Entry {
    std::uint64_t key = 0;
    std::uint32_t epoch = 0;
    FaceRef ref = 0;
  };
  std::vector<Entry> entries_;  // the first used_ are the table
  std::size_t used_ = kMinimumSize;
  std::uint32_t epoch_ = 0;
};

}  // namespace dtlab::engine
