#pragma once
// The synchronization policy of the optimistic methods (paper Fig. 6): per-tetrahedron lock
// words taken by compare-and-swap, waiting with deadlock detection (a wait-for cycle check in a
// short critical section) or deadlock prevention (priorities), and an undo log so that a thread
// that must not wait gives its insertion up and restores the mesh exactly.
//
// Burglary (paper Sect. 5, docs/design.md) keeps no undo log: a thread that detects a deadlock
// marks its counterpart, who is then parked in acquire() and writes nothing, as burgled and takes
// its locks (the picklock). The victim releases the rest, waits until the burglar's insertion
// ends, takes back the tetrahedra it had created and checks that they are all still alive. If
// they are, its remaining legalization is still valid and goes on; if not, it stops, counts a
// potential problem and marks the suspicious tetrahedra for the sequential post-check. Every
// write still happens under a lock its writer holds, so the mesh stays consistent.
#include <algorithm>
#include <atomic>
#include <cassert>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <random>
#include <thread>
#include <vector>

#include "dtlab/engine/tet_mesh.hpp"
#include "dtlab/engine/triangulate.hpp"
#include "shared_mesh.hpp"
#include "tet_id_list.hpp"

namespace dtlab::engine {

// State shared by all threads of one run.
struct LockTable {
  explicit LockTable(int threads)
      : waiting_for(static_cast<std::size_t>(threads) + 1),
        priority(static_cast<std::size_t>(threads) + 1),
        phase(static_cast<std::size_t>(threads) + 1),
        burgled_in_phase(static_cast<std::size_t>(threads) + 1),
        waiting_on(static_cast<std::size_t>(threads) + 1, kNoTet) {}
  // waiting_for[i]: the thread that thread i waits for (0: none), or kBurgled | burglar while
  // thread i is a burglary victim. Registered and followed under `cycle` so that the last thread
  // to close a cycle always sees it (no false negatives); withdrawn (0) without the mutex, so a
  // chain read under it may be stale (find_cycle re-checks it); burglary changes it by
  // compare-and-swap only, so that "stopped waiting" and "burgled" cannot both win. Every nonzero
  // value is written under `cycle`.
  std::vector<std::atomic<std::uint32_t>> waiting_for;
  std::vector<std::atomic<std::uint64_t>> priority;  // prevent: higher wins
  // Burglary: phase[i] counts the insertions (or parts of one) thread i has ended; a victim waits
  // until its burglar's phase moves past burgled_in_phase[victim].
  std::vector<std::atomic<std::uint64_t>> phase;
  std::vector<std::atomic<std::uint64_t>> burgled_in_phase;
  // waiting_on[i]: the tetrahedron of thread i's registered wait. Written and read under `cycle`
  // only, so a plain value.
  std::vector<TetId> waiting_on;
  static constexpr std::uint32_t kBurgled = 0x8000'0000U;
  // A lock word is the owner's id, plus kLogged once the owner has saved the tetrahedron in its
  // undo log (or created it): the owner asks its own word, already in cache, instead of a set.
  // The word's top bit is the tetrahedron's aliveness (TetStore::kAliveBit), which the owner
  // sets and clears and every other write keeps.
  static constexpr std::uint32_t kLogged = 0x4000'0000U;
  static constexpr std::uint32_t kAlive = TetStore::kAliveBit;
  static std::uint32_t owner_of(std::uint32_t word) { return word & ~(kLogged | kAlive); }
  std::mutex cycle;
  std::atomic<bool> stop{false};  // watchdog: give everything up
};

// What the registered waits from a thread lead to: no cycle back to it, a closed chain of
// registrations that no longer holds (a wait withdrawn, or a lock that changed hands, since it
// was registered), or a real deadlock.
enum class Cycle { None, Stale, Real };

// Follows the registered waits from `self` (whose wait is registered); the caller holds
// table.cycle. `chain` is scratch space.
//
// Why Real is a real deadlock. Registrations need the mutex, so while the caller holds it every
// other thread's waiting_for can only drop to 0 (withdrawn). The chain self = T0 -> T1 -> ... ->
// Tk -> T0 is read first (loads A), then for each edge the owner of the tetrahedron Ti waits on
// (loads B: owner Ti+1), then every waiting_for again (loads C: unchanged). A waiting thread takes
// no lock but the one it waits for, releases none, and withdraws (a store sequenced after its
// winning compare-and-swap and before any release). If Ti+1's compare-and-swap read by B came
// after its withdrawal, the withdrawal would happen before B (release/acquire on the lock word)
// and so before C, which could not read the registration. If it was the one that ended Ti+1's
// wait (Ti+1 waited for the same tetrahedron), edge i+1 needs a later owner of it, which again
// comes after the withdrawal. So Ti+1 took that lock before its registered wait and holds it
// until after its withdrawal; then Ti can get it only after Ti+1 has withdrawn (its release,
// acquire by Ti), and around the cycle every withdrawal would have to happen before itself: none
// of T0..Tk can ever get its lock unless one of them gives up. Stale chains (A alone would have
// counted them) come back as Stale. Burglary takes a victim's locks only after marking it
// burgled under the mutex, which ends a chain at the victim.
//
// Why a deadlock is never missed. Take the threads of a deadlock and, of their last registrations
// (each thread registers on every new owner it sees), the one made last under the mutex. Every
// other registration, and every lock a waiting thread holds (taken before its wait began), happens
// before that critical section, and none of them changes afterwards: all three passes of the
// thread that made it see the cycle, and it gives up (detect) or burgles (burglary).
inline Cycle find_cycle(const SharedMesh& mesh, const LockTable& table, std::uint32_t self,
                        std::vector<std::uint32_t>& chain) {
  chain.clear();
  for (std::uint32_t current = self;;) {
    chain.push_back(current);
    const std::uint32_t next = table.waiting_for[current].load(std::memory_order_acquire);
    if (next == 0 || (next & LockTable::kBurgled) != 0) return Cycle::None;
    if (next == self) break;
    if (chain.size() == table.waiting_for.size()) return Cycle::None;  // a cycle without self
    current = next;
  }
  const auto successor = [&](std::size_t i) { return i + 1 < chain.size() ? chain[i + 1] : self; };
  for (std::size_t i = 0; i < chain.size(); ++i) {
    const TetId t = table.waiting_on[chain[i]];
    // acquire: synchronizes with the owner's compare-and-swap (release), or with its later
    // kLogged store (release too), so that a withdrawal sequenced before the compare-and-swap is
    // seen by the loads C below. (A and C need no order of their own.)
    if (t == kNoTet || LockTable::owner_of(mesh.tets.lock_word(t).load(
                           std::memory_order_acquire)) != successor(i)) {
      return Cycle::Stale;
    }
  }
  for (std::size_t i = 0; i < chain.size(); ++i) {
    if (table.waiting_for[chain[i]].load(std::memory_order_acquire) != successor(i)) {
      return Cycle::Stale;
    }
  }
  return Cycle::Real;
}

class OptimisticSync {
 public:
  static constexpr bool kLocks = true;
  enum class Mode { Detect, Prevent, Burglary };

  OptimisticSync(SharedMesh& mesh, LockTable& table, std::uint32_t self, Mode mode,
                 ThreadStats& stats, bool stress)
      : mesh_(mesh),
        table_(table),
        self_(self),
        mode_(mode),
        stats_(stats),
        stress_(stress),
        rng_(self) {}

  // Takes t's lock; false when the insertion must be given up (or, burglary, this thread was
  // burgled: see resume()).
  bool acquire(TetId t) {
    std::atomic<std::uint32_t>& word = mesh_.tets.lock_word(t);
    // Only this thread ever stores self_, so a relaxed load that sees it is exact.
    if (LockTable::owner_of(word.load(std::memory_order_relaxed)) == self_) return true;
    bool waited = false;
    std::uint32_t registered_owner = 0;
    for (std::uint64_t spin = 0;; ++spin) {
      // Free: no owner, the aliveness as the last owner left it (only an owner changes it).
      std::uint32_t seen = word.load(std::memory_order_relaxed) & LockTable::kAlive;
      // acquire: what the previous owner wrote under the lock is visible from here on.
      if (word.compare_exchange_strong(seen, seen | self_, std::memory_order_acq_rel,
                                       std::memory_order_acquire)) {
        held_.push_back(t);
        if (waited && !stop_waiting()) return false;  // burgled after all: keep t in held_
        maybe_delay();
        return true;
      }
      std::uint32_t owner = LockTable::owner_of(seen);
      if (owner == 0) continue;  // freed between the load and the compare-and-swap
      if (owner == self_) return true;
      if (table_.stop.load(std::memory_order_relaxed)) {
        stop_waiting();
        return false;
      }
      if (mode_ == Mode::Burglary) {
        if (burgled()) return false;
        // The picklock: a victim of this thread holds t (burglary never sets kLogged, so the
        // word is the owner and the aliveness).
        if (table_.waiting_for[owner].load(std::memory_order_acquire) ==
                (LockTable::kBurgled | self_) &&
            word.compare_exchange_strong(seen, (seen & LockTable::kAlive) | self_,
                                         std::memory_order_acq_rel, std::memory_order_acquire)) {
          held_.push_back(t);
          if (waited && !stop_waiting()) return false;
          return true;
        }
        owner = LockTable::owner_of(seen);  // as the picklock's compare-and-swap found it
        if (owner == 0) continue;           // released meanwhile: take it normally
      }
      if (!waited) {
        waited = true;
        ++stats_.waits;
      }
      if (mode_ == Mode::Prevent) {
        // Never wait for a thread of higher priority (ties: the lower id wins) while holding a
        // lock. Holding none, nobody waits for this thread, so its wait closes no cycle: it waits.
        if (held_.empty()) {
          if (spin > 64) std::this_thread::yield();
          continue;
        }
        const std::uint64_t mine = table_.priority[self_].load(std::memory_order_relaxed);
        const std::uint64_t theirs = table_.priority[owner].load(std::memory_order_relaxed);
        if (theirs > mine || (theirs == mine && owner < self_)) {
          table_.priority[self_].fetch_add(1, std::memory_order_relaxed);
          ++stats_.priority_raises;
          stop_waiting();
          return false;
        }
      } else if (owner != registered_owner) {
        // (Re-)register only when the owner changes: whoever closes a cycle later sees it.
        registered_owner = owner;
        const Wait wait = register_wait(owner, t);
        if (wait == Wait::Deadlock) {
          ++stats_.deadlocks;
          return false;  // register_wait already withdrew the wait
        }
        if (wait == Wait::Burgled) return false;
        if (wait == Wait::Burgling) registered_owner = 0;  // re-read the owner, then pick
      }
      if (spin > 64) std::this_thread::yield();
    }
  }

  void before_write(TetId t) {
    if (mode_ == Mode::Burglary) return;  // no undo
    // Logged once; created tetrahedra carry kLogged from birth (retired whole on rollback). Only
    // this thread writes the word while it holds t. release: a find_cycle that reads this value
    // still synchronizes with everything before the compare-and-swap that took t.
    std::atomic<std::uint32_t>& word = mesh_.tets.lock_word(t);
    const std::uint32_t held = word.load(std::memory_order_relaxed);
    if ((held & LockTable::kLogged) != 0) return;
    word.store(held | LockTable::kLogged, std::memory_order_release);
    const Tet& tet = mesh_.tets[t];
    // Only live tetrahedra are written: each is the located leaf (checked after locking), an old
    // one of the replacement, or a neighbour of a locked live one (whoever kills it rewrites that
    // reference, under the lock). So rollback makes every logged one alive again without
    // having recorded its aliveness.
    assert(mesh_.tets.is_alive(t, std::memory_order_relaxed));
    // Filled in place: an entry built on the stack from overlapping stores and copied by wider
    // loads stalled on store forwarding (two fifths of this function's samples).
    Saved& s = log_.emplace_back();
    s.tet = t;
    s.neighbor = tet.neighbor;
    if (mesh_.tets.has_children()) {
      const auto& children = mesh_.tets.children(t);
      for (std::size_t i = 0; i < 4; ++i) s.child[i] = children[i].load(std::memory_order_relaxed);
    }
  }

  // last_write: this replacement ends the insertion (a cavity's), so neither rollback() nor
  // resume() can follow it and the lists they read need not hold t.
  void created(TetId t, bool last_write = false) {
    // Owned before it is published: nobody can lock it before this thread lets go. Never logged.
    // Not alive yet (the replacement sets it alive once linked).
    mesh_.tets.lock_word(t).store(mode_ == Mode::Burglary ? self_ : self_ | LockTable::kLogged,
                                  std::memory_order_relaxed);
    held_.push_back(t);
    if (last_write) {
      ended_ = true;
    } else {
      created_.push_back(t);
    }
  }

  // Burglary: t, alive until now, dies by this thread's own write.
  void killed(TetId t, bool last_write = false) {
    if (mode_ == Mode::Burglary && !last_write) own_kills_.push_back(t);
  }

  void commit() {
    log_.clear();
    created_.clear();
    own_kills_.clear();
    release_all();
    ended_ = false;
    end_phase();
  }

  // Restores every logged tetrahedron, then retires the new ones (dead, no children: a reader
  // that reaches one restarts its descent), then unlocks. New tetrahedra are not logged.
  void rollback() {
    assert(!ended_);  // nothing after a last write can be refused
    if (mode_ == Mode::Burglary) {
      // Only ever called before the insertion's first write: nothing to undo. A victim burgled
      // there (always so for a point inserted by a cavity, whose writes all come after its last
      // lock; not for the fast kernel's fallbacks to flips) lost nothing: it tries the point
      // again after the burglar's insertion.
      created_.clear();
      own_kills_.clear();
      release_all();
      end_phase();
      if (burgled()) {
        ++stats_.burgled;
        wait_for_burglar();
      }
      return;
    }
    for (auto it = log_.rbegin(); it != log_.rend(); ++it) {
      Tet& tet = mesh_.tets[it->tet];
      for (std::size_t f = 0; f < 4; ++f) {  // walking threads read these without a lock
        std::atomic_ref<FaceRef>(tet.neighbor[f]).store(it->neighbor[f], std::memory_order_release);
      }
      for (std::size_t i = 0; i < 4; ++i)
        if (mesh_.tets.has_children()) {
          mesh_.tets.children(it->tet)[i].store(it->child[i], std::memory_order_relaxed);
        }
      mesh_.tets.set_alive(it->tet, true);
    }
    for (const TetId t : created_) {
      if (mesh_.tets.has_children()) {
        for (auto& c : mesh_.tets.children(t)) c.store(kNoTet, std::memory_order_relaxed);
      }
      mesh_.tets.set_alive(t, false);
    }
    log_.clear();
    created_.clear();
    release_all();
  }

  // A lock was refused in the middle of legalization. Detect and prevent give the insertion up.
  // A burglary victim releases everything, waits for the burglar's insertion to end, takes back
  // the tetrahedra it created and checks them: all alive means the rest of its legalization is
  // still valid.
  Resume resume() {
    assert(!ended_);
    if (mode_ != Mode::Burglary) return Resume::GiveUp;
    ++stats_.burgled;
    std::vector<TetId> mine;
    for (const TetId c : created_) {
      if (std::find(own_kills_.begin(), own_kills_.end(), c) == own_kills_.end()) mine.push_back(c);
    }
    for (;;) {
      release_all();
      end_phase();
      if (burgled()) wait_for_burglar();
      if (table_.stop.load(std::memory_order_relaxed)) return Resume::Stop;
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

  // Burglary: a tetrahedron whose faces the sequential post-check must legalize (a dead one
  // stands for the live tetrahedra below it in the DAG).
  void mark_suspicious(TetId t) {
    suspicious_.push_back(t);
    ++stats_.suspicious_tetrahedra;
  }
  [[nodiscard]] const std::vector<TetId>& suspicious() const { return suspicious_; }

 private:
  enum class Wait { Waiting, Deadlock, Burgled, Burgling };

  struct Saved {
    TetId tet;
    std::array<FaceRef, 4> neighbor;
    std::array<TetId, 4> child;
  };

  // Withdraws this thread's registered wait; false when a burglar got there first.
  bool stop_waiting() {
    std::atomic<std::uint32_t>& status = table_.waiting_for[self_];
    if (mode_ != Mode::Burglary) {
      status.store(0, std::memory_order_relaxed);
      return true;
    }
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

  // Registers "self waits for owner, for t" and checks for a cycle (find_cycle). Under the mutex,
  // registration and check are one step, so of the threads that close a cycle the last one sees
  // it. Detect: self gives up. Burglary: self breaks into `owner`, which is parked in acquire()
  // and writes nothing until this insertion ends. A stale chain is only counted: self waits on,
  // and registers again when t's owner changes.
  Wait register_wait(std::uint32_t owner, TetId t) {
    std::lock_guard<std::mutex> guard(table_.cycle);
    std::atomic<std::uint32_t>& status = table_.waiting_for[self_];
    if ((status.load(std::memory_order_acquire) & LockTable::kBurgled) != 0) return Wait::Burgled;
    table_.waiting_on[self_] = t;
    status.store(owner, std::memory_order_release);
    const Cycle cycle = find_cycle(mesh_, table_, self_, chain_);
    if (cycle == Cycle::Stale) ++stats_.stale_cycles;
    if (cycle != Cycle::Real) return Wait::Waiting;
    if (mode_ != Mode::Burglary) {
      // Withdraw inside the critical section, so that the partner does not see this wait and
      // give up too (both giving up could repeat forever).
      status.store(0, std::memory_order_relaxed);
      return Wait::Deadlock;
    }
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

  void end_phase() {
    if (mode_ == Mode::Burglary) table_.phase[self_].fetch_add(1, std::memory_order_acq_rel);
  }

  // The victim holds no lock here, so nobody waits for it and this wait closes no cycle.
  void wait_for_burglar() {
    std::atomic<std::uint32_t>& status = table_.waiting_for[self_];
    const std::uint32_t burglar = status.load(std::memory_order_acquire) & ~LockTable::kBurgled;
    const std::uint64_t phase = table_.burgled_in_phase[self_].load(std::memory_order_relaxed);
    for (std::uint64_t spin = 0; table_.phase[burglar].load(std::memory_order_acquire) == phase;
         ++spin) {
      if (table_.stop.load(std::memory_order_relaxed)) break;
      if (spin > 64) std::this_thread::yield();
    }
    status.store(0, std::memory_order_release);
  }

  void release_all() {
    // A burglar takes only the locks of a thread it marked burgled while that thread waited, and
    // such a thread gives its attempt up. An insertion that reached its last write (a cavity's)
    // was never burgled, so every word it holds is its own: burglary releases those by plain
    // stores too.
    if (mode_ != Mode::Burglary || ended_) {
      // release: this thread's writes are visible to the next owner. Nobody else writes a word
      // this thread holds, so a plain store does (no locked instruction per tetrahedron).
      // The aliveness stays in the word.
      for (const TetId t : held_) {
        std::atomic<std::uint32_t>& word = mesh_.tets.lock_word(t);
        word.store(word.load(std::memory_order_relaxed) & LockTable::kAlive,
                   std::memory_order_release);
      }
      held_.clear();
      return;
    }
    for (const TetId t : held_) {
      // release, as above. A compare-and-swap, because a burglar may have taken the lock
      // meanwhile (then it is the burglar's to release).
      std::atomic<std::uint32_t>& word = mesh_.tets.lock_word(t);
      std::uint32_t expected = word.load(std::memory_order_relaxed);
      if (LockTable::owner_of(expected) != self_) continue;
      word.compare_exchange_strong(expected, expected & LockTable::kAlive,
                                   std::memory_order_release, std::memory_order_relaxed);
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
  TetIdList held_;
  TetIdList created_;
  bool ended_ = false;  // a last write happened in this insertion (checked in debug builds)
  std::vector<Saved> log_;
  std::vector<TetId> own_kills_;      // burglary: created tetrahedra this thread itself replaced
  std::vector<TetId> suspicious_;     // burglary: marks for the post-check
  std::vector<std::uint32_t> chain_;  // find_cycle's scratch
};

}  // namespace dtlab::engine
