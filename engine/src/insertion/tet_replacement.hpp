#pragma once
// Replacing a set of tetrahedra by new ones that fill the same region: every split, flip and
// cavity of the engine ends here. The contract: the caller names the old tetrahedra (old_tets(),
// all locked by the caller when there are locks) and the new ones, each an old one with one vertex
// replaced (push_replaced) or given whole (push_new); replace() matches every face before it
// writes anything (Impossible: the new ones do not close up, nothing written; GaveUp: a lock was
// refused, nothing written), then commits them through the store's one write path
// (mesh/topology_commit.hpp: locks and logs, new records, publication, deaths, births).
// created() lists the new ids. Direct versions that link without matching: replace_known() for
// 1->4, S23 and S32, replace_flip44() for S44 and S22, replace_edge_ring() for k->2k.
// The layers: generic_replacement.hpp (matching by face keys), known_replacement.hpp (the
// frequent flips and splits linked directly), and here Bowyer-Watson's cavity.
#include <cassert>
#include <cstdint>
#include <span>
#include <vector>

#include "insertion/cavity_edges.hpp"
#include "insertion/cavity_face.hpp"
#include "insertion/known_replacement.hpp"

namespace dtlab::engine {

template <class Sync>
class TetReplacement : public KnownReplacement<Sync> {
  using Base = KnownReplacement<Sync>;
  using Base::commit_;
  using Base::created_known_;
  using Base::mesh_;
  using Base::scratch_created_;

 public:
  using Base::Base;
  using typename Base::Replaced;

  // Bowyer-Watson's replacement (cavity_search.hpp): the cavity, `cavity`, by p joined to
  // each boundary face, in `boundary`'s order. New tetrahedron j is its face's inside
  // tetrahedron with the vertex at `face` replaced by p: its face there is the boundary face, and
  // each of its three other faces holds p and one edge of the boundary face, shared with the one
  // other new tetrahedron on that edge (the boundary of a star-shaped cavity is a sphere: every
  // edge on exactly two faces). Those are paired through a table of edges. Impossible, nothing
  // published (no live record changes), when an edge is not on exactly two boundary faces or
  // there are fewer than four faces (an inexact kernel's cavity).
  //
  // The new records are written into their slots as the edges pair up, with no scratch copy:
  // the slots are this thread's, unpublished (nothing references them, and a reused one's grace
  // period is over, or nobody else can reach it: mesh/read_confinement.hpp), so writing them
  // changes nothing anyone can see. Only then is the pairing checked; an impossible one gives the
  // slots back. The outside's references to the new tetrahedra, the deaths and the births come
  // after the check, as in commit_replacement. `cavity` lists the tetrahedra replaced (the search's
  // own list, read in place).
  Replaced replace_cavity(VertexId p, std::span<const CavityFace> boundary,
                          std::span<const TetId> cavity) {
    assert(!commit_.history());
    const std::size_t n = boundary.size();
    created_known_ = false;
    scratch_created_.resize(n);
    fresh_records_.resize(n);
    for (std::size_t j = 0; j < n; ++j) {
      scratch_created_[j] = commit_.allocate();
      fresh_records_[j] = &commit_.record(scratch_created_[j]);
    }
    const TetId* ids = scratch_created_.data();
    // The new records' addresses, looked up once: each is written up to four times below.
    Tet* const* records = fresh_records_.data();
    // Face ref 4 j + g of new tetrahedron j, as the mesh names it.
    auto global = [ids](FaceRef local) { return face_ref(ids[ref_tet(local)], ref_face(local)); };
    CavityEdges::Pass edges = edges_.begin(3 * n);
    for (std::size_t j = 0; j < n; ++j) {
      const CavityFace& b = boundary[j];
      const auto face = static_cast<std::size_t>(b.face);
      Tet& fresh = *records[j];
      fresh.vertex = mesh_.tets[b.inside].vertex;
      fresh.vertex[face] = p;
      fresh.neighbor[face] = b.outside;
      for (const auto& [g, u, w] : kOtherFaces[face]) {
        // Face g holds p and the edge (u, w) of the boundary face.
        const auto self = static_cast<FaceRef>(4 * j + g);
        const FaceRef partner = edges.pair(fresh.vertex[u], fresh.vertex[w], self);
        // Branch-free: partner == self while the edge's second face is still to come (that face
        // writes both references then).
        fresh.neighbor[g] = global(partner);
        records[ref_tet(partner)]->neighbor[static_cast<std::size_t>(ref_face(partner))] =
            global(self);
      }
    }
    // No edge on three faces, so every edge is paired exactly when there are 3n / 2 of them. A
    // closed surface of triangles has at least four: fewer is an inexact kernel's cavity (one
    // that took in every tetrahedron, infinite ones included, has no boundary at all and would
    // leave an empty mesh behind).
    if (n < 4 || edges.third_face() || 2 * edges.size() != 3 * n) {
      for (std::size_t j = n; j-- > 0;) commit_.give_back(ids[j]);
      scratch_created_.clear();
      return Replaced::Impossible;
    }
    // The search locked every tetrahedron written from here on (a confined policy's outside
    // neighbours excepted: cavity_search.hpp), and nothing after this write can be refused: no
    // undo log, and the new and dead tetrahedra stay out of the lists that only a rollback reads.
    for (std::size_t j = 0; j < n; ++j) commit_.created(ids[j], /*last_write=*/true);
    // Publishing: the outside's references to the complete new records (release).
    for (std::size_t j = 0; j < n; ++j) {
      const CavityFace& b = boundary[j];
      commit_.publish(b.outside, face_ref(ids[j], b.face));
    }
    for (const TetId o : cavity) {
      commit_.kill(
          o, [](TetStore::Children& /*no history*/) {}, /*last_write=*/true);
    }
    for (std::size_t j = 0; j < n; ++j) commit_.born(ids[j]);
    return Replaced::Done;
  }

 private:
  // kOtherFaces[a]: for each position g != a, g and the two positions other than a and g.
  struct OtherFace {
    std::size_t g, u, w;
  };
  static constexpr std::array<std::array<OtherFace, 3>, 4> kOtherFaces{{
      {{{1, 2, 3}, {2, 1, 3}, {3, 1, 2}}},
      {{{0, 2, 3}, {2, 0, 3}, {3, 0, 2}}},
      {{{0, 1, 3}, {1, 0, 3}, {3, 0, 1}}},
      {{{0, 1, 2}, {1, 0, 2}, {2, 0, 1}}},
  }};
  std::vector<Tet*> fresh_records_;  // the new tetrahedra's records
  CavityEdges edges_;
};

}  // namespace dtlab::engine
