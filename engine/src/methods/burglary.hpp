#pragma once
// Burglary (paper Sect. 5, docs/design.md): optimistic locking without an undo log. A thread
// whose wait closes a cycle marks its counterpart, who is then parked in acquire() and writes
// nothing, as burgled and takes its locks (the picklock). The victim releases the rest, waits
// until the burglar's insertion ends, takes back the tetrahedra it had created and checks that
// they are all still alive. If they are, its remaining legalization is still valid and goes on;
// if not, it stops, counts a potential problem and marks the suspicious tetrahedra for the
// sequential post-check (methods/burglary_post_check.hpp). Every write still happens under a lock
// its writer holds, so the mesh stays consistent. run_burglary (registered in registry.cpp) runs it
// on the optimistic worker loop, then the post-check.
#include <algorithm>
#include <atomic>
#include <cassert>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#include "insertion/sync.hpp"
#include "methods/lock_words.hpp"

namespace dtlab::engine {

class BurglarySync : public LockWords {
 public:
  using LockWords::LockWords;

  // Takes t's lock; false when the insertion must be given up, or this thread was burgled (see
  // resume()).
  bool acquire(TetId t) {
    std::atomic<std::uint32_t>& word = mesh_.tets.lock_word(t);
    if (owns(word)) return true;
    bool waited = false;
    std::uint32_t registered_owner = 0;
    for (std::uint64_t spin = 0;; ++spin) {
      std::uint32_t seen = 0;
      if (try_take(word, seen)) {
        held_.push_back(t);
        if (waited && !stop_waiting()) return false;  // burgled after all: keep t in held_
        maybe_delay();
        return true;
      }
      std::uint32_t owner = LockTable::owner_of(seen);
      if (owner == 0) continue;  // freed between the load and the compare-and-swap
      if (owner == self_) return true;
      if (stopped()) {
        stop_waiting();
        return false;
      }
      if (burgled()) return false;
      // The picklock: a victim of this thread holds t (burglary never sets kLogged, so the word
      // is the owner and the aliveness).
      if (table_.waiting_for[owner].load(std::memory_order_acquire) ==
              (LockTable::kBurgled | self_) &&
          word.compare_exchange_strong(seen, (seen & LockTable::kAlive) | self_,
                                       std::memory_order_acq_rel, std::memory_order_acquire)) {
        held_.push_back(t);
        return !waited || stop_waiting();
      }
      owner = LockTable::owner_of(seen);  // as the picklock's compare-and-swap found it
      if (owner == 0) continue;           // released meanwhile: take it normally
      count_wait(waited);
      if (owner != registered_owner) {
        // (Re-)register only when the owner changes: whoever closes a cycle later sees it.
        registered_owner = owner;
        const Wait wait = register_wait(owner, t);
        if (wait == Wait::Burgled) return false;
        if (wait == Wait::Burgling) registered_owner = 0;  // re-read the owner, then pick
      }
      if (spin > 64) std::this_thread::yield();
    }
  }

  void before_write(TetId /*t*/) {}  // no undo

  // last_write: this replacement ends the insertion (a cavity's), so neither rollback() nor
  // resume() can follow it and the lists they read need not hold t.
  void created(TetId t, bool last_write = false) {
    // Owned before it is published: nobody can lock it before this thread lets go. Not alive yet
    // (the replacement sets it alive once linked).
    mesh_.tets.lock_word(t).store(self_, std::memory_order_relaxed);
    held_.push_back(t);
    if (last_write) {
      ended_ = true;
    } else {
      created_.push_back(t);
    }
  }

  // t, alive until now, dies by this thread's own write.
  void killed(TetId t, bool last_write = false) {
    if (!last_write) own_kills_.push_back(t);
  }

  void commit() {
    created_.clear();
    own_kills_.clear();
    release_all();
    ended_ = false;
    end_phase();
  }

  // Only ever called before the insertion's first write: nothing to undo. A victim burgled there
  // (always so for a point inserted by a cavity, whose writes all come after its last lock; not
  // for the fast kernel's fallbacks to flips) lost nothing: it tries the point again after the
  // burglar's insertion.
  void rollback() {
    assert(!ended_);  // nothing after a last write can be refused
    created_.clear();
    own_kills_.clear();
    release_all();
    end_phase();
    if (burgled()) {
      ++stats_.burgled;
      wait_for_burglar();
    }
  }

  // A lock was refused in the middle of legalization: this thread was burgled. It releases
  // everything, waits for the burglar's insertion to end, takes back the tetrahedra it created
  // and checks them: all alive means the rest of its legalization is still valid.
  Resume resume() {
    assert(!ended_);
    ++stats_.burgled;
    std::vector<TetId> mine;
    for (const TetId c : created_) {
      if (std::find(own_kills_.begin(), own_kills_.end(), c) == own_kills_.end()) mine.push_back(c);
    }
    for (;;) {
      release_all();
      end_phase();
      if (burgled()) wait_for_burglar();
      if (stopped()) return Resume::Stop;
      bool refused = false;
      for (const TetId c : mine) {
        if (!acquire(c)) {
          refused = true;
          break;
        }
      }
      if (refused) continue;  // burgled again (or a deadlock broken by someone else): repeat
      for (const TetId c : mine) {
        if (!mesh_.tets.is_alive(c, std::memory_order_acquire)) {
          ++stats_.potential_problems;
          return Resume::Stop;
        }
      }
      return Resume::Continue;
    }
  }

  // A tetrahedron whose faces the sequential post-check must legalize (a dead one stands for the
  // live tetrahedra below it in the DAG).
  void mark_suspicious(TetId t) {
    suspicious_.push_back(t);
    ++stats_.suspicious_tetrahedra;
  }
  [[nodiscard]] const std::vector<TetId>& suspicious() const { return suspicious_; }

 private:
  enum class Wait { Waiting, Burgled, Burgling };

  // Withdraws this thread's registered wait; false when a burglar got there first.
  bool stop_waiting() {
    std::atomic<std::uint32_t>& status = table_.waiting_for[self_];
    std::uint32_t current = status.load(std::memory_order_acquire);
    while ((current & LockTable::kBurgled) == 0) {
      if (status.compare_exchange_weak(current, 0, std::memory_order_acq_rel,
                                       std::memory_order_acquire)) {
        return true;
      }
    }
    return false;
  }

  [[nodiscard]] bool burgled() const {
    return (table_.waiting_for[self_].load(std::memory_order_acquire) & LockTable::kBurgled) != 0;
  }

  // Registers "self waits for owner, for t" and checks for a cycle (register_wait_locked). A real
  // one: self breaks into `owner`, which is parked in acquire() and writes nothing until this
  // insertion ends. A stale chain: self waits on, and registers again when t's owner changes.
  Wait register_wait(std::uint32_t owner, TetId t) {
    std::lock_guard<std::mutex> guard(table_.cycle);
    std::atomic<std::uint32_t>& status = table_.waiting_for[self_];
    if ((status.load(std::memory_order_acquire) & LockTable::kBurgled) != 0) return Wait::Burgled;
    if (register_wait_locked(owner, t) != Cycle::Real) return Wait::Waiting;
    // `owner` cannot get its lock now (find_cycle), but it may still withdraw on the watchdog's
    // stop: the compare-and-swap decides, and a running owner is never burgled.
    std::uint32_t expected = table_.waiting_for[owner].load(std::memory_order_acquire);
    if (expected == 0 || (expected & LockTable::kBurgled) != 0) return Wait::Waiting;
    table_.burgled_in_phase[owner].store(table_.phase[self_].load(std::memory_order_relaxed),
                                         std::memory_order_relaxed);
    if (!table_.waiting_for[owner].compare_exchange_strong(expected, LockTable::kBurgled | self_,
                                                           std::memory_order_acq_rel,
                                                           std::memory_order_acquire)) {
      return Wait::Waiting;
    }
    status.store(0, std::memory_order_release);
    ++stats_.deadlocks;
    ++stats_.burglaries;
    return Wait::Burgling;
  }

  // phase[self] counts the insertions (or parts of one) this thread has ended; a victim waits
  // until its burglar's phase moves on.
  void end_phase() { table_.phase[self_].fetch_add(1, std::memory_order_acq_rel); }

  // The victim holds no lock here, so nobody waits for it and this wait closes no cycle.
  void wait_for_burglar() {
    std::atomic<std::uint32_t>& status = table_.waiting_for[self_];
    const std::uint32_t burglar = status.load(std::memory_order_acquire) & ~LockTable::kBurgled;
    const std::uint64_t phase = table_.burgled_in_phase[self_].load(std::memory_order_relaxed);
    for (std::uint64_t spin = 0; table_.phase[burglar].load(std::memory_order_acquire) == phase;
         ++spin) {
      if (stopped()) break;
      if (spin > 64) std::this_thread::yield();
    }
    status.store(0, std::memory_order_release);
  }

  // A burglar takes only the locks of a thread it marked burgled while that thread waited, and
  // such a thread gives its attempt up. An insertion that reached its last write (a cavity's) was
  // never burgled, so every word it holds is its own: those are released by plain stores.
  void release_all() {
    if (ended_) {
      release_held();
      return;
    }
    for (const TetId t : held_) {
      // release, as in release_held. A compare-and-swap, because a burglar may have taken the
      // lock meanwhile (then it is the burglar's to release).
      std::atomic<std::uint32_t>& word = mesh_.tets.lock_word(t);
      std::uint32_t expected = word.load(std::memory_order_relaxed);
      if (LockTable::owner_of(expected) != self_) continue;
      word.compare_exchange_strong(expected, expected & LockTable::kAlive,
                                   std::memory_order_release, std::memory_order_relaxed);
    }
    held_.clear();
  }

  TetIdList created_;
  bool ended_ = false;  // a last write happened in this insertion (checked in debug builds)
  std::vector<TetId> own_kills_;   // created tetrahedra this thread itself replaced
  std::vector<TetId> suspicious_;  // marks for the post-check
};

}  // namespace dtlab::engine
