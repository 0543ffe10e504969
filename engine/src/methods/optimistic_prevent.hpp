#pragma once
// optimistic-prevent (paper Sect. 5): deadlocks are prevented instead of detected. Every thread
// has a priority; a thread that holds a lock never waits for a thread of higher priority (ties:
// the lower id wins), it gives its insertion up (undo log) and raises its own priority, so that
// it wins later. A thread that holds no lock waits: nobody waits for it, so its wait closes no
// cycle. run_optimistic_prevent (registered in registry.cpp) runs it on the optimistic worker loop.
#include <atomic>
#include <cstdint>

#include "methods/undo_log_sync.hpp"

namespace dtlab::engine {

class PreventSync : public UndoLogSync {
 public:
  using UndoLogSync::UndoLogSync;

  // Takes t's lock; false when the insertion must be given up (a thread of higher priority
  // holds t while this one holds a lock, or the watchdog's stop).
  bool acquire(TetId t) {
    return take_or_wait(t, [&](std::uint32_t owner, TetId /*held*/) {
      if (held_.empty()) return true;
      const std::uint64_t mine = table_.priority[self_].load(std::memory_order_relaxed);
      const std::uint64_t theirs = table_.priority[owner].load(std::memory_order_relaxed);
      if (theirs < mine || (theirs == mine && owner > self_)) return true;
      table_.priority[self_].fetch_add(1, std::memory_order_relaxed);
      ++stats_.priority_raises;
      withdraw_wait();
      return false;
    });
  }
};

}  // namespace dtlab::engine
