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
#include <array>
#include <atomic>
#include <cstdint>
#include <vector>

#include "dtlab/engine/stats.hpp"
#include "insertion/sync.hpp"
#include "mesh/shared_mesh.hpp"
#include "mesh/tet_id_list.hpp"

namespace dtlab::engine {

class PartitionSync {
 public:
  static constexpr bool kLocks = true;  // acquire() is asked: the ownership test

  PartitionSync(SharedMesh& mesh, const std::vector<std::uint8_t>& part_of)
      : mesh_(mesh), part_of_(part_of) {}

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

  // Saves t's references before a write. A tetrahedron written twice is saved twice: rollback
  // restores from the last entry to the first, so the first (the state before the insertion)
  // wins, and no set of saved ids is needed.
  void before_write(TetId t) {
    Saved& s = log_.emplace_back();
    s.tet = t;
    s.neighbor = mesh_.tets[t].neighbor;
  }
  void created(TetId t, bool last_write = false) {
    if (!last_write) created_.push_back(t);
  }
  void killed(TetId /*t*/, bool /*last_write*/ = false) {}

  void commit() {
    log_.clear();
    created_.clear();
  }
  // The saved references back (with release: other threads' walks read them), every saved
  // tetrahedron alive again, every new one dead (the slot allocator takes their slots back).
  void rollback() {
    for (auto it = log_.rbegin(); it != log_.rend(); ++it) {
      Tet& tet = mesh_.tets[it->tet];
      for (int f = 0; f < 4; ++f) {
        store_neighbor(tet, f, it->neighbor[static_cast<std::size_t>(f)]);
      }
    }
    for (const Saved& s : log_) mesh_.tets.set_alive(s.tet, true);
    for (const TetId t : created_) mesh_.tets.set_alive(t, false);
    commit();
  }
  Resume resume() { return Resume::GiveUp; }
  void mark_suspicious(TetId /*t*/) {}

 private:
  struct Saved {
    TetId tet;
    std::array<FaceRef, 4> neighbor;
  };

  SharedMesh& mesh_;
  const std::vector<std::uint8_t>& part_of_;
  std::uint8_t part_ = 0;
  bool whole_ = true;
  std::vector<Saved> log_;
  TetIdList created_;
};

}  // namespace dtlab::engine
