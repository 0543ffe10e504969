#pragma once
// Replacing a set of tetrahedra by new ones that fill the same region: every split and flip of
// the engine ends in a replacement (the contract: tet_replacement.hpp). This layer is the general
// one: the caller names the old tetrahedra (old_tets(), all locked by the caller when there are
// locks) and the new ones, each an old one with one vertex replaced (push_replaced) or given
// whole (push_new); replace() matches every face before it writes anything (Impossible: the new
// ones do not close up, nothing written; GaveUp: a lock was refused, nothing written), then
// commits them through the store's one write path (mesh/topology_commit.hpp). created() lists
// the new ids. replace_edge_ring() is k->2k's direct linking, with replace() as its fallback.
#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <utility>
#include <vector>

#include "mesh/face_key.hpp"
#include "mesh/shared_mesh.hpp"
#include "mesh/slot_allocator.hpp"
#include "mesh/tet_store.hpp"
#include "mesh/topology_commit.hpp"

namespace dtlab::engine {

template <class Sync>
class GenericReplacement {
 public:
  enum class Replaced { Done, Impossible, GaveUp };

  // keep_dag: the old tetrahedra get the new ones as DAG children (not when slots are reused).
  GenericReplacement(SharedMesh& mesh, Sync& sync, SlotAllocator& slots, bool keep_dag)
      : mesh_(mesh), commit_(mesh, sync, slots, !keep_dag) {}

  // Starts a replacement of `old` (or of what the caller then puts in old_tets()).
  void begin(std::initializer_list<TetId> old) {
    scratch_old_.assign(old.begin(), old.end());
    scratch_new_.clear();
    scratch_parent_.clear();
    scratch_source_.clear();
  }
  std::vector<TetId>& old_tets() { return scratch_old_; }
  // The new ids of the last replacement that wrote (replace_known's and commit_fixed's in a fixed
  // array: a vector's assign or resize of 2 to 4 ids was a call and a memmove per flip).
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
                                        [&](const FaceEntry& of) { return of.key == key; });
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

 protected:
  // A lock can still be refused after these writes (a split or flip is followed by the rest of
  // the legalization): every tetrahedron written below is locked first (the outside neighbours
  // get new back references; the old ones are locked already), and the undo log sees each before
  // its first write.
  Replaced commit_replacement() {
    const auto outside = [&](auto&& visit) {
      for (const FaceMatch& m : matched_) {
        if (!m.is_new) visit(ref_tet(m.ref));
      }
    };
    if (!commit_.lock_and_log(outside, std::span<const TetId>(scratch_old_))) {
      return Replaced::GaveUp;
    }
    created_known_ = false;
    scratch_created_.clear();
    for (const Quad& q : scratch_new_) {
      const TetId id = commit_.allocate();
      commit_.record(id).vertex = q;
      commit_.created(id);  // locked by this thread before anyone can reach it
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
          commit_.publish(m.ref, face_ref(scratch_created_[j], f));
        }
      }
    }
    // History: children first (release), then the old tetrahedra die, then the new ones live.
    // A recycling engine keeps no history: the old slots are reused after this insertion.
    for (std::size_t r = 0; r < scratch_old_.size(); ++r) {
      commit_.kill(scratch_old_[r], [&](TetStore::Children& children) {
        std::size_t slot = 0;
        for (std::size_t j = 0; j < scratch_created_.size(); ++j) {
          if (scratch_parent_[j] == -1 || scratch_parent_[j] == static_cast<int>(r)) {
            children[slot++].store(scratch_created_[j], std::memory_order_release);
          }
        }
      });
    }
    for (const TetId id : scratch_created_) commit_.born(id);
    return Replaced::Done;
  }

  SharedMesh& mesh_;
  TopologyCommit<Sync> commit_;           // every write of the store (mesh/topology_commit.hpp)
  std::array<TetId, 4> known_created_{};  // a direct replacement's new ids (known_replacement.hpp)
  std::size_t known_count_ = 0;
  bool created_known_ = false;  // created() is known_created_, else scratch_created_
  std::vector<TetId> scratch_old_;
  std::vector<TetId> scratch_created_;

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

  // What a new face is glued to: an existing tetrahedron's face, or (is_new) 4 * new index + face.
  struct FaceMatch {
    FaceRef ref;
    bool is_new;
    bool set;
  };

  std::vector<Quad> scratch_new_;
  std::vector<int> scratch_parent_;  // index in scratch_old_ of the only DAG parent, or -1: all
  std::vector<std::pair<TetId, int>> scratch_source_;  // (old tetrahedron, replaced position)
  std::vector<FaceEntry> open_faces_;                  // ref: as FaceMatch::ref
  std::vector<FaceMatch> matched_;
  std::vector<FaceRef> claimed_;
  // link_from_sources's scratch: copy_of_[4 r + position] is the new tetrahedron made from old r
  // by replacing `position` (-1: none); source_old_[j] is new j's source as an index of
  // scratch_old_; boundary_used_[4 r + f]: old r's face f was taken over.
  std::vector<int> copy_of_;
  std::vector<int> source_old_;
  std::vector<char> boundary_used_;
};

}  // namespace dtlab::engine
