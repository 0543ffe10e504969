#pragma once
// The one path by which tetrahedra are written into the store: every replacement of the engine
// (the splits, the flips and the cavities of insertion/tet_replacement.hpp, the first
// tetrahedron) and every repair's write-back (star splaying's, a closed tetrahedron list's) goes
// through it, so that a change to the store's protocol is made here once. In order:
//  0. lock_and_log: every tetrahedron written besides the new ones (the outside neighbours, which
//     get back references; the old ones, locked already) is locked, then logged before its first
//     write (the lock policy's acquire and before_write), so a refused lock writes nothing (a
//     cavity locks in its search instead, and a confined policy's cavity leaves the outside
//     neighbours unlocked: insertion/cavity_search.hpp);
//  1. new records: a slot that is this thread's (fresh, or reused after its grace period, or at
//     once by a thread whose reads are confined: mesh/read_confinement.hpp) and
//     that nobody can reach, written by plain stores; created() clears its DAG children where the
//     store keeps history and hands it to the lock policy, owned from birth;
//  2. publish: the outside's references to the complete new records, with release, so that a
//     walking thread that reaches a new tetrahedron finds all four of its references set;
//  3. kill: each old tetrahedron dies; with history its DAG children are written first (release),
//     so a descent that finds it dead finds its children; with slot reuse its slot is retired, for
//     reuse once the insertion (and on a shared mesh the epochs, unless reads are confined) let
//     it go;
//  4. born: the new tetrahedra live.
// Slots: SlotAllocator (the engine's threads) or StoreSlots (a repair, whose slots follow each
// other in the order it takes them).
#include <atomic>
#include <cstdint>
#include <span>

#include "mesh/read_confinement.hpp"
#include "mesh/shared_mesh.hpp"
#include "mesh/slot_allocator.hpp"
#include "mesh/tet_store.hpp"

namespace dtlab::engine {

// Fresh slots one at a time, in order, straight from the store (no runs, no reuse).
class StoreSlots {
 public:
  explicit StoreSlots(TetStore& store) : store_(store) {}
  TetId allocate() { return store_.allocate(); }
  void retire(TetId /*t*/) {}
  void give_back(TetId /*t*/) {}

 private:
  TetStore& store_;
};

// Whether lock_and_log logs the outside neighbours (which get back references) before the write:
// yes, unless the policy's rollback restores their references from the dead tetrahedra it brings
// back (kReglueOnUndo: methods/local_undo_log.hpp).
template <class Sync>
inline constexpr bool kLogsOutside = !requires {
  requires Sync::kReglueOnUndo;
};

template <class Sync, class Slots = SlotAllocator>
class TopologyCommit {
 public:
  // recycle: dead slots are retired for reuse (then no history is written).
  TopologyCommit(SharedMesh& mesh, Sync& sync, Slots& slots, bool recycle)
      : mesh_(mesh),
        sync_(sync),
        slots_(slots),
        recycle_(recycle),
        history_(!recycle && mesh.tets.has_children()) {}

  // Whether old tetrahedra get DAG children (the store keeps history and slots are not reused).
  [[nodiscard]] bool history() const { return history_; }

  // Step 0. `outside(visit)` calls visit(t) for each outside tetrahedron written. False (nothing
  // written, nothing logged) when a lock is refused.
  template <class ForEachOutside>
  [[gnu::always_inline]] bool lock_and_log(ForEachOutside&& outside, std::span<const TetId> old) {
    if constexpr (Sync::kLocks) {
      // A confined thread's outside neighbours, as its cavity's (cavity_search.hpp), only get a
      // back reference across a face of its own, written atomically: not asked for.
      if constexpr (!kConfinedReads<Sync>) {
        bool locked = true;
        outside([&](TetId t) { locked = locked && sync_.acquire(t); });
        if (!locked) return false;
      }
      if constexpr (kLogsOutside<Sync>) outside([&](TetId t) { sync_.before_write(t); });
      for (const TetId o : old) sync_.before_write(o);
    }
    return true;
  }

  // Step 1.
  [[gnu::always_inline]] TetId allocate() { return slots_.allocate(); }
  [[gnu::always_inline]] Tet& record(TetId id) { return mesh_.tets[id]; }
  // The record `id` is written (its vertices; its neighbours may follow, it is unreachable).
  // last_write: nothing after this commit can be refused (a cavity's).
  [[gnu::always_inline]] void created(TetId id, bool last_write = false) {
    if (history_) {
      for (auto& c : mesh_.tets.children(id)) c.store(kNoTet, std::memory_order_relaxed);
    }
    sync_.created(id, last_write);
  }
  // A new record that was never published (an impossible cavity): dead again, its slot free.
  void give_back(TetId id) {
    // Where aliveness is kept in the record, writing the record made it look alive.
    mesh_.tets.set_alive<std::memory_order_relaxed>(id, false);
    slots_.give_back(id);
  }

  // Step 2: the outside face `outside` now lies across the new face `inside`.
  [[gnu::always_inline]] void publish(FaceRef outside, FaceRef inside) {
    store_neighbor(mesh_.tets[ref_tet(outside)], ref_face(outside), inside);
  }
  // Both faces' references to each other (a repair's write-back, whose faces are matched by key).
  void link(FaceRef a, FaceRef b) {
    store_neighbor(mesh_.tets[ref_tet(a)], ref_face(a), b);
    store_neighbor(mesh_.tets[ref_tet(b)], ref_face(b), a);
  }

  // Step 3: `old` dies. With history, write_children(children) sets its DAG children first.
  template <class WriteChildren>
  [[gnu::always_inline]] void kill(TetId old, WriteChildren&& write_children,
                                   bool last_write = false) {
    if (recycle_) {
      mesh_.tets.set_alive(old, false);
      slots_.retire(old);
      sync_.killed(old, last_write);
      return;
    }
    if (history_) write_children(mesh_.tets.children(old));
    mesh_.tets.set_alive(old, false);
    sync_.killed(old, last_write);
  }
  // A repair's write-back: old dies without children (nothing descends the DAG after it).
  void kill_without_history(TetId old) {
    kill(old, [](TetStore::Children& /*children*/) {});
  }

  // Step 4.
  [[gnu::always_inline]] void born(TetId id) { mesh_.tets.set_alive(id, true); }

 private:
  SharedMesh& mesh_;
  Sync& sync_;
  Slots& slots_;
  bool recycle_;
  bool history_;
};

}  // namespace dtlab::engine
