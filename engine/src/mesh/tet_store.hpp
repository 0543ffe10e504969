#pragma once
// Flat, index-based tetrahedral mesh with the history DAG of the paper.
//
// DAG mode: every tetrahedron ever created keeps its slot (no recycling): dead tetrahedra are the
// inner nodes of the location DAG, and a reader descending the DAG never sees a slot reused under
// it, which is what lets the parallel methods descend without locks. Walk mode: no DAG, and dead
// slots are reused (slot_allocator.hpp; on a shared mesh after epoch-based reclamation,
// slot_reclaimer.hpp). Storage is a chunked array with a fixed directory, so a slot's address
// never changes while other threads append.
//
// Orientation convention: a live tetrahedron (v0, v1, v2, v3) is positively oriented,
// orient3d(v0, v1, v2, v3) > 0. Face f is the face opposite v[f]; kFaceVertex[f] lists its
// vertices so that v[f] lies on the negative side (outward orientation). neighbor[f] = 4*t + g
// names the tetrahedron t across face f and the index g of the same face inside t.
#include <sys/mman.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cassert>
#include <cstdint>
#include <cstring>
#include <memory>
#include <new>
#include <span>
#include <stdexcept>
#include <string>
#include <thread>
#include <type_traits>

namespace dtlab::engine {

using VertexId = std::uint32_t;
using TetId = std::uint32_t;
using FaceRef = std::uint32_t;  // 4 * tet + face

inline constexpr VertexId kInfiniteVertex = 0xFFFFFFFFu;  // the symbolic vertex at infinity
inline constexpr TetId kNoTet = 0xFFFFFFFFu;
// The last vertex of a dead record where the store keeps no alive flags (TetStore::is_alive);
// never a point's id (triangulate refuses inputs that reach it).
inline constexpr VertexId kDeadVertex = 0xFFFFFFFEu;

// A tetrahedron's four vertex ids, as a record holds them.
using Quad = std::array<VertexId, 4>;

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

// The hot record: 32 bytes, two to a cache line. Whether it is alive, its lock word and its DAG
// children are kept beside it by the store (TetStore::is_alive, lock_word, children), each only
// where the mode needs it.
struct Tet {
  std::array<VertexId, 4> vertex{};
  std::array<FaceRef, 4> neighbor{};

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

static_assert(sizeof(Tet) == 32);

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

  TetStore() : blocks_(new std::atomic<char*>[kMaxBlocks]) {
    for (std::size_t i = 0; i < kMaxBlocks; ++i)
      blocks_[i].store(nullptr, std::memory_order_relaxed);
  }
  TetStore(const TetStore&) = delete;
  TetStore& operator=(const TetStore&) = delete;
  ~TetStore() {
    for (std::size_t i = 0; i < kMaxBlocks; ++i)
      free_block(blocks_[i].load(std::memory_order_relaxed));
  }

  // A slot is the record, then its lock word (parallel lock methods only), then its DAG children
  // (DAG mode only): 32 bytes for a sequential walk, 36 for a parallel one, 48 and 52 with the DAG.
  // Both in the slot so that locking or descending reads the record's own cache line.
  //
  // DAG children: the tetrahedra that replaced a dead one (kNoTet when unused). Written before
  // the tetrahedron is marked dead; published with release, read with acquire.
  using Children = std::array<std::atomic<TetId>, 4>;
  // Before the first allocation.
  void keep_children(bool keep) {
    children_ = keep;
    set_stride();
  }
  [[nodiscard]] bool has_children() const { return children_; }
  Children& children(TetId t) {
    return *std::launder(reinterpret_cast<Children*>(slot(t) + children_offset()));
  }
  // Lock words, one per slot, only for the parallel lock methods (4 bytes a slot that a
  // sequential run does not pay). Before the first allocation.
  void keep_lock_words(bool keep) {
    lock_words_ = keep;
    set_stride();
  }
  [[nodiscard]] bool has_lock_words() const { return lock_words_; }
  // Whether aliveness is the record's last vertex (kDeadVertex once dead): neither lock words nor
  // DAG children (is_alive says where else it is kept).
  [[nodiscard]] bool alive_in_record() const { return alive_in_record_; }

  // Whether slot t holds a live tetrahedron. Dead tetrahedra are DAG history (or, in walk mode,
  // free slots).
  // - Where other threads read the mesh (lock words): kAliveBit of the slot's lock word, in the
  //   record's cache line; release on death and birth, acquire on reading.
  // - Where only dead records are read (DAG children, one thread): a byte per slot, in an array
  //   after the block's slots (a byte in the slot would cost the alignment of the next record).
  // - A walk without lock words keeps neither: the sequential walk, and the partitioned method,
  //   whose threads never read a record another thread writes (methods/partition_sync.hpp).
  //   Nobody reads a dead record there while another thread writes it (the walk's remembered
  //   start and the legalization's stack ask first; a stale start from an earlier pass is asked
  //   after the threads were joined), so death writes kDeadVertex into the
  //   record's last vertex, and birth is writing the record. 32 bytes a slot instead of 33.
  // is_alive, set_alive, operator[] and the slot lookup are always inlined: a few instructions
  // each, called several times per flip, and GCC had left is_alive and set_alive out of line in
  // the sequential walk (a call per test).
  [[nodiscard, gnu::always_inline]] bool is_alive(
      TetId t, std::memory_order order = std::memory_order_acquire) const {
    if (alive_in_record_) return (*this)[t].vertex[3] != kDeadVertex;
    if (lock_words_) return (lock_word(t).load(order) & kAliveBit) != 0;
    return alive_flag(t).load(order);
  }
  // The order is a template argument: a run-time one makes GCC store with seq_cst (an xchg on
  // x86, a full barrier at each birth and death) wherever the call is not inlined, which it was
  // not in the optimistic methods' build.
  template <std::memory_order Order = std::memory_order_release>
  [[gnu::always_inline]] void set_alive(TetId t, bool alive) {
    if (alive_in_record_) {
      if (!alive) (*this)[t].vertex[3] = kDeadVertex;
      assert(!alive || (*this)[t].vertex[3] != kDeadVertex);  // born by writing the record
      return;
    }
    if (lock_words_) {
      // Only t's lock holder (or the only thread, or the creator of an unpublished slot) writes
      // its word, so a load and a store keep the owner's bits: other threads' compare-and-swaps
      // fail while it is held.
      std::atomic<std::uint32_t>& word = lock_word(t);
      const std::uint32_t w = word.load(std::memory_order_relaxed);
      word.store(alive ? (w | kAliveBit) : (w & ~kAliveBit), Order);
      return;
    }
    alive_flag(t).store(alive, Order);
  }
  // Where lock words exist, a tetrahedron's aliveness is this bit of its word (the lock methods
  // keep the other bits: methods/lock_words.hpp), read with the record's own cache line instead of
  // a byte array's.
  static constexpr std::uint32_t kAliveBit = 0x8000'0000U;
  // Owner of t's lock (thread id + 1; 0 when free) in the bits below kAliveBit and the lock
  // methods' own flag (methods/lock_table.hpp, kLogged). Only where has_lock_words().
  [[gnu::always_inline]] std::atomic<std::uint32_t>& lock_word(TetId t) const {
    assert(lock_words_);
    return *std::launder(reinterpret_cast<std::atomic<std::uint32_t>*>(slot(t) + sizeof(Tet)));
  }

  // Asks for slot t's cache lines ahead of use: its first and its last byte, since a slot of 36
  // or 52 bytes often spans two lines (the lock word, read first by a lock method, in the second).
  void prefetch(TetId t) const {
    const char* s = slot(t);
    __builtin_prefetch(s);
    __builtin_prefetch(s + stride_ - 1);
  }

  [[gnu::always_inline]] Tet& operator[](TetId t) {
    return *std::launder(reinterpret_cast<Tet*>(slot(t)));
  }
  [[gnu::always_inline]] const Tet& operator[](TetId t) const {
    return *std::launder(reinterpret_cast<const Tet*>(slot(t)));
  }

  // Reserves a fresh slot, dead until written and set alive (single writer in the sequential
  // engine; the parallel methods take slots with the atomic counter).
  TetId allocate() {
    const std::size_t t = size_.fetch_add(1, std::memory_order_relaxed);
    if (t >= capacity_) {
      throw StoreFull("the tetrahedron store is full: " + std::to_string(capacity_) +
                      " tetrahedra and DAG nodes" +
                      (capacity_ == kMaxTets ? " (2^30, the limit of 32-bit neighbour references)"
                                             : " (the capacity asked for)"));
    }
    ensure_block(t >> kBlockBits);
    if (alive_in_record_) (*this)[static_cast<TetId>(t)].vertex[3] = kDeadVertex;
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
    for (std::size_t t = first; alive_in_record_ && t < first + count; ++t) {
      (*this)[static_cast<TetId>(t)].vertex[3] = kDeadVertex;
    }
    // The run over a block's middle slot maps the next block ahead of need (one run, so one
    // thread): the threads that reach it later find it ready instead of waiting for its mapping.
    // Only a head start: when the system has no memory for it, the thread that needs the block
    // maps it (or reports that) later, and this run keeps its slots.
    const std::size_t next = (first >> kBlockBits) + 1;
    const std::size_t middle = ((next - 1) << kBlockBits) + kBlockSize / 2;
    if (first <= middle && middle < first + count && (next << kBlockBits) < capacity_) {
      try {
        ensure_block(next);
      } catch (const std::bad_alloc&) {  // ensure_block left the entry unmapped
      }
    }
    return static_cast<TetId>(first);
  }
  // The output step's copy without a second buffer: the vertices of block b's first `slots`
  // slots that keep(t) holds, passed through rename (VertexId -> VertexId), packed to the front
  // of the block's own memory in slot order (16 bytes each where a slot takes 32 or more, so a
  // quad never lands on a slot not read yet). The block holds no records afterwards: only
  // release_block_of may follow. Blocks are disjoint, so threads pack different ones at once.
  template <class Keep, class Rename>
  std::span<Quad> pack_quads(std::size_t b, std::size_t slots, Keep keep, Rename rename) {
    static_assert(sizeof(Quad) <= sizeof(Tet));
    char* const block = blocks_[b].load(std::memory_order_acquire);
    std::size_t packed = 0;
    for (std::size_t i = 0; i < slots; ++i) {
      const auto t = static_cast<TetId>((b << kBlockBits) + i);
      if (!keep(t)) continue;
      Quad q = (*this)[t].vertex;  // read whole before the write, which may overlap slot 0
      for (VertexId& v : q) v = rename(v);
      std::memcpy(block + packed * sizeof(Quad), &q, sizeof(Quad));
      ++packed;
    }
    return {std::launder(reinterpret_cast<Quad*>(block)), packed};
  }
  // Frees the block that holds slot t (the output step's last use of the store).
  void release_block_of(TetId t) {
    free_block(blocks_[t >> kBlockBits].exchange(nullptr, std::memory_order_acq_rel));
  }
  // Whether slot t's block is installed. An id below size() can lie in a block that the thread
  // that took it has not installed yet: a scan over ids (not reached through a reference) asks
  // this first.
  [[nodiscard]] bool has_block(TetId t) const {
    if ((t >> kBlockBits) >= kMaxBlocks) return false;
    const char* block = blocks_[t >> kBlockBits].load(std::memory_order_acquire);
    return block != nullptr && block != being_mapped();
  }
  // Slots handed out (a refused allocate counted no slot).
  [[nodiscard]] std::size_t size() const {
    const std::size_t n = size_.load(std::memory_order_relaxed);
    return n < capacity_ ? n : capacity_;
  }
  [[nodiscard]] std::size_t capacity() const { return capacity_; }
  // Blocks mapped so far (each once, however many threads needed it at the same time).
  [[nodiscard]] std::size_t blocks_mapped() const {
    return blocks_mapped_.load(std::memory_order_relaxed);
  }
  // A smaller capacity (a memory cap; tests reach the limit with it). Before the first allocate.
  void set_capacity(std::size_t tets) { capacity_ = tets < kMaxTets ? tets : kMaxTets; }
  // Tests only: the next slot is `first` (its block is allocated on demand), to reach the 2^30
  // boundary without allocating 2^30 slots. Before the first allocate.
  void skip_to_for_testing(std::size_t first) { size_.store(first, std::memory_order_relaxed); }

 private:
  // A block is mapped by one thread: the first to need it marks its entry being_mapped() and
  // maps it (new_block touches every page of a parallel run's block); a thread that needs it
  // meanwhile waits. (When every thread that needed it mapped its own copy and all but one unmapped
  // theirs, up to 16 threads faulted in a copy each of a block, and each unmapping interrupted
  // every core for its TLBs.) Waits are rare: allocate_run maps each next block ahead.
  void ensure_block(std::size_t block) {
    std::atomic<char*>& entry = blocks_[block];
    while (true) {
      char* seen = entry.load(std::memory_order_acquire);
      if (seen == being_mapped()) {
        std::this_thread::yield();
        continue;
      }
      if (seen != nullptr) return;
      if (!entry.compare_exchange_strong(seen, being_mapped(), std::memory_order_acquire)) {
        continue;
      }
      try {
        char* fresh = new_block();
        blocks_mapped_.fetch_add(1, std::memory_order_relaxed);
        entry.store(fresh, std::memory_order_release);  // the block's objects before its address
      } catch (...) {
        entry.store(nullptr, std::memory_order_release);  // a waiting thread tries itself
        throw;
      }
      return;
    }
  }
  // The mark of a block entry whose block one thread is mapping: never a block's address.
  static char* being_mapped() {
    static char mark = 0;
    return &mark;
  }

  // Blocks are mapped from the system directly (2 MiB for a sequential walk, 3.3 with DAG
  // children and lock words), not from the heap: a
  // released block goes back to the system at once, which is what lets take_finite_tetrahedra
  // build the output in the memory the store gives up. (malloc would serve them from its heap
  // once a larger block had been freed, and keep them there.)
  // A block: kBlockSize slots (stride_ bytes each), then their alive flags (1 byte each) unless
  // the records or their lock words carry them.
  [[nodiscard, gnu::always_inline]] char* block_of(TetId t) const {
    return blocks_[t >> kBlockBits].load(std::memory_order_acquire);
  }
  [[nodiscard, gnu::always_inline]] char* slot(TetId t) const {
    return block_of(t) + (t & (kBlockSize - 1)) * stride_;
  }
  std::atomic<bool>& alive_flag(TetId t) const {
    return *std::launder(reinterpret_cast<std::atomic<bool>*>(block_of(t) + alive_offset() +
                                                              (t & (kBlockSize - 1))));
  }
  [[nodiscard]] std::size_t alive_offset() const { return kBlockSize * stride_; }
  [[nodiscard]] std::size_t block_bytes() const {
    return alive_offset() + (alive_in_record_ || lock_words_ ? 0 : kBlockSize);
  }
  [[nodiscard]] std::size_t children_offset() const {
    return sizeof(Tet) + (lock_words_ ? sizeof(std::uint32_t) : 0);
  }
  void set_stride() {
    stride_ = children_offset() + (children_ ? sizeof(Children) : 0);
    alive_in_record_ = !children_ && !lock_words_;
  }
  char* new_block() const {
    void* memory =
        mmap(nullptr, block_bytes(), PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (memory == MAP_FAILED) throw std::bad_alloc();
    char* block = static_cast<char*>(memory);
    // Records alone (a sequential walk) are implicit-lifetime aggregates on zeroed pages: they
    // are marked dead as they are handed out (allocate), so that a block's pages are touched only
    // as far as it is used.
    if (alive_in_record_) return block;
    for (std::size_t i = 0; i < kBlockSize; ++i) {
      new (block + i * stride_) Tet();
      if (lock_words_) new (block + i * stride_ + sizeof(Tet)) std::atomic<std::uint32_t>(0);
      if (children_) new (block + i * stride_ + children_offset()) Children{};
      if (!lock_words_) new (block + alive_offset() + i) std::atomic<bool>(false);
    }
    return block;
  }
  void free_block(char* block) const {
    static_assert(std::is_trivially_destructible_v<Tet> &&
                  std::is_trivially_destructible_v<Children> &&
                  std::is_trivially_destructible_v<std::atomic<bool>> &&
                  std::is_trivially_destructible_v<std::atomic<std::uint32_t>>);
    if (block != nullptr && block != being_mapped()) munmap(block, block_bytes());
  }

  std::unique_ptr<std::atomic<char*>[]> blocks_;
  std::atomic<std::size_t> size_{0};
  std::atomic<std::size_t> blocks_mapped_{0};
  bool children_ = true;
  bool lock_words_ = true;
  bool alive_in_record_ = false;  // neither lock words nor children: a walk without lock words
  std::size_t stride_ = sizeof(Tet) + sizeof(std::uint32_t) + sizeof(Children);  // per slot
  std::size_t capacity_ = kMaxTets;
};

}  // namespace dtlab::engine
