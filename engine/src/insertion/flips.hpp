#pragma once
// Legalization by flips (Kohout and Kolingerova 2003, Sect. 4; Joe 1991): the swaps S23, S32, S22
// and S44 of one face whose apex across lies inside the circumsphere, each a replacement
// (tet_replacement.hpp). The new tetrahedra go on a stack whose faces the caller checks next: the
// inserter's legalization around a new point (inserter.hpp) and the Lawson pass (lawson_pass.hpp).
#include <array>
#include <cstdint>

#include "insertion/mesh_editor.hpp"
#include "mesh/tet_id_list.hpp"

namespace dtlab::engine {

template <class K, class Sync = NoSync>
class Flipper : public MeshEditor<K, Sync> {
  using Base = MeshEditor<K, Sync>;

 public:
  using Base::Base;

  // Exhausted: the per-insertion flip bound was hit.
  enum class Flip { Done, NotApplied, GaveUp, Exhausted };

  // Face ip of live tetrahedron t (the face opposite its vertex `apex`): flips it when the vertex
  // across lies strictly inside t's circumsphere and the flip exists; the new tetrahedra go on
  // stack_. `flips` counts against the per-insertion bound.
  // With `force`, the face is flipped whether or not it is locally Delaunay (flip_face).
  Flip legalize_face(TetId t, int ip, std::uint64_t& flips, bool force = false) {
    const Tet& tet = mesh_.tets[t];
    const VertexId apex = tet.vertex[static_cast<std::size_t>(ip)];
    const FaceRef across = tet.neighbor[static_cast<std::size_t>(ip)];
    const TetId t2 = ref_tet(across);
    const VertexId y = mesh_.tets[t2].vertex[static_cast<std::size_t>(ref_face(across))];
    if (!force && !geometry_.in_conflict(mesh_.tets[t2], apex)) return Flip::NotApplied;
    if (++flips > this->options_.max_flips_per_insertion) return Flip::Exhausted;
    if (!sync_->acquire(t2)) return Flip::GaveUp;
    // A flip writes back references into the records around t and t2 (a locking policy locks
    // them first), and the legalization reads them next: ask for their cache lines now, so that
    // they arrive during the orientation tests below (docs/performance.md, "Measured choices").
    for (int f = 0; f < 4; ++f) {
      if (f != ip) mesh_.tets.prefetch(ref_tet(tet.neighbor[static_cast<std::size_t>(f)]));
      if (f != ref_face(across)) {
        mesh_.tets.prefetch(ref_tet(mesh_.tets[t2].neighbor[static_cast<std::size_t>(f)]));
      }
    }
    // Where does segment apex-y pass face F = t minus apex? o[m] is the orientation of t with
    // F's vertex m replaced by y: all positive, through F's interior; one negative, outside the
    // edge opposite m; one zero, through that edge (apex, y and the edge coplanar).
    int negative = -1;
    int zero = -1;
    int negatives = 0;
    int zeros = 0;
    std::array<int, 4> o{};
    for (int m = 0; m < 4; ++m) {
      if (m == ip) continue;
      o[static_cast<std::size_t>(m)] = geometry_.orient_replaced(tet, m, y);
      if (o[static_cast<std::size_t>(m)] < 0) {
        negative = m;
        ++negatives;
      } else if (o[static_cast<std::size_t>(m)] == 0) {
        zero = m;
        ++zeros;
      }
    }
    if (negatives == 0 && zeros == 0) return flip23(t, t2, ip, y);
    if (negatives == 1 && zeros == 0) return flip32(t, t2, ip, negative, y);
    if (zeros == 1 && negatives == 0) return flip44(t, t2, ip, zero, y);
    // Not flippable now; a later flip removes it (Joe 1991).
    return Flip::NotApplied;
  }

 protected:
  using Base::geometry_;
  using Base::mesh_;
  using Base::replacement_;
  using Base::stats_;
  using Base::sync_;
  using typename Base::Replaced;

  TetIdList stack_;  // new tetrahedra whose face opposite the point is unchecked

 private:
  // S23: abcp + abcy -> three tetrahedra around the new edge py.
  Flip flip23(TetId t, TetId t2, int ip, VertexId y) {
    std::array<int, 3> positions{};
    std::size_t n = 0;
    for (int m = 0; m < 4; ++m) {
      if (m != ip) positions[n++] = m;
    }
    const Flip result = finish_flip(replacement_.replace_known(t, t2, kNoTet, ip, y, positions));
    if (result == Flip::Done) ++stats_.flips.s23;
    return result;
  }

  // S32: the reflex edge opposite F's vertex `m` has exactly three tetrahedra (t, t2 and the one
  // across t's face m, which must contain y); they become two around the face (p, y, F[m]).
  Flip flip32(TetId t, TetId t2, int ip, int m, VertexId y) {
    const FaceRef across = mesh_.tets[t].neighbor[static_cast<std::size_t>(m)];
    const TetId t3 = ref_tet(across);
    if (mesh_.tets[t3].vertex[static_cast<std::size_t>(ref_face(across))] != y) {
      return Flip::NotApplied;
    }
    if (!sync_->acquire(t3)) return Flip::GaveUp;
    std::array<int, 2> positions{};
    std::size_t n = 0;
    for (int j = 0; j < 4; ++j) {
      if (j != ip && j != m) positions[n++] = j;
    }
    const Flip result = finish_flip(replacement_.replace_known(t, t2, t3, ip, y, positions));
    if (result == Flip::Done) ++stats_.flips.s32;
    return result;
  }

  // S44 (S22 on the hull): p, y and the edge opposite F's vertex `m` are coplanar and the edge has
  // exactly four tetrahedra; the edge is replaced by py.
  Flip flip44(TetId t, TetId t2, int ip, int m, VertexId y) {
    const Tet& tet = mesh_.tets[t];
    const VertexId vm = tet.vertex[static_cast<std::size_t>(m)];
    const FaceRef across3 = tet.neighbor[static_cast<std::size_t>(m)];
    const TetId t3 = ref_tet(across3);
    const VertexId w = mesh_.tets[t3].vertex[static_cast<std::size_t>(ref_face(across3))];
    const int m2 = mesh_.tets[t2].index_of(vm);
    if (m2 < 0) return Flip::NotApplied;  // t2 lacks t's vertex m: a broken mesh
    const FaceRef across4 = mesh_.tets[t2].neighbor[static_cast<std::size_t>(m2)];
    const TetId t4 = ref_tet(across4);
    if (mesh_.tets[t4].vertex[static_cast<std::size_t>(ref_face(across4))] != w) {
      return Flip::NotApplied;
    }
    std::array<int, 2> edge{};
    int k = 0;
    for (int j = 0; j < 4; ++j) {
      if (j != ip && j != m) edge[static_cast<std::size_t>(k++)] = j;
    }
    // The two new tetrahedra on w's side must be positively oriented too.
    const Tet& tet3 = mesh_.tets[t3];
    const int e0 = tet3.index_of(tet.vertex[static_cast<std::size_t>(edge[0])]);
    const int e1 = tet3.index_of(tet.vertex[static_cast<std::size_t>(edge[1])]);
    if (e0 < 0 || e1 < 0) return Flip::NotApplied;  // t3 lacks the edge: a broken mesh
    if (geometry_.orient_replaced(tet3, e0, y) <= 0 ||
        geometry_.orient_replaced(tet3, e1, y) <= 0) {
      return Flip::NotApplied;
    }
    if (!sync_->acquire(t3) || !sync_->acquire(t4)) return Flip::GaveUp;
    const Flip result = finish_flip(replacement_.replace_flip44(t, t2, t3, t4, ip, m, edge, y));
    if (result != Flip::Done) return result;
    if (vm == kInfiniteVertex || w == kInfiniteVertex) {
      ++stats_.flips.s22;
    } else {
      ++stats_.flips.s44;
    }
    return Flip::Done;
  }

  // NotApplied when the flip's faces do not close up (inexact kernel only); the mesh is then
  // unchanged.
  Flip finish_flip(Replaced done) {
    if (done == Replaced::GaveUp) return Flip::GaveUp;
    if (done == Replaced::Impossible) return Flip::NotApplied;
    for (const TetId id : replacement_.created()) stack_.push_back(id);
    return Flip::Done;
  }
};

}  // namespace dtlab::engine
