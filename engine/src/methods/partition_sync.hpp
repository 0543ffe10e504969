#pragma once
// The partitioned method's policy (partitioned.cpp): no lock words and no waiting. A thread may
// change only the tetrahedra its part owns: those whose finite vertices all lie in its part
// (part_of, fixed for the pass; the vertex at infinity belongs to every part). acquire() is that
// test, asked for every tetrahedron an insertion reads for change or writes (inserter.hpp,
// topology_commit.hpp). The parts are disjoint and a tetrahedron's vertices do not change while
// it lives (nor while a reader's epoch holds its slot), so no tetrahedron is ever written by two
// threads in a pass: docs/design.md, "The partitioned method", has the argument. A refusal gives
// the insertion up: a cavity has written nothing yet; the flips are undone from this thread's
// log, and the point waits for a pass with other cuts.
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
      if (v != kInfiniteVertex && part_of_[v] != part_) return false;
    }
    return true;
  }

  void commit() { forget(); }
  void rollback() { undo(); }

 private:
  const std::vector<std::uint8_t>& part_of_;
  std::uint8_t part_ = 0;
  bool whole_ = true;
};

}  // namespace dtlab::engine
