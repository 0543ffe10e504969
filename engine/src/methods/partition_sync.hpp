#pragma once
// The partitioned method's policy (partitioned.cpp): no lock words, no waiting, and no read of
// anything another thread writes. A thread may change only the tetrahedra its part owns: those
// whose finite vertices all lie in its part (part_of, fixed for the pass; the vertex at infinity
// belongs to every part). acquire() is that test, asked for every tetrahedron an insertion changes
// (inserter.hpp, topology_commit.hpp; the cavity search's acquire_across() asks it of the one
// vertex a step adds, and a cavity's outside neighbours only get an atomic back reference,
// unasked: insertion/cavity_search.hpp). A tetrahedron with a finite vertex of
// this thread's part is owned by no other part, so no other thread writes it during the pass: the
// thread reads only such tetrahedra (readable), and its walk crosses only faces with a vertex of
// its part (may_cross), into such a tetrahedron. The parts are disjoint, so no tetrahedron is
// written by two threads nor read while another writes it: docs/design.md, "The partitioned
// method", has the argument. A refusal gives the insertion up: a cavity has written nothing yet;
// the flips are undone from this thread's log, and the point waits for a pass with other cuts.
// A flip's outside neighbours, like a cavity's, are not asked (mesh/topology_commit.hpp).
#include <cassert>
#include <cstdint>
#include <vector>

#include "dtlab/engine/stats.hpp"
#include "mesh/shared_mesh.hpp"
#include "methods/local_undo_log.hpp"

namespace dtlab::engine {

class PartitionSync : public LocalUndoLog {
 public:
  static constexpr bool kLocks = true;  // acquire() is asked: the ownership test

  PartitionSync(SharedMesh& mesh, const std::vector<std::uint8_t>& part_of)
      : LocalUndoLog(mesh), part_of_(part_of) {}

  // This thread's part for the next pass; `whole`: the pass has one part, which owns everything.
  void set_part(std::uint8_t part, bool whole) {
    part_ = part;
    whole_ = whole;
  }

  bool acquire(TetId t) const {
    if (whole_) return true;
    for (const VertexId v : mesh_.tets[t].vertex) {
      if (v != kInfiniteVertex && !mine(v)) return false;
    }
    return true;
  }

  // acquire(t) for a tetrahedron entered across its face `face` from one this thread holds (the
  // cavity search's step), `record` being t's record, which the search has just read: the face's
  // three vertices are that one's, this part's or the vertex at infinity, so only t's vertex
  // opposite the face can be another part's. One look-up, not four, and always inlined.
  [[gnu::always_inline]] bool acquire_across(TetId t, const Tet& record, int face) const {
    if (whole_) return true;
    const VertexId apex = record.vertex[static_cast<std::size_t>(face)];
    const bool owned = apex == kInfiniteVertex || mine(apex);
    assert(owned == acquire(t));
    (void)t;
    return owned;
  }

  // Whether other threads write the mesh during this pass (a pass of several parts).
  [[nodiscard]] bool confined() const { return !whole_; }
  // Whether the tetrahedron across face f of `tet` (a readable one) is readable: the face has a
  // finite vertex of this part (a face has at least two finite vertices).
  [[nodiscard]] bool may_cross(const Tet& tet, int f) const {
    if (whole_) return true;
    for (const int k : kFaceVertex[static_cast<std::size_t>(f)]) {
      if (mine(tet.vertex[static_cast<std::size_t>(k)])) return true;
    }
    return false;
  }
  // Whether no other thread writes `tet` during the pass: it has a finite vertex of this part.
  [[nodiscard]] bool readable(const Tet& tet) const {
    if (whole_) return true;
    for (const VertexId v : tet.vertex) {
      if (mine(v)) return true;
    }
    return false;
  }

  // A pass of one part refuses nothing, so its insertions are never undone: nothing to log.
  void before_write(TetId t) {
    if (!whole_) LocalUndoLog::before_write(t);
  }
  void created(TetId t, bool last_write = false) {
    if (!whole_) LocalUndoLog::created(t, last_write);
  }

  void commit() { forget(); }
  void rollback() { undo(); }

 private:
  // v is a finite vertex of this thread's part.
  [[nodiscard, gnu::always_inline]] bool mine(VertexId v) const {
    return v != kInfiniteVertex && part_of_[v] == part_;
  }

  const std::vector<std::uint8_t>& part_of_;
  std::uint8_t part_ = 0;
  bool whole_ = true;
};

}  // namespace dtlab::engine
