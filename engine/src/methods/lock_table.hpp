#pragma once
// What the optimistic lock methods (optimistic-detect, optimistic-prevent, burglary) share across
// their threads: the wait-for table and the cycle check of deadlock detection (paper Fig. 6).
// A tetrahedron's lock word itself lives in its slot (TetStore::lock_word).
#include <atomic>
#include <cstdint>
#include <mutex>
#include <vector>

#include "mesh/shared_mesh.hpp"
#include "mesh/tet_store.hpp"

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

}  // namespace dtlab::engine
