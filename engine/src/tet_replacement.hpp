#pragma once
// Replacing a set of tetrahedra by new ones that fill the same region: every split and flip of
// the engine ends here. The contract: the caller names the old tetrahedra (old_tets(), all
// locked by the caller when there are locks) and the new ones, each an old one with one vertex
// replaced (push_replaced) or given whole (push_new); replace() matches every face before it
// writes anything (Impossible: the new ones do not close up, nothing written; GaveUp: a lock was
// refused, nothing written), then writes the new records, the neighbour references (new ones
// complete before the outside links to them), the DAG children, the deaths and the births.
// created() lists the new ids. Direct versions that link without matching: replace_known() for
// 1->4, S23 and S32, replace_flip44() for S44 and S22, replace_edge_ring() for k->2k.
#include <algorithm>
#include <array>
#include <atomic>
#include <cassert>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <utility>
#include <vector>

#include "cavity_edges.hpp"
#include "cavity_face.hpp"
#include "conflict.hpp"  // Quad
#include "dtlab/engine/tet_mesh.hpp"
#include "shared_mesh.hpp"
#include "slot_allocator.hpp"

namespace dtlab::engine {

template <class Sync>
class TetReplacement {
 public:
  enum class Replaced { Done, Impossible, GaveUp };

  // keep_dag: the old tetrahedra get the new ones as DAG children (not when slots are reused).
  TetReplacement(SharedMesh& mesh, Sync& sync, SlotAllocator& slots, bool keep_dag)
      : mesh_(mesh),
        sync_(sync),
        slots_(slots),
        recycle_(!keep_dag),
        dag_(keep_dag && mesh.tets.has_children()) {}

  // Starts a replacement of `old` (or of what the caller then puts in old_tets()).
  void begin(std::initializer_list<TetId> old) {
    scratch_old_.assign(old.begin(), old.end());
    scratch_new_.clear();
    scratch_parent_.clear();
    scratch_source_.clear();
  }
  std::vector<TetId>& old_tets() { return scratch_old_; }
  // The new ids of the last replacement that wrote (replace_known's and commit_fixed's in a fixed
  // array: a vector's assign or resize of 2 to 4 ids was a call, and its memmove 5 % of a
  // sequential walk's time with flips at 1M points).
  [[nodiscard]] std::span<const TetId> created() const {
    if (created_known_) return {known_created_.data(), known_count_};
    return scratch_created_;
  }

  // Adds to scratch_new_ tetrahedron t's copy with the vertex at `position` replaced by v. Its
  // face `position` is t's face `position`: replace() links it without searching.
  void push_replaced(TetId t, int position, VertexId v, int parent) {
    Quad q = mesh_.tets[t].vertex;
    q[static_cast<std::size_t>(position)] = v;
    scratch_new_.push_back(q);
    scratch_parent_.push_back(parent);
    scratch_source_.push_back({t, position});
  }
  // A new tetrahedron given whole, child of every old one, linked by matching only.
  void push_new(const Quad& q) {
    scratch_new_.push_back(q);
    scratch_parent_.push_back(-1);
    scratch_source_.push_back({kNoTet, 0});
  }

  // Replaces the tetrahedra scratch_old_ by scratch_new_ (same region), linking the new ones to
  // each other and to the outside by their shared faces. scratch_parent_[j] is the index in
  // scratch_old_ of new tetrahedron j's only DAG parent, or -1 when it is a child of every old one.
  // Every face is matched before anything is written: when the new tetrahedra do not close up
  // (only possible with an inexact kernel's contradictory signs) nothing changes and the result
  // is false. The new ids land in scratch_created_.
  Replaced replace() {
    if (link_from_sources()) return commit_replacement();
    auto is_old = [&](TetId t) {
      return std::find(scratch_old_.begin(), scratch_old_.end(), t) != scratch_old_.end();
    };
    // Direct links: new tetrahedron j's face `position` is its source's face `position`.
    matched_.assign(4 * scratch_new_.size(), FaceMatch{0, false, false});
    claimed_.clear();
    for (std::size_t j = 0; j < scratch_new_.size(); ++j) {
      const auto [source, position] = scratch_source_[j];
      if (source == kNoTet) continue;
      const FaceRef outside = mesh_.tets[source].neighbor[static_cast<std::size_t>(position)];
      if (is_old(ref_tet(outside))) continue;
      matched_[4 * j + static_cast<std::size_t>(position)] = {outside, false, true};
      claimed_.push_back(face_ref(source, position));
    }
    // The other faces of the region's boundary, seen from outside.
    open_faces_.clear();
    for (const TetId o : scratch_old_) {
      const Tet& tet = mesh_.tets[o];
      for (int f = 0; f < 4; ++f) {
        const FaceRef outside = tet.neighbor[static_cast<std::size_t>(f)];
        if (is_old(ref_tet(outside))) continue;
        if (std::find(claimed_.begin(), claimed_.end(), face_ref(o, f)) != claimed_.end()) continue;
        open_faces_.push_back({face_key(tet.vertex, f), outside, false});
      }
    }
    // Match the remaining new faces before writing anything.
    for (std::size_t j = 0; j < scratch_new_.size(); ++j) {
      for (int f = 0; f < 4; ++f) {
        const auto self = static_cast<FaceRef>(4 * j + static_cast<std::size_t>(f));
        if (matched_[self].set) continue;
        const auto key = face_key(scratch_new_[j], f);
        const auto match = std::find_if(open_faces_.begin(), open_faces_.end(),
                                        [&](const OpenFace& of) { return of.key == key; });
        if (match == open_faces_.end()) {
          open_faces_.push_back({key, self, true});
          continue;
        }
        matched_[self] = {match->ref, match->is_new, true};
        if (match->is_new) matched_[match->ref] = {self, true, true};
        *match = open_faces_.back();
        open_faces_.pop_back();
      }
    }
    if (!open_faces_.empty()) return Replaced::Impossible;
    return commit_replacement();
  }

  // k->2k, the split of edge ab by p: old_tets() is the ring of tetrahedra around ab in ring
  // order (each glued to the next), and new tetrahedra 2r and 2r + 1 are ring tetrahedron r with
  // a, then b, replaced by p (push_replaced, parent r). Linked by link_edge_ring, without the
  // generic search; replace() decides where that does not apply.
  Replaced replace_edge_ring(VertexId a, VertexId b) {
    if (link_edge_ring(a, b)) return commit_replacement();
    return replace();
  }

  // The three most frequent replacements, written directly: 1->4 (N = 4, old t), S23 (N = 3, old
  // t and t2) and S32 (N = 2, old t, t2 and t3). New tetrahedron j is t with the vertex at
  // positions[j] replaced by `put`, and its faces follow from the adjacency alone, without
  // matching keys. Two new tetrahedra made from t by replacing positions a and b share the face
  // opposite b in the first and opposite a in the second; a new tetrahedron's face at its own
  // replaced position is t's face there; its face opposite p (S23, S32) belongs to t2, across t's
  // face ip, and its face opposite t[m] (S32) to t3, across t's face m; each is found by the
  // vertex it lacks, t[a]. N is a template argument so that every loop below has a known length
  // (with a run-time count and a table of matches, this was 900 instructions per flip).
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
    // Not value-initialized: every entry is written below, and zeroing them was a `rep stos`
    // (its start-up, a tenth of S32's samples at 1M points).
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

    // As in commit_replacement: lock every tetrahedron written, log it before its first write.
    if constexpr (Sync::kLocks) {
      for (std::size_t j = 0; j < N; ++j) {
        for (std::size_t r = 0; r < kOld; ++r) {
          if (!sync_.acquire(ref_tet(out_ref[j][r]))) return Replaced::GaveUp;
        }
      }
      for (std::size_t j = 0; j < N; ++j) {
        for (std::size_t r = 0; r < kOld; ++r) sync_.before_write(ref_tet(out_ref[j][r]));
      }
      for (std::size_t r = 0; r < kOld; ++r) sync_.before_write(old[r]);
    }
    std::array<TetId, N> ids{};
    for (std::size_t j = 0; j < N; ++j) ids[j] = slots_.allocate();
    // The new records: their slots are this thread's and unpublished (fresh, or reused after
    // their grace period), so nobody reads them before the outside's references below.
    for (std::size_t j = 0; j < N; ++j) {
      // Written in place, field by field: a record assembled on the stack from 4-byte stores and
      // copied with 16-byte loads stalled on store forwarding (a fifth of this function's samples).
      Tet& fresh = mesh_.tets[ids[j]];
      fresh.vertex = tet.vertex;
      fresh.vertex[static_cast<std::size_t>(positions[j])] = put;
      for (std::size_t k = 0; k < N; ++k) {
        if (k != j)
          fresh.neighbor[static_cast<std::size_t>(positions[k])] = face_ref(ids[k], positions[j]);
      }
      for (std::size_t r = 0; r < kOld; ++r) {
        fresh.neighbor[static_cast<std::size_t>(out_face[j][r])] = out_ref[j][r];
      }
      if (dag_) {
        for (auto& c : mesh_.tets.children(ids[j])) c.store(kNoTet, std::memory_order_relaxed);
      }
      sync_.created(ids[j]);
    }
    // Then the outside's references to them (release): a walking thread that reaches a new
    // tetrahedron finds all four of its references set.
    for (std::size_t j = 0; j < N; ++j) {
      for (std::size_t r = 0; r < kOld; ++r) {
        const FaceRef l = out_ref[j][r];
        store_neighbor(mesh_.tets[ref_tet(l)], ref_face(l), face_ref(ids[j], out_face[j][r]));
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

  // Bowyer-Watson's replacement (cavity_search.hpp): the cavity, `cavity`, by p joined to
  // each boundary face, in `boundary`'s order. New tetrahedron j is its face's inside
  // tetrahedron with the vertex at `face` replaced by p: its face there is the boundary face, and
  // each of its three other faces holds p and one edge of the boundary face, shared with the one
  // other new tetrahedron on that edge (the boundary of a star-shaped cavity is a sphere: every
  // edge on exactly two faces). Those are paired through a table of edges. Impossible, nothing
  // published (no live record changes), when an edge is not on exactly two boundary faces (an
  // inexact kernel's cavity).
  //
  // The new records are written into their slots as the edges pair up, with no scratch copy:
  // the slots are this thread's, unpublished (nothing references them, and a reused one's grace
  // period is over), so writing them changes nothing anyone can see. Only then is the pairing
  // checked; an impossible one gives the slots back. The outside's references to the new
  // tetrahedra, the deaths and the births come after the check, as in commit_replacement.
  // `cavity` lists the tetrahedra replaced (the search's own list, read in place).
  Replaced replace_cavity(VertexId p, std::span<const CavityFace> boundary,
                          std::span<const TetId> cavity) {
    assert(!dag_);
    const std::size_t n = boundary.size();
    created_known_ = false;
    scratch_created_.resize(n);
    fresh_records_.resize(n);
    for (std::size_t j = 0; j < n; ++j) {
      scratch_created_[j] = slots_.allocate();
      fresh_records_[j] = &mesh_.tets[scratch_created_[j]];
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
    // No edge on three faces, so every edge is paired exactly when there are 3n / 2 of them.
    if (edges.third_face() || 2 * edges.size() != 3 * n) {
      for (std::size_t j = n; j-- > 0;) {
        // Dead again: where aliveness is kept in the record, writing the record made it look alive.
        mesh_.tets.set_alive<std::memory_order_relaxed>(ids[j], false);
        slots_.give_back(ids[j]);
      }
      scratch_created_.clear();
      return Replaced::Impossible;
    }
    // The search locked every tetrahedron written from here on, and nothing after this write can
    // be refused: no undo log, and the new and dead tetrahedra stay out of the lists that only a
    // rollback reads.
    for (std::size_t j = 0; j < n; ++j) sync_.created(ids[j], /*last_write=*/true);
    // Publishing: the outside's references to the complete new records (release).
    for (std::size_t j = 0; j < n; ++j) {
      const CavityFace& b = boundary[j];
      store_neighbor(mesh_.tets[ref_tet(b.outside)], ref_face(b.outside), face_ref(ids[j], b.face));
    }
    for (const TetId o : cavity) {
      mesh_.tets.set_alive(o, false);
      slots_.retire(o);
      sync_.killed(o, /*last_write=*/true);
    }
    for (std::size_t j = 0; j < n; ++j) mesh_.tets.set_alive(ids[j], true);
    return Replaced::Done;
  }

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
    if constexpr (Sync::kLocks) {
      for (std::size_t j = 0; j < N; ++j) {
        for (std::size_t f = 0; f < 4; ++f) {
          if (!links.is_inner(j, f) && !sync_.acquire(ref_tet(links.link[j][f]))) {
            return Replaced::GaveUp;
          }
        }
      }
      for (std::size_t j = 0; j < N; ++j) {
        for (std::size_t f = 0; f < 4; ++f) {
          if (!links.is_inner(j, f)) sync_.before_write(ref_tet(links.link[j][f]));
        }
      }
      for (const TetId o : old) sync_.before_write(o);
    }
    std::array<TetId, N> ids{};
    for (std::size_t j = 0; j < N; ++j) ids[j] = slots_.allocate();
    for (std::size_t j = 0; j < N; ++j) {
      Tet& fresh = mesh_.tets[ids[j]];  // in place, as in replace_known
      fresh.vertex = links.quad[j];
      for (std::size_t f = 0; f < 4; ++f) {
        const FaceRef l = links.link[j][f];
        fresh.neighbor[f] = links.is_inner(j, f) ? face_ref(ids[ref_tet(l)], ref_face(l)) : l;
      }
      if (dag_) {
        for (auto& c : mesh_.tets.children(ids[j])) c.store(kNoTet, std::memory_order_relaxed);
      }
      sync_.created(ids[j]);
    }
    for (std::size_t j = 0; j < N; ++j) {
      for (std::size_t f = 0; f < 4; ++f) {
        if (links.is_inner(j, f)) continue;
        const FaceRef l = links.link[j][f];
        store_neighbor(mesh_.tets[ref_tet(l)], ref_face(l), face_ref(ids[j], static_cast<int>(f)));
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
      if (recycle_) {
        mesh_.tets.set_alive(o, false);
        slots_.retire(o);
        sync_.killed(o);
        continue;
      }
      if (dag_) {
        auto& children = mesh_.tets.children(o);
        for (std::size_t j = 0; j < N; ++j) children[j].store(ids[j], std::memory_order_release);
      }
      mesh_.tets.set_alive(o, false);
      sync_.killed(o);
    }
    for (std::size_t j = 0; j < N; ++j) known_created_[j] = ids[j];
    known_count_ = N;
    created_known_ = true;
    for (std::size_t j = 0; j < N; ++j) mesh_.tets.set_alive(ids[j], true);
  }

  // A lock can still be refused after these writes (a split or flip is followed by the rest of
  // the legalization): every tetrahedron written below is locked first (the outside neighbours
  // get new back references; the old ones are locked already), and the undo log sees each before
  // its first write.
  Replaced commit_replacement() {
    if constexpr (Sync::kLocks) {
      for (const FaceMatch& m : matched_) {
        if (!m.is_new && !sync_.acquire(ref_tet(m.ref))) return Replaced::GaveUp;
      }
      for (const FaceMatch& m : matched_) {
        if (!m.is_new) sync_.before_write(ref_tet(m.ref));
      }
      for (const TetId o : scratch_old_) sync_.before_write(o);
    }

    created_known_ = false;
    scratch_created_.clear();
    for (const Quad& q : scratch_new_) {
      const TetId id = slots_.allocate();
      Tet& tet = mesh_.tets[id];
      tet.vertex = q;
      if (dag_) {
        for (auto& c : mesh_.tets.children(id)) c.store(kNoTet, std::memory_order_relaxed);
      }
      sync_.created(id);  // locked by this thread before anyone can reach it
      scratch_created_.push_back(id);
    }
    // The new tetrahedra's own references first, then the outside's references to them.
    for (std::size_t j = 0; j < scratch_created_.size(); ++j) {
      Tet& tet = mesh_.tets[scratch_created_[j]];
      for (int f = 0; f < 4; ++f) {
        const FaceMatch m = matched_[4 * j + static_cast<std::size_t>(f)];
        store_neighbor(
            tet, f, m.is_new ? face_ref(scratch_created_[ref_tet(m.ref)], ref_face(m.ref)) : m.ref);
      }
    }
    for (std::size_t j = 0; j < scratch_created_.size(); ++j) {
      for (int f = 0; f < 4; ++f) {
        const FaceMatch m = matched_[4 * j + static_cast<std::size_t>(f)];
        if (!m.is_new) {
          store_neighbor(mesh_.tets[ref_tet(m.ref)], ref_face(m.ref),
                         face_ref(scratch_created_[j], f));
        }
      }
    }
    // History: children first (release), then the old tetrahedra die, then the new ones live.
    // A recycling engine keeps no history: the old slots are reused after this insertion.
    for (std::size_t r = 0; r < scratch_old_.size(); ++r) {
      if (recycle_) {
        mesh_.tets.set_alive(scratch_old_[r], false);
        slots_.retire(scratch_old_[r]);
        sync_.killed(scratch_old_[r]);
        continue;
      }
      int slot = 0;
      for (std::size_t j = 0; dag_ && j < scratch_created_.size(); ++j) {
        if (scratch_parent_[j] == -1 || scratch_parent_[j] == static_cast<int>(r)) {
          mesh_.tets.children(scratch_old_[r])[static_cast<std::size_t>(slot++)].store(
              scratch_created_[j], std::memory_order_release);
        }
      }
      mesh_.tets.set_alive(scratch_old_[r], false);
      sync_.killed(scratch_old_[r]);
    }
    for (const TetId id : scratch_created_) mesh_.tets.set_alive(id, true);
    return Replaced::Done;
  }

 private:
  [[nodiscard]] int old_index(TetId t) const {
    for (std::size_t r = 0; r < scratch_old_.size(); ++r) {
      if (scratch_old_[r] == t) return static_cast<int>(r);
    }
    return -1;
  }

  // replace_edge_ring's links. Copy 2r of ring tetrahedron R_r (a replaced by p, at a's position
  // ia) and copy 2r + 1 (b replaced, at ib): face ia of copy 2r is R_r's face ia, on the
  // boundary (likewise face ib of copy 2r + 1); the two copies share their faces ib and ia; and
  // across R_r's face c (c the position of one of its two other vertices) lies its ring neighbour
  // R_q, at face g, so face c of each copy of R_r is face g of the copy of R_q that replaced the
  // same vertex. False (nothing written) where the ring is not the textbook one: the new
  // tetrahedra not in that order, p in a ring tetrahedron, a ring neighbour that is not the next
  // or the previous one or not glued back, or a boundary face that belongs to the ring.
  bool link_edge_ring(VertexId a, VertexId b) {
    const std::size_t k = scratch_old_.size();
    if (k < 3 || scratch_new_.size() != 2 * k) return false;
    matched_.resize(4 * 2 * k);
    auto in_ring = [&](TetId x) {
      return std::find(scratch_old_.begin(), scratch_old_.end(), x) != scratch_old_.end();
    };
    for (std::size_t r = 0; r < k; ++r) {
      const TetId current = scratch_old_[r];
      const Tet& tet = mesh_.tets[current];
      const int ia = tet.index_of(a);
      const int ib = tet.index_of(b);
      if (ia < 0 || ib < 0 || scratch_source_[2 * r] != std::pair<TetId, int>{current, ia} ||
          scratch_source_[2 * r + 1] != std::pair<TetId, int>{current, ib} ||
          tet.index_of(scratch_new_[2 * r][static_cast<std::size_t>(ia)]) >= 0) {
        return false;
      }
      const std::size_t copy_a = 4 * (2 * r);
      const std::size_t copy_b = 4 * (2 * r + 1);
      const FaceRef out_a = tet.neighbor[static_cast<std::size_t>(ia)];
      const FaceRef out_b = tet.neighbor[static_cast<std::size_t>(ib)];
      if (in_ring(ref_tet(out_a)) || in_ring(ref_tet(out_b))) return false;
      matched_[copy_a + static_cast<std::size_t>(ia)] = {out_a, false, true};
      matched_[copy_b + static_cast<std::size_t>(ib)] = {out_b, false, true};
      matched_[copy_a + static_cast<std::size_t>(ib)] = {
          static_cast<FaceRef>(copy_b) + static_cast<FaceRef>(ia), true, true};
      matched_[copy_b + static_cast<std::size_t>(ia)] = {
          static_cast<FaceRef>(copy_a) + static_cast<FaceRef>(ib), true, true};
      const std::size_t next = r + 1 == k ? 0 : r + 1;
      const std::size_t previous = r == 0 ? k - 1 : r - 1;
      for (int c = 0; c < 4; ++c) {
        if (c == ia || c == ib) continue;
        const FaceRef across = tet.neighbor[static_cast<std::size_t>(c)];
        std::size_t q = next;
        if (ref_tet(across) != scratch_old_[next]) {
          if (ref_tet(across) != scratch_old_[previous]) return false;
          q = previous;
        }
        const int g = ref_face(across);
        const Tet& neighbour = mesh_.tets[scratch_old_[q]];
        if (neighbour.neighbor[static_cast<std::size_t>(g)] != face_ref(current, c) ||
            neighbour.vertex[static_cast<std::size_t>(g)] == a ||
            neighbour.vertex[static_cast<std::size_t>(g)] == b) {
          return false;
        }
        matched_[copy_a + static_cast<std::size_t>(c)] = {
            static_cast<FaceRef>(4 * (2 * q) + static_cast<std::size_t>(g)), true, true};
        matched_[copy_b + static_cast<std::size_t>(c)] = {
            static_cast<FaceRef>(4 * (2 * q + 1) + static_cast<std::size_t>(g)), true, true};
      }
    }
    return true;
  }

  // replace()'s direct path: fills matched_ from the sources alone, without matching keys, when
  // every new tetrahedron is a copy of an old one (push_replaced). New tetrahedron j is old s with
  // position a replaced by v. Its face a is s's face a, on the region's boundary. Its face g != a
  // is shared with the copy of s that replaced position g, if there is one (at that copy's face
  // a); otherwise with the copy of s's neighbour s2 across face g that replaced the same vertex
  // s[a] (at its face across from s), or, when s2 has no such copy and its vertex across from s
  // is v itself (S44: the two old tetrahedra that only give their apex), with s2's own face
  // opposite s[a], on the boundary. On a mesh whose references are mutual (the engine's writes
  // keep them so, with any kernel) these are the right faces; what is checked is what a broken
  // neighbourhood could still get wrong: v is not already a vertex of s, links between new
  // tetrahedra are mutual, and the boundary faces taken over are all of the region's, each once.
  // Anything else is left to the generic matching, which decides as before.
  bool link_from_sources() {
    const std::size_t n = scratch_new_.size();
    const std::size_t old_count = scratch_old_.size();
    copy_of_.assign(4 * old_count, -1);
    source_old_.resize(n);
    for (std::size_t j = 0; j < n; ++j) {
      const auto [source, position] = scratch_source_[j];
      const int r = source == kNoTet ? -1 : old_index(source);
      if (r < 0) return false;
      int& copy = copy_of_[4 * static_cast<std::size_t>(r) + static_cast<std::size_t>(position)];
      if (copy >= 0 ||
          mesh_.tets[source].index_of(scratch_new_[j][static_cast<std::size_t>(position)]) >= 0) {
        return false;
      }
      copy = static_cast<int>(j);
      source_old_[j] = r;
    }
    matched_.resize(4 * n);
    boundary_used_.assign(4 * old_count, 0);
    // New face `self` takes over the outside of old r's face f.
    auto on_boundary = [&](std::size_t self, std::size_t r, int face) {
      const FaceRef out = mesh_.tets[scratch_old_[r]].neighbor[static_cast<std::size_t>(face)];
      char& used = boundary_used_[4 * r + static_cast<std::size_t>(face)];
      if (used != 0 || old_index(ref_tet(out)) >= 0) return false;
      used = 1;
      matched_[self] = {out, false, true};
      return true;
    };
    for (std::size_t j = 0; j < n; ++j) {
      const int a = scratch_source_[j].second;
      const auto r = static_cast<std::size_t>(source_old_[j]);
      const Tet& st = mesh_.tets[scratch_old_[r]];
      for (int g = 0; g < 4; ++g) {
        const std::size_t self = 4 * j + static_cast<std::size_t>(g);
        if (g == a) {
          if (!on_boundary(self, r, a)) return false;
          continue;
        }
        if (const int k = copy_of_[4 * r + static_cast<std::size_t>(g)]; k >= 0) {
          matched_[self] = {static_cast<FaceRef>(4 * k + a), true, true};
          continue;
        }
        const FaceRef across = st.neighbor[static_cast<std::size_t>(g)];
        const int r2 = old_index(ref_tet(across));
        if (r2 < 0) return false;
        const Tet& second = mesh_.tets[ref_tet(across)];
        const int a2 = second.index_of(st.vertex[static_cast<std::size_t>(a)]);
        if (a2 < 0) return false;
        const int k = copy_of_[4 * static_cast<std::size_t>(r2) + static_cast<std::size_t>(a2)];
        if (k >= 0) {
          matched_[self] = {static_cast<FaceRef>(4 * k + ref_face(across)), true, true};
          continue;
        }
        if (second.vertex[static_cast<std::size_t>(ref_face(across))] !=
                scratch_new_[j][static_cast<std::size_t>(a)] ||
            !on_boundary(self, static_cast<std::size_t>(r2), a2)) {
          return false;
        }
      }
    }
    for (std::size_t self = 0; self < 4 * n; ++self) {
      const FaceMatch m = matched_[self];
      if (m.is_new && (!matched_[m.ref].is_new || matched_[m.ref].ref != self)) return false;
    }
    for (std::size_t r = 0; r < old_count; ++r) {
      for (int f = 0; f < 4; ++f) {
        const FaceRef out = mesh_.tets[scratch_old_[r]].neighbor[static_cast<std::size_t>(f)];
        if (boundary_used_[4 * r + static_cast<std::size_t>(f)] == 0 &&
            old_index(ref_tet(out)) < 0) {
          return false;  // a boundary face nobody took over
        }
      }
    }
    return true;
  }

  // A face's vertex set as two integers (sorted ids): cheap to compare.
  struct FaceKey {
    std::uint64_t high;
    std::uint32_t low;
    bool operator==(const FaceKey&) const = default;
  };
  struct OpenFace {
    FaceKey key;
    FaceRef ref;  // an existing tetrahedron's face, or (is_new) 4 * new index + face
    bool is_new;
  };
  struct FaceMatch {
    FaceRef ref;
    bool is_new;
    bool set;
  };

  static FaceKey face_key(const Quad& v, int f) {
    const auto& fv = kFaceVertex[static_cast<std::size_t>(f)];
    VertexId a = v[static_cast<std::size_t>(fv[0])];
    VertexId b = v[static_cast<std::size_t>(fv[1])];
    VertexId c = v[static_cast<std::size_t>(fv[2])];
    if (a > b) std::swap(a, b);
    if (b > c) std::swap(b, c);
    if (a > b) std::swap(a, b);
    return {(static_cast<std::uint64_t>(a) << 32) | b, c};
  }

  SharedMesh& mesh_;
  Sync& sync_;
  SlotAllocator& slots_;
  bool recycle_;  // dead slots are retired for reuse (walk mode)
  bool dag_;      // the old tetrahedra get the new ones as DAG children (the store keeps them)
  std::vector<TetId> scratch_old_;
  std::vector<Quad> scratch_new_;
  std::vector<int> scratch_parent_;  // index in scratch_old_ of the only DAG parent, or -1: all
  std::vector<std::pair<TetId, int>> scratch_source_;  // (old tetrahedron, replaced position)
  std::vector<TetId> scratch_created_;
  std::array<TetId, 4> known_created_{};  // replace_known's and commit_fixed's new ids
  std::size_t known_count_ = 0;
  bool created_known_ = false;  // created() is known_created_, else scratch_created_
  std::vector<OpenFace> open_faces_;
  std::vector<FaceMatch> matched_;
  std::vector<FaceRef> claimed_;
  // link_from_sources's scratch: copy_of_[4 r + position] is the new tetrahedron made from old r
  // by replacing `position` (-1: none); source_old_[j] is new j's source as an index of
  // scratch_old_; boundary_used_[4 r + f]: old r's face f was taken over.
  std::vector<int> copy_of_;
  std::vector<int> source_old_;
  std::vector<char> boundary_used_;
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
  std::vector<Tet*> fresh_records_;  // replace_cavity's: the new tetrahedra's records
  CavityEdges edges_;                // replace_cavity's scratch
};

}  // namespace dtlab::engine
