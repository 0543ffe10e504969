#pragma once
// The tetrahedra at a vertex of an exactly built shared mesh, found by a walk instead of read from
// incidence lists: star splaying reads few stars when burglary broke little, and lists for the
// whole mesh cost more than the splaying itself there (docs/design.md, star splaying).
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "mesh/shared_mesh.hpp"
#include "repair/star_splaying.hpp"

namespace dtlab::engine {

// A set of tetrahedron ids for one walk: open addressing with linear probing, cleared in time
// proportional to what it holds (a star has about 27 tetrahedra, a few have thousands).
class TetIdSet {
 public:
  TetIdSet() : slots_(std::size_t{1} << kFirstBits, kNoTet) {}
  void clear() {
    for (const std::size_t i : used_) slots_[i] = kNoTet;
    used_.clear();
  }
  // True when t was not in the set.
  bool insert(TetId t) {
    if (2 * (used_.size() + 1) > slots_.size()) grow();
    const std::size_t mask = slots_.size() - 1;
    // Fibonacci hashing: the top bits of t times floor(2^64 / golden ratio).
    std::size_t i = static_cast<std::size_t>((t * 0x9E3779B97F4A7C15ULL) >> (64 - bits_)) & mask;
    while (slots_[i] != kNoTet) {
      if (slots_[i] == t) return false;
      i = (i + 1) & mask;
    }
    slots_[i] = t;
    used_.push_back(i);
    return true;
  }

 private:
  void grow() {
    std::vector<TetId> held;
    held.reserve(used_.size());
    for (const std::size_t i : used_) held.push_back(slots_[i]);
    ++bits_;
    slots_.assign(std::size_t{1} << bits_, kNoTet);
    used_.clear();
    for (const TetId t : held) insert(t);
  }
  static constexpr int kFirstBits = 6;
  std::vector<TetId> slots_;
  std::vector<std::size_t> used_;
  int bits_ = kFirstBits;  // slots_.size() == 2^bits_
};

// The shared mesh as MeshStars where it is consistent (references mutual, each finite tetrahedron
// positive, the hull covered once: an exactly built mesh, burglary's included): the tetrahedra at
// x are those reached from one of them across faces that contain x, since the star of a vertex of
// a triangulation (closed by the infinite tetrahedra) is connected through those faces. Not for a
// broken mesh, whose star need not be connected: the incidence lists serve there.
// `some_tetrahedron[x]`: a live tetrahedron at x, kNoTet where x is no vertex. Several threads
// may ask at once (StarSplayer::activate_all): the walk's scratch is each thread's own.
class WalkedMeshStars : public MeshStars {
 public:
  WalkedMeshStars(const SharedMesh& mesh, const std::vector<TetId>& some_tetrahedron)
      : mesh_(mesh), some_tetrahedron_(some_tetrahedron) {}

  void tetrahedra_of(VertexId x, std::vector<Quad>& out) const override {
    std::vector<TetId>& ids = scratch().ids;
    tetrahedron_ids_of(x, ids);
    out.clear();
    for (const TetId t : ids) out.push_back(mesh_.tets[t].vertex);
  }

  // The same tetrahedra as ids, in the order the walk met them.
  void tetrahedron_ids_of(VertexId x, std::vector<TetId>& out) const {
    out.clear();
    const TetId start = some_tetrahedron_[x];
    if (start == kNoTet) return;
    // A dead start would walk the references the tetrahedron had when it died (a reused slot,
    // from one without x).
    if (!mesh_.tets.is_alive(start, std::memory_order_relaxed) ||
        mesh_.tets[start].index_of(x) < 0) {
      throw std::logic_error("star splaying: the walk around vertex " + std::to_string(x) +
                             " starts at a tetrahedron that is dead or lacks it");
    }
    TetIdSet& visited = scratch().visited;
    std::vector<TetId>& to_visit = scratch().to_visit;
    visited.clear();
    visited.insert(start);
    to_visit.assign(1, start);
    while (!to_visit.empty()) {
      const TetId t = to_visit.back();
      to_visit.pop_back();
      out.push_back(t);
      const Tet& tet = mesh_.tets[t];
      const int at = tet.index_of(x);
      for (int f = 0; f < 4; ++f) {
        if (f == at) continue;
        const TetId next = ref_tet(tet.neighbor[static_cast<std::size_t>(f)]);
        // The face across contains x, so its other tetrahedron does, in a consistent mesh.
        if (mesh_.tets[next].index_of(x) < 0) {
          throw std::logic_error("star splaying: tetrahedron " + std::to_string(t) +
                                 " and its neighbour " + std::to_string(next) +
                                 " do not share vertex " + std::to_string(x) +
                                 " (the mesh's references are not mutual)");
        }
        if (visited.insert(next)) to_visit.push_back(next);
      }
    }
  }

 private:
  struct WalkScratch {
    TetIdSet visited;
    std::vector<TetId> to_visit;
    std::vector<TetId> ids;
  };
  static WalkScratch& scratch() {
    thread_local WalkScratch mine;
    return mine;
  }

  const SharedMesh& mesh_;
  const std::vector<TetId>& some_tetrahedron_;
};

}  // namespace dtlab::engine
