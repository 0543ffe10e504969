#pragma once
// What the three optimistic lock methods' policies share (optimistic_detect.hpp,
// optimistic_prevent.hpp, burglary.hpp): one thread's side of the per-tetrahedron lock words, taken
// by compare-and-swap, the list of words it holds, the registration of its waits in the
// LockTable, and the random delays of --stress. Each method's policy derives from it and adds
// what it does when a word is taken: wait with cycle detection, give way by priority, or burgle.
//
// A lock word (TetStore::lock_word) is the owner's id (thread + 1; 0 when free), plus
// LockTable::kLogged once the owner has saved the tetrahedron in its undo log, plus the
// tetrahedron's aliveness in the top bit (TetStore::kAliveBit), which only the owner changes and
// every other write keeps.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <random>
#include <thread>
#include <vector>

#include "dtlab/engine/stats.hpp"
#include "mesh/shared_mesh.hpp"
#include "mesh/tet_id_list.hpp"
#include "methods/lock_table.hpp"

namespace dtlab::engine {

class LockWords {
 public:
  static constexpr bool kLocks = true;

  LockWords(SharedMesh& mesh, LockTable& table, std::uint32_t self, ThreadStats& stats, bool stress)
      : mesh_(mesh), table_(table), self_(self), stats_(stats), stress_(stress), rng_(self) {}

 protected:
  // The loop of optimistic-detect's and optimistic-prevent's acquire(): takes t's word, or, while
  // another thread holds it, counts the wait and asks `on_held(owner, t)` whether to keep waiting
  // (true) or to give the insertion up (false). The watchdog's stop gives up too.
  template <class OnHeld>
  [[gnu::always_inline]] bool take_or_wait(TetId t, OnHeld&& on_held) {
    std::atomic<std::uint32_t>& word = mesh_.tets.lock_word(t);
    if (owns(word)) return true;
    bool waited = false;
    for (std::uint64_t spin = 0;; ++spin) {
      std::uint32_t seen = 0;
      if (try_take(word, seen)) [[likely]] {
        held_.push_back(t);
        if (waited) withdraw_wait();
        maybe_delay();
        return true;
      }
      const std::uint32_t owner = LockTable::owner_of(seen);
      if (owner == 0) continue;  // freed between the load and the compare-and-swap
      if (owner == self_) return true;
      if (stopped()) {
        withdraw_wait();
        return false;
      }
      count_wait(waited);
      if (!on_held(owner, t)) return false;
      if (spin > 64) std::this_thread::yield();
    }
  }

  // Only this thread ever stores self_, so a relaxed load that sees it is exact.
  [[nodiscard]] bool owns(const std::atomic<std::uint32_t>& word) const {
    return LockTable::owner_of(word.load(std::memory_order_relaxed)) == self_;
  }
  // One attempt to take a free word: free is no owner, the aliveness as the last owner left it
  // (only an owner changes it). acquire: what the previous owner wrote under the lock is visible
  // from here on. On failure `seen` is the word as found.
  bool try_take(std::atomic<std::uint32_t>& word, std::uint32_t& seen) {
    seen = word.load(std::memory_order_relaxed) & LockTable::kAlive;
    return word.compare_exchange_strong(seen, seen | self_, std::memory_order_acq_rel,
                                        std::memory_order_acquire);
  }
  [[nodiscard]] bool stopped() const { return table_.stop.load(std::memory_order_relaxed); }
  // The first time an acquire finds its word taken, it counts one wait.
  void count_wait(bool& waited) {
    if (!waited) {
      waited = true;
      ++stats_.waits;
    }
  }
  // Withdraws this thread's registered wait (detect and prevent: nobody else writes it).
  void withdraw_wait() { table_.waiting_for[self_].store(0, std::memory_order_relaxed); }

  // Registers "self waits for owner, for t" and follows the chain (find_cycle); the caller holds
  // table.cycle, so that registration and check are one step and of the threads that close a
  // cycle the last one sees it. A stale chain is only counted.
  Cycle register_wait_locked(std::uint32_t owner, TetId t) {
    table_.waiting_on[self_] = t;
    table_.waiting_for[self_].store(owner, std::memory_order_release);
    const Cycle cycle = find_cycle(mesh_, table_, self_, chain_);
    if (cycle == Cycle::Stale) ++stats_.stale_cycles;
    return cycle;
  }

  // Lets every held word go by a plain store (release: this thread's writes are visible to the
  // next owner). Nobody else writes a word this thread holds, so no locked instruction per
  // tetrahedron; the aliveness stays in the word.
  void release_held() {
    for (const TetId t : held_) {
      std::atomic<std::uint32_t>& word = mesh_.tets.lock_word(t);
      word.store(word.load(std::memory_order_relaxed) & LockTable::kAlive,
                 std::memory_order_release);
    }
    held_.clear();
  }

  // --stress: a short random delay after one lock in 16, while it is held, to shake out races.
  void maybe_delay() {
    if (!stress_) return;
    if (std::uniform_int_distribution<int>(0, 15)(rng_) == 0) {
      std::this_thread::sleep_for(
          std::chrono::microseconds(std::uniform_int_distribution<int>(1, 50)(rng_)));
    }
  }

  SharedMesh& mesh_;
  LockTable& table_;
  std::uint32_t self_;
  ThreadStats& stats_;
  bool stress_;
  std::minstd_rand rng_;
  TetIdList held_;
  std::vector<std::uint32_t> chain_;  // find_cycle's scratch
};

}  // namespace dtlab::engine
