#pragma once
// The undo log of the methods without per-tetrahedron lock words (partitioned, lock-grid): a
// thread saves a tetrahedron's references before each write and undoes its own insertion from
// them. Which tetrahedra it may write is the method's acquire() (partition_sync.hpp,
// lock_grid.hpp); nobody else writes them until it commits or rolls back.
#include <array>
#include <vector>

#include "insertion/sync.hpp"
#include "mesh/shared_mesh.hpp"
#include "mesh/tet_id_list.hpp"

namespace dtlab::engine {

// A cache line to itself: each thread's policy object is written at every write of its insertions
// (the log's ends) and read at every ownership test, and the partitioned method's two objects,
// allocated one after the other, shared a line in one build's heap layout and not in another's
// (flips, uniform:1000000, 2 threads: ownership tests and logging 37 % of the run's samples
// against 18 %, the run 1.17x as long; docs/performance-log.md, fourteenth session).
class alignas(64) LocalUndoLog {
 public:
  explicit LocalUndoLog(SharedMesh& mesh) : mesh_(mesh) {}

  // Saves t's references before a write. A tetrahedron written twice is saved twice: rollback
  // restores from the last entry to the first, so the first (the state before the insertion)
  // wins, and no set of saved ids is needed.
  void before_write(TetId t) {
    Saved& s = log_.emplace_back();
    s.tet = t;
    s.neighbor = mesh_.tets[t].neighbor;
    s.last_vertex = mesh_.tets[t].vertex[3];
  }
  void created(TetId t, bool last_write = false) {
    if (!last_write) created_.push_back(t);
  }
  void killed(TetId /*t*/, bool /*last_write*/ = false) {}
  Resume resume() { return Resume::GiveUp; }
  void mark_suspicious(TetId /*t*/) {}

 protected:
  void forget() {
    log_.clear();
    created_.clear();
  }
  // The saved references back (with release: the lock grid's other threads walk over them),
  // every saved tetrahedron alive again (only live ones are written), every new one dead (the
  // slot allocator takes their slots back). Where the record carries its aliveness (the
  // partitioned method's store, which no other thread reads while this one writes) death
  // overwrote the last vertex: it comes back too.
  void undo() {
    const bool in_record = mesh_.tets.alive_in_record();
    for (auto it = log_.rbegin(); it != log_.rend(); ++it) {
      Tet& tet = mesh_.tets[it->tet];
      for (int f = 0; f < 4; ++f) {
        store_neighbor(tet, f, it->neighbor[static_cast<std::size_t>(f)]);
      }
      if (in_record) tet.vertex[3] = it->last_vertex;
    }
    for (const Saved& s : log_) mesh_.tets.set_alive(s.tet, true);
    for (const TetId t : created_) mesh_.tets.set_alive(t, false);
    forget();
  }

  SharedMesh& mesh_;

 private:
  struct Saved {
    TetId tet;
    std::array<FaceRef, 4> neighbor;
    VertexId last_vertex;  // kDeadVertex once dead, where the record carries aliveness
  };
  std::vector<Saved> log_;
  TetIdList created_;
};

}  // namespace dtlab::engine
