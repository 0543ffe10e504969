#pragma once
// The Lawson pass: flips from given faces until every face they reach is locally Delaunay (or no
// flip applies there), each new tetrahedron's faces queued in turn. Lawson flips raise no face of
// the lifted triangulation, so with exact predicates they cannot cycle; in 3D they can get stuck
// at a face no flip removes (Joe 1991), which is why the callers check or splay what is left.
// Burglary's post-check (methods/burglary_post_check.cpp) and --repair=flips-splay's first stage run it
// alone, on a shared mesh after the run; the inserter (inserter.hpp) has it too, for the tests'
// forced flips.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "insertion/flips.hpp"
#include "mesh/conflict.hpp"

namespace dtlab::engine {

template <class K, class Sync = NoSync>
class LawsonPass : public Flipper<K, Sync> {
  using Base = Flipper<K, Sync>;

 protected:
  using Flip = typename Base::Flip;
  using Base::geometry_;
  using Base::legalize_face;
  using Base::mesh_;
  using Base::stack_;

 public:
  using Base::Base;

  // Flips face f of live tetrahedron t by S23, S32 or S44/S22, whatever the Delaunay test says,
  // when the same geometry as in legalization allows a flip: the tests inject non-Delaunay faces
  // into a Delaunay mesh with it and check that relegalize() removes them. Sequential use only.
  // Returns the new tetrahedra (empty when no flip exists there).
  std::vector<TetId> flip_face(TetId t, int f) {
    if (!mesh_.tets.is_alive(t, std::memory_order_acquire) || !finite_side(t, f)) return {};
    std::uint64_t count = 0;
    stack_.clear();
    std::vector<TetId> created;
    if (legalize_face(t, f, count, /*force=*/true) == Flip::Done) {
      created.assign(stack_.begin(), stack_.end());
    }
    stack_.clear();
    return created;
  }

  // Burglary's sequential post-check: legalizes every face of the live tetrahedra at or below
  // the marked DAG nodes (all live tetrahedra when `everything`) by Lawson flips, following the
  // faces of each new tetrahedron. Lawson flips in 3D can get stuck at a non-flippable face; the
  // caller checks the result with the validator. Returns the number of flips.
  std::uint64_t relegalize(const std::vector<TetId>& marks, bool everything) {
    std::vector<std::pair<TetId, int>> faces;
    std::vector<char> seen(mesh_.tets.size(), 0);
    std::vector<TetId> pending;
    if (everything) {
      for (TetId t = 0; t < mesh_.tets.size(); ++t) pending.push_back(t);
    } else {
      pending = marks;
    }
    while (!pending.empty()) {  // down the DAG to the live tetrahedra
      const TetId t = pending.back();
      pending.pop_back();
      if (t >= seen.size() || seen[t] != 0) continue;
      seen[t] = 1;
      if (mesh_.tets.is_alive(t, std::memory_order_acquire)) {
        for (int f = 0; f < 4; ++f) faces.emplace_back(t, f);
        continue;
      }
      if (everything || !mesh_.tets.has_children()) continue;  // walk mode: no DAG
      for (const auto& c : mesh_.tets.children(t)) {
        const TetId child = c.load(std::memory_order_acquire);
        if (child != kNoTet) pending.push_back(child);
      }
    }
    // Lawson flips raise no face of the lifted triangulation, so they cannot cycle; the bound
    // only guards against an inexact kernel, whose flips can. It counts the live tetrahedra, not
    // the slots: in DAG mode every flip adds slots, and a bound on slots let a sweep after a
    // cycling first pass run to tens of millions of flips (the parallel fuzzer: 60 points, the
    // fast kernel, over 3 GB of pending faces).
    std::uint64_t live = 0;
    for (TetId t = 0; t < mesh_.tets.size(); ++t) {
      live += mesh_.tets.is_alive(t, std::memory_order_acquire) ? 1 : 0;
    }
    return lawson(faces, 64 * live + 1024, nullptr, nullptr);
  }

  // --repair=flips-splay's first stage (splay_repair.hpp, FlipPass): Lawson flips from every face
  // of the live tetrahedra among `tets`, at most `max_flips` of them (the faces still queued then
  // are handed on as they are). Returns the flips; `created` gets every tetrahedron they made (some
  // dead again by the end), `left` the vertices of the two tetrahedra of each face still
  // non-Delaunay at the end (once a face), where no flip applied or the bound stopped the pass
  // before its turn: star splaying's seeds. Each face is tested on its last pair of tetrahedra,
  // since the faces of every new tetrahedron are queued after its creation, so no face is
  // non-Delaunay at the end but those in `left` and those that already were, outside `tets`
  // (docs/design.md, "Flips, then star splaying").
  std::uint64_t flip_from(const std::vector<TetId>& tets, std::vector<TetId>& created,
                          std::vector<Quad>& left,
                          std::uint64_t max_flips = std::numeric_limits<std::uint64_t>::max()) {
    std::vector<std::pair<TetId, int>> faces;
    for (const TetId t : tets) {
      if (!mesh_.tets.is_alive(t, std::memory_order_acquire)) continue;
      for (int f = 0; f < 4; ++f) faces.emplace_back(t, f);
    }
    std::vector<std::pair<TetId, int>> stuck;
    // A bound from the faces given, not the whole mesh (counting its live tetrahedra took longer
    // than the flips for a few dozen faces): a pass stopped by it hands the rest to the stars,
    // which finish it whatever is left.
    const std::uint64_t bound = std::min<std::uint64_t>(64 * faces.size() + 1024, max_flips);
    const std::uint64_t flips = lawson(faces, bound, &stuck, &created);
    // Each face once: named from the side of its finite apex, the lower tetrahedron where both
    // apexes are finite.
    std::vector<std::pair<TetId, int>> named;
    for (auto [t, f] : stuck) {
      if (!mesh_.tets.is_alive(t, std::memory_order_acquire)) continue;  // flipped away later
      const FaceRef across = mesh_.tets[t].neighbor[static_cast<std::size_t>(f)];
      const TetId u = ref_tet(across);
      const int g = ref_face(across);
      const bool mine_infinite =
          mesh_.tets[t].vertex[static_cast<std::size_t>(f)] == kInfiniteVertex;
      const bool its_infinite =
          mesh_.tets[u].vertex[static_cast<std::size_t>(g)] == kInfiniteVertex;
      if (mine_infinite != its_infinite ? mine_infinite : u < t) {
        t = u;
        f = g;
      }
      named.emplace_back(t, f);
    }
    std::sort(named.begin(), named.end());
    named.erase(std::unique(named.begin(), named.end()), named.end());
    for (const auto& [t, f] : named) {
      const Tet& tet = mesh_.tets[t];
      const Tet& across = mesh_.tets[ref_tet(tet.neighbor[static_cast<std::size_t>(f)])];
      const VertexId apex = tet.vertex[static_cast<std::size_t>(f)];
      // A face between two infinite apexes (never on a mesh built exactly) is handed on as found.
      if (apex != kInfiniteVertex && !geometry_.in_conflict(across, apex)) continue;
      left.push_back(tet.vertex);
      left.push_back(across.vertex);
    }
    return flips;
  }

 private:
  // Names face f of t from the side of its finite apex (a face has at most one infinite apex on a
  // sound mesh): false where both apexes are infinite.
  bool finite_side(TetId& t, int& f) const {
    if (mesh_.tets[t].vertex[static_cast<std::size_t>(f)] != kInfiniteVertex) return true;
    const FaceRef across = mesh_.tets[t].neighbor[static_cast<std::size_t>(f)];
    t = ref_tet(across);
    f = ref_face(across);
    return mesh_.tets[t].vertex[static_cast<std::size_t>(f)] != kInfiniteVertex;
  }

  // Lawson flips from `faces` (tetrahedron, face) until none is left or `bound` flips were made;
  // the faces of every new tetrahedron follow. A face is tested from the side of its finite apex.
  // `stuck`, when given, receives the faces found non-Delaunay where no flip exists (and those
  // still queued if the bound stops the pass); `created` every new tetrahedron. Returns the number
  // of flips.
  std::uint64_t lawson(std::vector<std::pair<TetId, int>>& faces, std::uint64_t bound,
                       std::vector<std::pair<TetId, int>>* stuck, std::vector<TetId>* created) {
    std::uint64_t flips = 0;
    while (!faces.empty()) {
      if (flips >= bound) {  // what is left is star splaying's, where it runs
        if (stuck != nullptr) stuck->insert(stuck->end(), faces.begin(), faces.end());
        faces.clear();
        break;
      }
      auto [t, f] = faces.back();
      faces.pop_back();
      if (!mesh_.tets.is_alive(t, std::memory_order_acquire)) continue;
      if (!finite_side(t, f)) {
        // Two infinite tetrahedra glued on one face: a mesh the fast kernel broke (seen after
        // its burglary runs). No flip applies; the face stays for the validator to count.
        if (stuck != nullptr) stuck->emplace_back(t, f);
        continue;
      }
      const Tet& tet = mesh_.tets[t];
      const Tet& other = mesh_.tets[ref_tet(tet.neighbor[static_cast<std::size_t>(f)])];
      if (!geometry_.in_conflict(other, tet.vertex[static_cast<std::size_t>(f)])) continue;
      std::uint64_t count = 0;
      stack_.clear();
      if (legalize_face(t, f, count, /*force=*/true) != Flip::Done) {
        if (stuck != nullptr) stuck->emplace_back(t, f);
        stack_.clear();
        continue;
      }
      ++flips;
      for (const TetId id : stack_) {
        for (int g = 0; g < 4; ++g) faces.emplace_back(id, g);
        if (created != nullptr) created->push_back(id);
      }
      stack_.clear();
    }
    return flips;
  }
};

}  // namespace dtlab::engine
