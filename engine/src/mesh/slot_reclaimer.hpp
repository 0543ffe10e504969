#pragma once
// Epoch-based reclamation of tetrahedron slots for the parallel walk mode (docs/design.md, "Walk
// mode"). A thread's operation (one insertion attempt, or one location of the batch method's
// locating threads) is bracketed by enter() and leave(). A slot dies inside the operation of the
// thread that kills it, which entered at epoch a; it is reused only once the global epoch is
// a + 3. The epoch moves from e to e + 1 only when every thread inside an operation entered it at
// e, so while the killer is inside the epoch is at most a + 1, and any other thread that may still
// hold a reference read before the unlink became visible to it entered at a + 1 at the latest: it
// must have left before the epoch can reach a + 3. (a + 2 is not enough: a thread may enter at
// a + 1, even after the killer left, without synchronizing with the killer's unlinking store, and
// the epoch may reach a + 2 while it is inside.) Operations that enter at a + 2 or later read an
// epoch whose advance saw the killer leave, so they see the unlink: they start from a live
// tetrahedron and follow neighbour references, and a slot is retired only after it was unlinked
// from every live tetrahedron.
#include <atomic>
#include <cassert>
#include <cstdint>
#include <deque>
#include <memory>

#include "mesh/tet_id_list.hpp"
#include "mesh/tet_store.hpp"

namespace dtlab::engine {

class EpochDomain {
 public:
  static constexpr std::uint64_t kQuiescent = ~std::uint64_t{0};
  explicit EpochDomain(int threads)
      : announced_(new Announcement[static_cast<std::size_t>(threads)]), threads_(threads) {}
  std::atomic<std::uint64_t>& announced(int thread) {
    return announced_[static_cast<std::size_t>(thread)].epoch;
  }
  std::atomic<std::uint64_t> epoch{2};

  // Advances the epoch when every thread inside an operation entered it at the current one.
  void try_advance() {
    std::uint64_t current = epoch.load(std::memory_order_acquire);
    for (int i = 0; i < threads_; ++i) {
      const std::uint64_t a = announced(i).load(std::memory_order_acquire);
      if (a != kQuiescent && a != current) return;
    }
    epoch.compare_exchange_strong(current, current + 1, std::memory_order_acq_rel);
  }

 private:
  struct alignas(64) Announcement {  // one cache line per thread
    std::atomic<std::uint64_t> epoch{kQuiescent};
  };
  std::unique_ptr<Announcement[]> announced_;
  int threads_;
};

// One thread's side: its announcement, and the slots it retired, oldest first.
class SlotReclaimer {
 public:
  SlotReclaimer(EpochDomain& domain, int thread)
      : domain_(domain), mine_(domain.announced(thread)) {}

  void enter() {
    if (inside_) return;
    inside_ = true;
    // seq_cst: the announcement is visible to every advancing thread before this thread reads
    // the mesh (a store-load order that acquire and release alone do not give).
    entered_ = domain_.epoch.load(std::memory_order_seq_cst);
    mine_.store(entered_, std::memory_order_seq_cst);
  }
  void leave() {
    if (!inside_) return;
    inside_ = false;
    mine_.store(EpochDomain::kQuiescent, std::memory_order_release);
  }
  // t died in this thread's current operation: tagged with the epoch the operation entered at.
  void retire(TetId t) {
    assert(inside_);
    limbo_.push_back({t, entered_});
  }
  // Moves the slots that no operation can reach any more to `free`.
  void collect(TetIdList& free) {
    if ((++collections_ & 63) == 0) domain_.try_advance();
    const std::uint64_t now = domain_.epoch.load(std::memory_order_acquire);
    while (!limbo_.empty() && limbo_.front().epoch + 3 <= now) {
      free.push_back(limbo_.front().tet);
      limbo_.pop_front();
    }
  }

 private:
  struct Retired {
    TetId tet;
    std::uint64_t epoch;
  };
  EpochDomain& domain_;
  std::atomic<std::uint64_t>& mine_;
  std::deque<Retired> limbo_;
  std::uint64_t collections_ = 0;
  std::uint64_t entered_ = 0;  // the epoch the current operation announced
  bool inside_ = false;
};

}  // namespace dtlab::engine
