#pragma once
// Flat, index-based tetrahedral mesh with the history DAG of the paper.
//
// Every tetrahedron ever created keeps its slot (no recycling): dead tetrahedra are the inner
// nodes of the location DAG, and a reader descending the DAG never sees a slot reused under it,
// which is what lets the parallel methods descend without locks. Storage is a chunked array with
// a fixed directory, so a slot's address never changes while other threads append.
//
// Orientation convention: a live tetrahedron (v0, v1, v2, v3) is positively oriented,
// orient3d(v0, v1, v2, v3) > 0. Face f is the face opposite v[f]; kFaceVertex[f] lists its
// vertices so that v[f] lies on the negative side (outward orientation). neighbor[f] = 4*t + g
// names the tetrahedron t across face f and the index g of the same face inside t.
#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

namespace dtlab::engine {

using VertexId = std::uint32_t;
using TetId = std::uint32_t;
using FaceRef = std::uint32_t;  // 4 * tet + face

inline constexpr VertexId kInfiniteVertex = 0xFFFFFFFFu;  // the symbolic vertex at infinity
inline constexpr TetId kNoTet = 0xFFFFFFFFu;

inline constexpr std::array<std::array<int, 3>, 4> kFaceVertex{
    {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}}};

inline FaceRef face_ref(TetId t, int f) {
  return 4 * t + static_cast<FaceRef>(f);
}
inline TetId ref_tet(FaceRef r) {
  return r >> 2;
}
inline int ref_face(FaceRef r) {
  return static_cast<int>(r & 3u);
}

struct Tet {
  std::array<VertexId, 4> vertex{};
  std::array<FaceRef, 4> neighbor{};
  // DAG children: the tetrahedra that replaced this one (kNoTet when unused). Written before the
  // tetrahedron is marked dead; published with release, read with acquire.
  std::array<std::atomic<TetId>, 4> child{};
  // Owner of the lock (thread id + 1), 0 when free: used by the parallel lock methods.
  std::atomic<std::uint32_t> lock_owner{0};
  // Dead tetrahedra are DAG history; release on death, acquire on reading.
  std::atomic<bool> alive{false};

  [[nodiscard]] bool is_infinite() const {
    return vertex[0] == kInfiniteVertex || vertex[1] == kInfiniteVertex ||
           vertex[2] == kInfiniteVertex || vertex[3] == kInfiniteVertex;
  }
  [[nodiscard]] int index_of(VertexId v) const {
    for (int i = 0; i < 4; ++i) {
      if (vertex[static_cast<std::size_t>(i)] == v) return i;
    }
    return -1;
  }
};

// The store ran out of slots: the run cannot go on (triangulate reports it as an error).
class StoreFull : public std::length_error {
 public:
  using std::length_error::length_error;
};

// Append-only storage with stable addresses: a fixed directory of fixed-size blocks.
class TetStore {
 public:
  static constexpr unsigned kBlockBits = 16;
  static constexpr std::size_t kBlockSize = std::size_t{1} << kBlockBits;
  static constexpr std::size_t kMaxBlocks = std::size_t{1} << 14;
  // A FaceRef is 4 * tet + face in 32 bits, so tetrahedron ids stay below 2^30: the store refuses
  // the 2^30-th slot (DAG nodes included: about 20M uniform points) instead of wrapping.
  static constexpr std::size_t kMaxTets = kBlockSize * kMaxBlocks;
  static_assert(kMaxTets == (std::size_t{1} << 30) && 4 * (kMaxTets - 1) + 3 <= 0xFFFFFFFFu);

  TetStore() : blocks_(new std::atomic<Tet*>[kMaxBlocks]) {
    for (std::size_t i = 0; i < kMaxBlocks; ++i)
      blocks_[i].store(nullptr, std::memory_order_relaxed);
  }
  TetStore(const TetStore&) = delete;
  TetStore& operator=(const TetStore&) = delete;
  ~TetStore() {
    for (std::size_t i = 0; i < kMaxBlocks; ++i)
      delete[] blocks_[i].load(std::memory_order_relaxed);
  }

  Tet& operator[](TetId t) {
    return blocks_[t >> kBlockBits].load(std::memory_order_acquire)[t & (kBlockSize - 1)];
  }
  const Tet& operator[](TetId t) const {
    return blocks_[t >> kBlockBits].load(std::memory_order_acquire)[t & (kBlockSize - 1)];
  }

  // Reserves a fresh slot (single writer in the sequential engine; the parallel methods take
  // slots with the atomic counter).
  TetId allocate() {
    const std::size_t t = size_.fetch_add(1, std::memory_order_relaxed);
    if (t >= capacity_) {
      throw StoreFull("the tetrahedron store is full: " + std::to_string(capacity_) +
                      " tetrahedra and DAG nodes" +
                      (capacity_ == kMaxTets ? " (2^30, the limit of 32-bit neighbour references)"
                                             : " (the capacity asked for)"));
    }
    ensure_block(t >> kBlockBits);
    return static_cast<TetId>(t);
  }
  // A run of up to `wanted` consecutive fresh slots, [first, first + count): one atomic step for
  // many allocations, so that threads do not contend for the counter nor interleave their
  // records on shared cache lines. Fewer than wanted only at the capacity; none throws.
  TetId allocate_run(std::size_t wanted, std::size_t& count) {
    const std::size_t first = size_.fetch_add(wanted, std::memory_order_relaxed);
    if (first >= capacity_) return allocate();  // throws StoreFull with the message
    count = std::min(wanted, capacity_ - first);
    for (std::size_t b = first >> kBlockBits; b <= (first + count - 1) >> kBlockBits; ++b) {
      ensure_block(b);
    }
    return static_cast<TetId>(first);
  }
  // Slots handed out (a refused allocate counted no slot).
  [[nodiscard]] std::size_t size() const {
    const std::size_t n = size_.load(std::memory_order_relaxed);
    return n < capacity_ ? n : capacity_;
  }
  [[nodiscard]] std::size_t capacity() const { return capacity_; }
  // A smaller capacity (a memory cap; tests reach the limit with it). Before the first allocate.
  void set_capacity(std::size_t tets) { capacity_ = tets < kMaxTets ? tets : kMaxTets; }
  // Tests only: the next slot is `first` (its block is allocated on demand), to reach the 2^30
  // boundary without allocating 2^30 slots. Before the first allocate.
  void skip_to_for_testing(std::size_t first) { size_.store(first, std::memory_order_relaxed); }

 private:
  void ensure_block(std::size_t block) {
    if (blocks_[block].load(std::memory_order_acquire) != nullptr) return;
    Tet* fresh = new Tet[kBlockSize];
    Tet* expected = nullptr;
    if (!blocks_[block].compare_exchange_strong(expected, fresh, std::memory_order_acq_rel)) {
      delete[] fresh;  // another thread installed it first
    }
  }

  std::unique_ptr<std::atomic<Tet*>[]> blocks_;
  std::atomic<std::size_t> size_{0};
  std::size_t capacity_ = kMaxTets;
};

}  // namespace dtlab::engine
