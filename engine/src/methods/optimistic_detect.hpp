#pragma once
// optimistic-detect (paper Sect. 5, Fig. 6): a thread that finds a lock taken waits for it,
// registering the wait in the LockTable; when its wait closes a cycle of waits (a deadlock,
// confirmed by find_cycle) it gives its insertion up (undo log) and retries the point later.
// run_optimistic_detect (registered in registry.cpp) runs it on the optimistic worker loop.
#include <atomic>
#include <cstdint>
#include <mutex>

#include "methods/undo_log_sync.hpp"

namespace dtlab::engine {

class DetectSync : public UndoLogSync {
 public:
  using UndoLogSync::UndoLogSync;

  // Takes t's lock; false when the insertion must be given up (a real deadlock, or the
  // watchdog's stop).
  bool acquire(TetId t) {
    std::uint32_t registered_owner = 0;
    return take_or_wait(t, [&](std::uint32_t owner, TetId held) {
      // (Re-)register only when the owner changes: whoever closes a cycle later sees it.
      if (owner == registered_owner) return true;
      registered_owner = owner;
      if (!deadlocked(owner, held)) return true;
      ++stats_.deadlocks;
      return false;  // the wait is withdrawn already
    });
  }

 private:
  // Registers the wait and checks for a cycle; a real one is withdrawn inside the critical
  // section, so that the partner does not see this wait and give up too (both giving up could
  // repeat forever). Out of line: the wait's slow path, kept out of acquire()'s registers.
  [[gnu::noinline]] bool deadlocked(std::uint32_t owner, TetId t) {
    std::lock_guard<std::mutex> guard(table_.cycle);
    if (register_wait_locked(owner, t) != Cycle::Real) return false;
    table_.waiting_for[self_].store(0, std::memory_order_relaxed);
    return true;
  }
};

}  // namespace dtlab::engine
