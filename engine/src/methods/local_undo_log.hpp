#pragma once
// The undo log of the methods without per-tetrahedron lock words (partitioned, lock-grid): a
// thread saves the references of each tetrahedron its insertion kills, before the kill, and
// undoes its own insertion from them. Which tetrahedra it may write is the method's acquire()
// (partition_sync.hpp, lock_grid.hpp); nobody else writes them until it commits or rolls back.
//
// The outside neighbours, whose only change is a back reference to a new tetrahedron, are not
// logged (kReglueOnUndo): their first load would be the log's (a cache miss that the sequential
// engine's stores never wait for: 14 % of a one-thread partitioned run by flips). Undo re-glues
// them instead. A reference changes only when the tetrahedron it names dies, so every changed
// reference of a surviving tetrahedron first named one that this insertion killed and that was
// there before it (logged, brought back), and that one's reference back was unchanged when it
// was logged (it changes only when the survivor dies). A brought-back record's own reference
// may have changed before its death, but then only to a new tetrahedron, dead after the undo:
// so the references of the brought-back records to live tetrahedra are the ones from before the
// insertion, and storing their mirror images restores every reference the insertion changed.
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
  static constexpr bool kReglueOnUndo = true;

  explicit LocalUndoLog(SharedMesh& mesh) : mesh_(mesh) {}

  // Saves t's references before it dies (each tetrahedron dies once).
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
  // every saved tetrahedron alive again, every new one dead (the slot allocator takes their
  // slots back; a new one that died is both), then the live neighbours' references to the
  // brought-back ones (the header's argument). Where the record carries its aliveness (the
  // partitioned method's store, which no other thread reads while this one writes) death
  // overwrote the last vertex: it comes back too.
  void undo() {
    const bool in_record = mesh_.tets.alive_in_record();
    for (const Saved& s : log_) {
      Tet& tet = mesh_.tets[s.tet];
      for (int f = 0; f < 4; ++f) store_neighbor(tet, f, s.neighbor[static_cast<std::size_t>(f)]);
      if (in_record) tet.vertex[3] = s.last_vertex;
      mesh_.tets.set_alive(s.tet, true);
    }
    for (const TetId t : created_) mesh_.tets.set_alive(t, false);
    for (const Saved& s : log_) {
      if (!mesh_.tets.is_alive(s.tet)) continue;  // a new one
      for (int f = 0; f < 4; ++f) {
        const FaceRef across = s.neighbor[static_cast<std::size_t>(f)];
        if (!mesh_.tets.is_alive(ref_tet(across))) continue;  // a new one: changed, see above
        store_neighbor(mesh_.tets[ref_tet(across)], ref_face(across), face_ref(s.tet, f));
      }
    }
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
