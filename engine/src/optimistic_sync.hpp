#pragma once
// The synchronization policy of the optimistic methods (paper Fig. 6): per-tetrahedron lock
// words taken by compare-and-swap, waiting with deadlock detection (a wait-for cycle check in a
// short critical section) or deadlock prevention (priorities), and an undo log so that a thread
// that must not wait gives its insertion up and restores the mesh exactly.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <random>
#include <thread>
#include <vector>

#include "dtlab/engine/tet_mesh.hpp"
#include "dtlab/engine/triangulate.hpp"
#include "shared_mesh.hpp"

namespace dtlab::engine {

// State shared by all threads of one run.
struct LockTable {
  explicit LockTable(int threads)
      : waiting_for(static_cast<std::size_t>(threads) + 1),
        priority(static_cast<std::size_t>(threads) + 1) {}
  // waiting_for[i]: the thread that thread i waits for (0: none). Written and followed under
  // `cycle` so that the last thread to close a cycle always sees it (no false negatives).
  std::vector<std::atomic<std::uint32_t>> waiting_for;
  std::vector<std::atomic<std::uint64_t>> priority;  // prevent: higher wins
  std::mutex cycle;
  std::atomic<bool> stop{false};  // watchdog: give everything up
};

class OptimisticSync {
 public:
  static constexpr bool kLocks = true;
  enum class Mode { Detect, Prevent };

  OptimisticSync(SharedMesh& mesh, LockTable& table, std::uint32_t self, Mode mode,
                 ThreadStats& stats, bool stress)
      : mesh_(mesh),
        table_(table),
        self_(self),
        mode_(mode),
        stats_(stats),
        stress_(stress),
        rng_(self) {}

  // Takes t's lock; false when the insertion must be given up.
  bool acquire(TetId t) {
    std::atomic<std::uint32_t>& word = mesh_.tets[t].lock_owner;
    bool waited = false;
    std::uint32_t registered_owner = 0;
    for (std::uint64_t spin = 0;; ++spin) {
      std::uint32_t owner = 0;
      // acquire: what the previous owner wrote under the lock is visible from here on.
      if (word.compare_exchange_strong(owner, self_, std::memory_order_acq_rel,
                                       std::memory_order_acquire)) {
        held_.push_back(t);
        if (waited) table_.waiting_for[self_].store(0, std::memory_order_relaxed);
        maybe_delay();
        return true;
      }
      if (owner == self_) return true;
      if (table_.stop.load(std::memory_order_relaxed)) return stop_waiting();
      if (!waited) {
        waited = true;
        ++stats_.waits;
      }
      if (mode_ == Mode::Prevent) {
        // Never wait for a thread of higher priority (ties: the lower id wins).
        const std::uint64_t mine = table_.priority[self_].load(std::memory_order_relaxed);
        const std::uint64_t theirs = table_.priority[owner].load(std::memory_order_relaxed);
        if (theirs > mine || (theirs == mine && owner < self_)) {
          table_.priority[self_].fetch_add(1, std::memory_order_relaxed);
          ++stats_.priority_raises;
          return stop_waiting();
        }
      } else if (owner != registered_owner) {
        // (Re-)register only when the owner changes: whoever closes a cycle later sees it.
        registered_owner = owner;
        if (would_deadlock(owner)) {
          ++stats_.deadlocks;
          return false;  // would_deadlock already withdrew the wait
        }
      }
      if (spin > 64) std::this_thread::yield();
    }
  }

  void before_write(TetId t) {
    for (const Saved& s : log_) {
      if (s.tet == t) return;
    }
    for (const TetId c : created_) {
      if (c == t) return;  // retired as a whole on rollback
    }
    const Tet& tet = mesh_.tets[t];
    Saved s{t, tet.neighbor, {}, tet.alive.load(std::memory_order_relaxed)};
    for (std::size_t i = 0; i < 4; ++i) s.child[i] = tet.child[i].load(std::memory_order_relaxed);
    log_.push_back(s);
  }

  void created(TetId t) {
    // Owned before it is published: nobody can lock it before this thread lets go.
    mesh_.tets[t].lock_owner.store(self_, std::memory_order_relaxed);
    held_.push_back(t);
    created_.push_back(t);
  }

  void commit() {
    log_.clear();
    created_.clear();
    release_all();
  }

  // Restores every logged tetrahedron, then retires the new ones (dead, no children: a reader
  // that reaches one restarts its descent), then unlocks. New tetrahedra are not logged.
  void rollback() {
    for (auto it = log_.rbegin(); it != log_.rend(); ++it) {
      Tet& tet = mesh_.tets[it->tet];
      tet.neighbor = it->neighbor;
      for (std::size_t i = 0; i < 4; ++i)
        tet.child[i].store(it->child[i], std::memory_order_relaxed);
      tet.alive.store(it->alive, std::memory_order_release);
    }
    for (const TetId t : created_) {
      Tet& tet = mesh_.tets[t];
      for (auto& c : tet.child) c.store(kNoTet, std::memory_order_relaxed);
      tet.alive.store(false, std::memory_order_release);
    }
    log_.clear();
    created_.clear();
    release_all();
  }

 private:
  struct Saved {
    TetId tet;
    std::array<FaceRef, 4> neighbor;
    std::array<TetId, 4> child;
    bool alive;
  };

  bool stop_waiting() {
    table_.waiting_for[self_].store(0, std::memory_order_relaxed);
    return false;
  }

  // Registers "self waits for owner" and follows the chain of waits; a chain that comes back to
  // self is a deadlock. Under the mutex, registration and check are one step, so of the threads
  // that close a cycle the last one sees it.
  bool would_deadlock(std::uint32_t owner) {
    std::lock_guard<std::mutex> guard(table_.cycle);
    table_.waiting_for[self_].store(owner, std::memory_order_relaxed);
    std::uint32_t current = owner;
    for (std::size_t steps = 0; steps < table_.waiting_for.size(); ++steps) {
      const std::uint32_t next = table_.waiting_for[current].load(std::memory_order_relaxed);
      if (next == 0) return false;
      if (next == self_) {
        // Withdraw inside the critical section, so that the partner does not see this wait and
        // give up too (both giving up could repeat forever).
        table_.waiting_for[self_].store(0, std::memory_order_relaxed);
        return true;
      }
      current = next;
    }
    return false;
  }

  void release_all() {
    for (const TetId t : held_) {
      // release: this thread's writes are visible to the next owner.
      mesh_.tets[t].lock_owner.store(0, std::memory_order_release);
    }
    held_.clear();
  }

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
  Mode mode_;
  ThreadStats& stats_;
  bool stress_;
  std::minstd_rand rng_;
  std::vector<TetId> held_;
  std::vector<TetId> created_;
  std::vector<Saved> log_;
};

}  // namespace dtlab::engine
