#pragma once
// The most frequent replacements, linked without matching keys (the contract: tet_replacement.hpp):
// 1->4, S23 and S32 (replace_known), S44 and S22 (replace_flip44). Each checks that the
// neighbourhood is the textbook one and otherwise leaves the replacement to the generic matching
// (generic_replacement.hpp), which decides as before.
#include <array>
#include <atomic>
#include <cstdint>
#include <span>

#include "insertion/generic_replacement.hpp"

namespace dtlab::engine {

template <class Sync>
class KnownReplacement : public GenericReplacement<Sync> {
  using Base = GenericReplacement<Sync>;

 public:
  using Base::Base;
  using Base::begin;
  using Base::push_replaced;
  using Base::replace;
  using typename Base::Replaced;

  // The three most frequent replacements, written directly: 1->4 (N = 4, old t), S23 (N = 3, old
  // t and t2) and S32 (N = 2, old t, t2 and t3). New tetrahedron j is t with the vertex at
  // positions[j] replaced by `put`, and its faces follow from the adjacency alone, without
  // matching keys. Two new tetrahedra made from t by replacing positions a and b share the face
  // opposite b in the first and opposite a in the second; a new tetrahedron's face at its own
  // replaced position is t's face there; its face opposite p (S23, S32) belongs to t2, across t's
  // face ip, and its face opposite t[m] (S32) to t3, across t's face m; each is found by the
  // vertex it lacks, t[a]. N is a template argument so that every loop below has a known length
  // (with a run-time count and a table of matches, a flip took several times the instructions).
  // When the neighbourhood is not the textbook one (a broken mesh from an inexact kernel: the
  // vertex put in already in t, old tetrahedra not glued to each other both ways, or an outside
  // face that belongs to an old tetrahedron) the generic matching of replace() decides.
  template <std::size_t N>
  Replaced replace_known(TetId t, TetId t2, TetId t3, int ip, VertexId put,
                         const std::array<int, N>& positions) {
    static_assert(N >= 2 && N <= 4);
    constexpr std::size_t kOld = 5 - N;  // 1->4, 2->3, 3->2
    const std::array<TetId, 3> old{t, t2, t3};
    const Tet& tet = mesh_.tets[t];
    auto generic = [&] {
      scratch_old_.assign(old.begin(), old.begin() + kOld);
      scratch_new_.clear();
      scratch_parent_.clear();
      scratch_source_.clear();
      for (std::size_t j = 0; j < N; ++j) push_replaced(t, positions[j], put, kOld == 1 ? 0 : -1);
      return replace();
    };
    if (tet.index_of(put) >= 0) return generic();
    // The old tetrahedra other than t, and the face of t each lies across (ip, then m).
    std::array<const Tet*, kOld - 1> others{};
    std::array<int, kOld - 1> across{};
    if constexpr (kOld >= 2) {
      const Tet& second = mesh_.tets[t2];
      const int put_at = second.index_of(put);
      if (put_at < 0 || second.neighbor[static_cast<std::size_t>(put_at)] != face_ref(t, ip)) {
        return generic();
      }
      others[0] = &second;
      across[0] = ip;
      if constexpr (kOld == 3) {
        const int m = 6 - ip - positions[0] - positions[1];
        const Tet& third = mesh_.tets[t3];
        const int m_at = second.index_of(tet.vertex[static_cast<std::size_t>(m)]);
        const int p_at = third.index_of(tet.vertex[static_cast<std::size_t>(ip)]);
        // Glued both ways: t and t3 across t's face m, t2 and t3 across t2's face at t[m].
        const FaceRef to3 = tet.neighbor[static_cast<std::size_t>(m)];
        if (m_at < 0 || p_at < 0 || ref_tet(to3) != t3 ||
            second.neighbor[static_cast<std::size_t>(m_at)] != face_ref(t3, p_at) ||
            third.neighbor[static_cast<std::size_t>(p_at)] != face_ref(t2, m_at) ||
            third.neighbor[static_cast<std::size_t>(ref_face(to3))] != face_ref(t, m)) {
          return generic();
        }
        others[1] = &third;
        across[1] = m;
      }
    }
    // New tetrahedron j's faces on the region's boundary: out_face[j][r] (its own replaced
    // position, then ip and m), across which lies the outside face out_ref[j][r]. Its other
    // faces are inner: face positions[k] is new k's face positions[j].
    // Not value-initialized: every entry is written below, and zeroing them was a `rep stos`,
    // whose start-up S32 paid at every flip.
    std::array<std::array<int, kOld>, N>
        out_face;  // NOLINT(cppcoreguidelines-pro-type-member-init)
    std::array<std::array<FaceRef, kOld>, N>
        out_ref;  // NOLINT(cppcoreguidelines-pro-type-member-init)
    for (std::size_t j = 0; j < N; ++j) {
      const int a = positions[j];
      const VertexId lost = tet.vertex[static_cast<std::size_t>(a)];
      out_face[j][0] = a;
      out_ref[j][0] = tet.neighbor[static_cast<std::size_t>(a)];
      for (std::size_t r = 1; r < kOld; ++r) {
        const int i = others[r - 1]->index_of(lost);
        if (i < 0) return generic();
        out_face[j][r] = across[r - 1];
        out_ref[j][r] = others[r - 1]->neighbor[static_cast<std::size_t>(i)];
      }
      for (std::size_t r = 0; r < kOld; ++r) {
        for (std::size_t q = 0; q < kOld; ++q) {
          if (ref_tet(out_ref[j][r]) == old[q]) return generic();
        }
      }
    }

    const auto outside = [&](auto&& visit) {
      for (std::size_t j = 0; j < N; ++j) {
        for (std::size_t r = 0; r < kOld; ++r) visit(ref_tet(out_ref[j][r]));
      }
    };
    if (!commit_.lock_and_log(outside, std::span<const TetId>(old.data(), kOld))) {
      return Replaced::GaveUp;
    }
    std::array<TetId, N> ids{};
    for (std::size_t j = 0; j < N; ++j) ids[j] = commit_.allocate();
    // The new records: their slots are this thread's and unpublished (fresh, or reused after
    // their grace period or, for a confined thread, at once), so nobody reads them before the
    // outside's references below.
    for (std::size_t j = 0; j < N; ++j) {
      // Written in place, field by field: a record assembled on the stack from 4-byte stores and
      // copied with 16-byte loads stalled on store forwarding.
      Tet& fresh = commit_.record(ids[j]);
      fresh.vertex = tet.vertex;
      fresh.vertex[static_cast<std::size_t>(positions[j])] = put;
      for (std::size_t k = 0; k < N; ++k) {
        if (k != j)
          fresh.neighbor[static_cast<std::size_t>(positions[k])] = face_ref(ids[k], positions[j]);
      }
      for (std::size_t r = 0; r < kOld; ++r) {
        fresh.neighbor[static_cast<std::size_t>(out_face[j][r])] = out_ref[j][r];
      }
      commit_.created(ids[j]);
    }
    // Then the outside's references to them (release): a walking thread that reaches a new
    // tetrahedron finds all four of its references set.
    for (std::size_t j = 0; j < N; ++j) {
      for (std::size_t r = 0; r < kOld; ++r) {
        commit_.publish(out_ref[j][r], face_ref(ids[j], out_face[j][r]));
      }
    }
    // Every old tetrahedron is covered by all the new ones (1->4 has one old tetrahedron).
    end_known(std::span<const TetId>(old.data(), kOld), ids);
    return Replaced::Done;
  }

  // S44 (S22 on the hull), the most frequent flip on grids: t, t2 across t's face ip (apex y), t3
  // across t's face m and t4 across t3's face opposite p (apex y) lie around the edge
  // t[edge[0]] t[edge[1]]; new s (s = 0, 1) is t with t[edge[s]] replaced by y and new 2 + s is
  // t3 with the same vertex replaced. These are link_from_sources' rules with every lookup known:
  // each new one's face at its replaced position is its source's, on the boundary; the two copies
  // of one source share a face; the copies of t and t3 that replaced the same vertex share the
  // face across t's face m; and the face of a copy of t across t's face ip is t2's face opposite
  // the replaced vertex (of a copy of t3, across t3's face opposite p, t4's), on the boundary. The
  // neighbourhood is checked as in replace_known (the four tetrahedra distinct, each pair that
  // shares a face glued both ways, t2's and t4's apex y, y in neither t nor t3, no boundary face
  // that belongs to an old tetrahedron); otherwise the generic replace() decides. Written directly,
  // as replace_known (through commit_replacement's vectors it was a quarter of the grid's linking
  // time).
  Replaced replace_flip44(TetId t, TetId t2, TetId t3, TetId t4, int ip, int m,
                          const std::array<int, 2>& edge, VertexId y) {
    const Tet& first = mesh_.tets[t];
    const Tet& third = mesh_.tets[t3];
    auto generic = [&] {
      begin({t, t2, t3, t4});
      const int e0 = third.index_of(first.vertex[static_cast<std::size_t>(edge[0])]);
      const int e1 = third.index_of(first.vertex[static_cast<std::size_t>(edge[1])]);
      push_replaced(t, edge[0], y, -1);
      push_replaced(t, edge[1], y, -1);
      if (e0 < 0 || e1 < 0) return Replaced::Impossible;  // t3 does not hold the edge
      push_replaced(t3, e0, y, -1);
      push_replaced(t3, e1, y, -1);
      return replace();
    };
    const FaceRef to2 = first.neighbor[static_cast<std::size_t>(ip)];
    const FaceRef to3 = first.neighbor[static_cast<std::size_t>(m)];
    const int w_at = ref_face(to3);
    const int p_at = third.index_of(first.vertex[static_cast<std::size_t>(ip)]);
    if (ref_tet(to2) != t2 || ref_tet(to3) != t3 || p_at < 0 || t3 == t || t4 == t || t4 == t2 ||
        t4 == t3 || third.neighbor[static_cast<std::size_t>(w_at)] != face_ref(t, m) ||
        first.index_of(y) >= 0 || third.index_of(y) >= 0) {
      return generic();
    }
    const FaceRef to4 = third.neighbor[static_cast<std::size_t>(p_at)];
    const Tet& second = mesh_.tets[t2];
    const Tet& fourth = mesh_.tets[t4];
    if (ref_tet(to4) != t4 || second.vertex[static_cast<std::size_t>(ref_face(to2))] != y ||
        fourth.vertex[static_cast<std::size_t>(ref_face(to4))] != y ||
        second.neighbor[static_cast<std::size_t>(ref_face(to2))] != face_ref(t, ip) ||
        fourth.neighbor[static_cast<std::size_t>(ref_face(to4))] != face_ref(t3, p_at)) {
      return generic();
    }
    {
      // t2 and t4 glued both ways, across t2's face at t[m] and t4's face at t3's apex w.
      const int vm_at2 = second.index_of(first.vertex[static_cast<std::size_t>(m)]);
      const int w_at4 = fourth.index_of(third.vertex[static_cast<std::size_t>(w_at)]);
      if (vm_at2 < 0 || w_at4 < 0 ||
          second.neighbor[static_cast<std::size_t>(vm_at2)] != face_ref(t4, w_at4) ||
          fourth.neighbor[static_cast<std::size_t>(w_at4)] != face_ref(t2, vm_at2)) {
        return generic();
      }
    }
    const std::array<TetId, 4> old{t, t2, t3, t4};
    auto is_old = [&](FaceRef r) {
      const TetId o = ref_tet(r);
      return o == t || o == t2 || o == t3 || o == t4;
    };
    FixedLinks<4> links;
    for (std::size_t s = 0; s < 2; ++s) {
      const int e = edge[s];
      const int other = edge[1 - s];
      const VertexId v = first.vertex[static_cast<std::size_t>(e)];
      const int e3 = third.index_of(v);
      const int other3 = third.index_of(first.vertex[static_cast<std::size_t>(other)]);
      const int e2 = second.index_of(v);
      const int e4 = fourth.index_of(v);
      if (e3 < 0 || other3 < 0 || e2 < 0 || e4 < 0 ||
          ((1 << e3) | (1 << other3) | (1 << w_at) | (1 << p_at)) != 15) {
        return generic();  // every face of each new tetrahedron is set below, once
      }
      const std::array<FaceRef, 4> outside{first.neighbor[static_cast<std::size_t>(e)],
                                           second.neighbor[static_cast<std::size_t>(e2)],
                                           third.neighbor[static_cast<std::size_t>(e3)],
                                           fourth.neighbor[static_cast<std::size_t>(e4)]};
      for (const FaceRef r : outside) {
        if (is_old(r)) return generic();
      }
      const std::size_t from_first = s;
      const std::size_t from_third = 2 + s;
      links.quad[from_first] = first.vertex;
      links.quad[from_first][static_cast<std::size_t>(e)] = y;
      links.quad[from_third] = third.vertex;
      links.quad[from_third][static_cast<std::size_t>(e3)] = y;
      links.outside(from_first, e, outside[0]);
      links.inner(from_first, other, 1 - s, e);
      links.outside(from_first, ip, outside[1]);
      links.inner(from_first, m, 2 + s, w_at);
      links.outside(from_third, e3, outside[2]);
      links.inner(from_third, other3, 3 - s, e3);
      links.inner(from_third, w_at, s, m);
      links.outside(from_third, p_at, outside[3]);
    }
    return commit_fixed(old, links);
  }

 protected:
  using Base::commit_;
  using Base::created_known_;
  using Base::known_count_;
  using Base::known_created_;
  using Base::mesh_;
  using Base::scratch_new_;
  using Base::scratch_old_;
  using Base::scratch_parent_;
  using Base::scratch_source_;

  // A replacement whose N new tetrahedra and every link are known (replace_flip44): new j is
  // quad[j]; its face f lies across link[j][f], an outside face as the mesh names it, or (bit f of
  // inner_mask[j]) face g of new k, as 4 k + g.
  template <std::size_t N>
  struct FixedLinks {
    // quad and link are written whole by the caller before use (not zeroed: see out_face in
    // replace_known); the mask starts empty.
    std::array<Quad, N> quad;                    // NOLINT(cppcoreguidelines-pro-type-member-init)
    std::array<std::array<FaceRef, 4>, N> link;  // NOLINT(cppcoreguidelines-pro-type-member-init)
    std::array<unsigned, N> inner_mask{};
    void outside(std::size_t j, int f, FaceRef r) { link[j][static_cast<std::size_t>(f)] = r; }
    void inner(std::size_t j, int f, std::size_t k, int g) {
      link[j][static_cast<std::size_t>(f)] = face_ref(static_cast<TetId>(k), g);
      inner_mask[j] |= 1U << f;
    }
    [[nodiscard]] bool is_inner(std::size_t j, std::size_t f) const {
      return ((inner_mask[j] >> f) & 1U) != 0;
    }
  };

  // commit_replacement for FixedLinks, with the same order of locks and logs and the same
  // publication (the new records complete, then the outside's references to them, with release;
  // the records themselves by plain stores, as in replace_known); every old tetrahedron gets every
  // new one as a DAG child.
  template <std::size_t N, std::size_t kOld>
  Replaced commit_fixed(const std::array<TetId, kOld>& old, const FixedLinks<N>& links) {
    const auto outside = [&](auto&& visit) {
      for (std::size_t j = 0; j < N; ++j) {
        for (std::size_t f = 0; f < 4; ++f) {
          if (!links.is_inner(j, f)) visit(ref_tet(links.link[j][f]));
        }
      }
    };
    if (!commit_.lock_and_log(outside, std::span<const TetId>(old))) return Replaced::GaveUp;
    std::array<TetId, N> ids{};
    for (std::size_t j = 0; j < N; ++j) ids[j] = commit_.allocate();
    for (std::size_t j = 0; j < N; ++j) {
      Tet& fresh = commit_.record(ids[j]);  // in place, as in replace_known
      fresh.vertex = links.quad[j];
      for (std::size_t f = 0; f < 4; ++f) {
        const FaceRef l = links.link[j][f];
        fresh.neighbor[f] = links.is_inner(j, f) ? face_ref(ids[ref_tet(l)], ref_face(l)) : l;
      }
      commit_.created(ids[j]);
    }
    for (std::size_t j = 0; j < N; ++j) {
      for (std::size_t f = 0; f < 4; ++f) {
        if (links.is_inner(j, f)) continue;
        commit_.publish(links.link[j][f], face_ref(ids[j], static_cast<int>(f)));
      }
    }
    end_known(std::span<const TetId>(old), ids);
    return Replaced::Done;
  }

  // The end of replace_known and commit_fixed, after the outside's references: the old
  // tetrahedra die (walk mode: their slots retired for reuse; DAG mode: each the parent of every
  // new one, children published first), then the new ones are created() and live.
  template <std::size_t N>
  void end_known(std::span<const TetId> old, const std::array<TetId, N>& ids) {
    for (const TetId o : old) {
      commit_.kill(o, [&](TetStore::Children& children) {
        for (std::size_t j = 0; j < N; ++j) children[j].store(ids[j], std::memory_order_release);
      });
    }
    for (std::size_t j = 0; j < N; ++j) known_created_[j] = ids[j];
    known_count_ = N;
    created_known_ = true;
    for (std::size_t j = 0; j < N; ++j) commit_.born(ids[j]);
  }
};

}  // namespace dtlab::engine
