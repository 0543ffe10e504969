#pragma once
// Where an inserting thread's new tetrahedra get their slots, and where its dead ones go.
// DAG mode: fresh slots only, never reused (the dead tetrahedra are the DAG). Walk mode: the
// slots an insertion killed are reused once it has ended (its legalization stack may name them
// until then); on a shared mesh only after the epochs say no other thread's operation can reach
// them (slot_reclaimer.hpp), unless the thread's reads are confined (mesh/read_confinement.hpp:
// nobody else reaches its dead slots, reused at once). Fresh slots come in runs from the store
// (kFirstSlotRun doubling to kLongestSlotRun): one atomic step per run, and one thread's records
// share cache lines and mostly pages only with its own.
#include <algorithm>
#include <cassert>
#include <cstddef>

#include "mesh/slot_reclaimer.hpp"
#include "mesh/tet_id_list.hpp"
#include "mesh/tet_store.hpp"

namespace dtlab::engine {

class SlotAllocator {
 public:
  // recycle: reuse dead slots; reclaimer: a shared mesh's epochs (nullptr for the owning engine,
  // for a thread that reads only what it alone writes, and for an engine that keeps every slot);
  // track_attempts: an attempt can be rolled back, and its new slots are then free again (where
  // slots are reused).
  SlotAllocator(TetStore& store, bool recycle, SlotReclaimer* reclaimer, bool track_attempts)
      : store_(store),
        recycle_(recycle),
        reclaimer_(reclaimer),
        track_attempts_((track_attempts && recycle) || reclaimer != nullptr) {}

  // An operation reads the mesh (a location, an insertion attempt): the epochs protect what it
  // reaches until it ends. Entering twice is one operation (the pessimistic method's lock-free
  // walk and its insertion).
  void begin_operation() {
    if (reclaimer_ != nullptr) reclaimer_->enter();
  }
  void end_operation() {
    if (reclaimer_ != nullptr) reclaimer_->leave();
  }
  void begin_insertion() {
    begin_operation();
    attempt_created_.clear();
  }
  // undone: the attempt was rolled back (the tetrahedra it killed are alive again, the ones it
  // created are dead); else the tetrahedra it killed are dead for good.
  void end_insertion(bool undone) {
    if (recycle_) {
      for (const TetId t : undone ? attempt_created_ : retired_) release(t);
      retired_.clear();
    }
    if (reclaimer_ != nullptr) {
      reclaimer_->leave();
      reclaimer_->collect(free_slots_);
    }
  }

  // A free slot: a reused one, else the next of this thread's run of fresh slots.
  // Always inlined (out of line it was a call per new tetrahedron, and GCC's choice changed
  // with the caller's size); a new run of fresh slots is the call.
  [[gnu::always_inline]] TetId allocate() {
    TetId id = kNoTet;
    if (!free_slots_.empty()) {
      id = free_slots_.pop_back();
    } else {
      if (run_next_ == run_end_) [[unlikely]]
        next_run();
      id = run_next_++;
    }
    if (track_attempts_) attempt_created_.push_back(id);
    return id;
  }
  // t, the last slot this attempt allocated, was never published (nothing references it, and
  // it is dead): free again at once, also on a shared mesh.
  void give_back(TetId t) {
    if (track_attempts_) {
      assert(!attempt_created_.empty() && attempt_created_.back() == t);
      (void)attempt_created_.pop_back();
    }
    free_slots_.push_back(t);
  }
  // t died in the current insertion (walk mode). Always inlined, like allocate.
  [[gnu::always_inline]] void retire(TetId t) { retired_.push_back(t); }

  // A thread's runs of fresh slots start at kFirstSlotRun and double up to kLongestSlotRun. Whole
  // runs keep one thread's records on cache lines of its own; long ones also keep them on pages
  // of its own: with runs of 64 slots (2 KiB at 32 bytes) two threads' runs alternated within
  // each 4 KiB page, every page a thread wrote held the other's records too, and a 2-thread
  // partitioned run was 2.5-7 % slower (uniform:1000000, docs/performance-log.md, sixteenth
  // session). Short first runs keep a small run's unused tail small: what a thread leaves
  // unused at the end (dead, never alive) is less than its last run.
  static constexpr std::size_t kFirstSlotRun = 64;
  static constexpr std::size_t kLongestSlotRun = 1024;

 private:
  [[gnu::noinline]] void next_run() {
    std::size_t count = 0;
    run_next_ = store_.allocate_run(run_length_, count);
    run_end_ = run_next_ + static_cast<TetId>(count);
    run_length_ = std::min(2 * run_length_, kLongestSlotRun);
  }
  // A dead slot: free at once for the owning engine, after the epochs on a shared mesh.
  void release(TetId t) {
    if (reclaimer_ != nullptr) {
      reclaimer_->retire(t);
    } else {
      free_slots_.push_back(t);
    }
  }

  TetStore& store_;
  bool recycle_;
  SlotReclaimer* reclaimer_;
  bool track_attempts_;
  TetIdList free_slots_;
  TetIdList retired_;          // killed by the current insertion
  TetIdList attempt_created_;  // taken by the current attempt (track_attempts_ only)
  TetId run_next_ = 0;         // this thread's run of fresh slots: [run_next_, run_end_)
  TetId run_end_ = 0;
  std::size_t run_length_ = kFirstSlotRun;  // of the next run
};

}  // namespace dtlab::engine
