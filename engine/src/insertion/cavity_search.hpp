#pragma once
// The walk mode's alternative to the flips (--insertion cavity): Bowyer-Watson insertion (Bowyer
// 1981, Watson 1981). The tetrahedra whose perturbed circumsphere holds p strictly (the conflict
// region, or cavity) are found by a search over faces from the tetrahedron that contains p; they
// are replaced by p joined to the cavity's boundary faces (TetReplacement::replace_cavity).
//
// Why the result is the flips' result. With exact predicates and a perturbation of the lifting
// map the conflict test is "p's lifted point lies below the hyperplane of t's lifted vertices"
// for one consistent set of lifted heights, so the region is connected, contains the tetrahedron
// that contains p, and p joined to its boundary is the perturbed Delaunay tetrahedralization
// with p (docs/design.md, "Cavity insertion"). The same argument shows that p is never coplanar
// with a boundary face: on the vertical flat over that face's plane, the lifted hyperplanes of
// the two tetrahedra that share the face meet in the same 2-flat, so p is below both or neither
// (a face with the vertex at infinity: the same, on the plane through its edge and the interior
// point O). Not flat, the new tetrahedron is positive: it fills part of the cavity, on the side of
// the face where the cavity's tetrahedron lies.
// So with the adaptive, filtered and exact kernels nothing is checked; with the fast kernel, which
// can contradict itself, every new tetrahedron is (one orientation each): a
// cavity that is no star around p is NotStar, and the caller inserts that point by flips instead.
//
// Locks: every tetrahedron is locked before it is tested (the cavity's are then replaced, the
// boundary's outside neighbours get new references), and nothing is written before the search
// and the checks end, so a refused lock gives the insertion up with nothing to undo. A policy
// that confines its thread's reads (sync.hpp; the partitioned method's) is asked only for the
// cavity's tetrahedra: the outside neighbours' back references are atomic stores into
// tetrahedra no other thread writes, across faces no other thread crosses.
#include <cstdint>
#include <span>
#include <vector>

#include "insertion/cavity_face.hpp"
#include "insertion/epoch_table.hpp"
#include "insertion/sync.hpp"
#include "mesh/mesh_geometry.hpp"
#include "mesh/shared_mesh.hpp"
#include "mesh/tet_store.hpp"

namespace dtlab::engine {

template <class K, class Sync>
class CavitySearch {
 public:
  enum class Grown { Done, GaveUp, NotStar };

  // verify_star: check that every new tetrahedron is positive (an inexact kernel).
  CavitySearch(const SharedMesh& mesh, MeshGeometry<K>& geometry, Sync& sync, bool verify_star)
      : mesh_(mesh), geometry_(geometry), sync_(sync), verify_star_(verify_star) {}

  // The cavity of p from live tetrahedron t, which contains p and is locked (when there are
  // locks). Done: cavity() and boundary() hold it, every tetrahedron in either locked (a confined
  // policy's: the cavity's only). GaveUp: a
  // lock was refused. NotStar: t is not in conflict, or a new tetrahedron would not be positive
  // (checked with verify_star only).
  // Out of line: inlined into the callers' loops, it ran more instructions.
  [[gnu::noinline]] Grown grow(TetId t, VertexId p) {
    in_cavity_.clear();
    cavity_size_ = 0;
    boundary_size_ = 0;
    if (!geometry_.in_conflict(mesh_.tets[t], p)) return Grown::NotStar;
    in_cavity_.insert(t, true);
    enter(t, 0);
    const Tet& first = mesh_.tets[t];
    for (int f = 0; f < 4; ++f) {
      if (!look_across(t, first, f, p)) return Grown::GaveUp;
    }
    // A later tetrahedron was entered across one of its faces from one already in the cavity:
    // that face is inner, and only its other three are looked across. (Looked up, the neighbour
    // there was found in the table: a fifth to a quarter of all look-ups, each a branch the
    // predictor could not tell from the untested neighbours'.)
    for (std::size_t i = 1; i < cavity_size_; ++i) {
      const TetId s = cavity_[i];
      const Tet& tet = mesh_.tets[s];
      const int entered = entered_by_[i];
      for (int k = 1; k < 4; ++k) {
        if (!look_across(s, tet, (entered + k) & 3, p)) return Grown::GaveUp;
      }
    }
    for (const CavityFace& b : boundary()) {
      if (verify_star_ && geometry_.orient_replaced(mesh_.tets[b.inside], b.face, p) <= 0)
        return Grown::NotStar;
    }
    return Grown::Done;
  }

  // After Done only.
  [[nodiscard]] std::span<const TetId> cavity() const { return {cavity_.data(), cavity_size_}; }
  // The boundary's faces, in the order found (after Done only; the replacement reads both in
  // place).
  [[nodiscard]] std::span<const CavityFace> boundary() const {
    return {boundary_.data(), boundary_size_};
  }

 private:
  // t joins the cavity; its neighbours' records are fetched now, to be tested when t's turn
  // comes (the search's time goes mostly to first reads of the neighbours beyond the cavity).
  // The boundary and the cavity grow by a store (push_back was a call per entry, not inlined).
  // Both vectors are kept from earlier
  // insertions (the replacement reads the cavity in place), so only a larger cavity or boundary
  // than any before grows them.
  void add_boundary(const CavityFace& face) {
    if (boundary_size_ == boundary_.size()) [[unlikely]] {
      boundary_.resize(2 * boundary_size_ + 64);
    }
    boundary_[boundary_size_++] = face;
  }

  // Cavity tetrahedron s's (record `tet`) neighbour across face f: tested once (the table keeps
  // the answer), entered when in conflict, else f is a boundary face. False: a lock was refused.
  bool look_across(TetId s, const Tet& tet, int f, VertexId p) {
    const FaceRef out = tet.neighbor[static_cast<std::size_t>(f)];
    const TetId n = ref_tet(out);
    // A refused lock leaves n's entry in the table: the search ends there, and the next
    // one starts from an empty table.
    auto [in_conflict, untested] = in_cavity_.find_or_insert(n, false);
    if (untested) {
      if constexpr (kConfinedReads<Sync>) {
        // A confined thread may read n (across a face of its own tetrahedron) and asks only
        // for the cavity's: an outside tetrahedron just gets a back reference, written
        // atomically, which no other thread follows (the face has none of its vertices).
        const Tet& record = mesh_.tets[n];
        *in_conflict = geometry_.in_conflict(record, p);
        if (*in_conflict) {
          // n shares the face with s, which this thread holds: its apex decides.
          if (!sync_.acquire_across(n, record, ref_face(out))) return false;
          enter(n, ref_face(out));
        }
      } else {
        if (!sync_.acquire(n)) return false;
        *in_conflict = geometry_.in_conflict(mesh_.tets[n], p);
        if (*in_conflict) enter(n, ref_face(out));
      }
    }
    if (!*in_conflict) add_boundary({s, f, out});
    return true;
  }

  // t joins the cavity, entered across its face `entered_by` (the search's first: any).
  void enter(TetId t, int entered_by) {
    if (cavity_size_ == cavity_.size()) [[unlikely]] {
      cavity_.resize(2 * cavity_size_ + 64);
      entered_by_.resize(cavity_.size());
    }
    entered_by_[cavity_size_] = entered_by;
    cavity_[cavity_size_++] = t;
    const Tet& tet = mesh_.tets[t];
    for (const FaceRef r : tet.neighbor) mesh_.tets.prefetch(ref_tet(r));
  }

  const SharedMesh& mesh_;
  MeshGeometry<K>& geometry_;
  Sync& sync_;
  bool verify_star_;
  EpochTable<TetId, bool> in_cavity_;  // the tetrahedra tested: in conflict or not
  std::vector<TetId> cavity_;          // the first cavity_size_ entries
  std::vector<int> entered_by_;        // cavity_[i] was entered across its face entered_by_[i]
  std::size_t cavity_size_ = 0;
  std::vector<CavityFace> boundary_;  // the first boundary_size_ entries
  std::size_t boundary_size_ = 0;
};

}  // namespace dtlab::engine
