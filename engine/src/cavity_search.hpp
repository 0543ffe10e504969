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
// can contradict itself, every new tetrahedron is (one orientation each, about 5% of a run): a
// cavity that is no star around p is NotStar, and the caller inserts that point by flips instead.
//
// Locks: every tetrahedron is locked before it is tested (the cavity's are then replaced, the
// boundary's outside neighbours get new references), and nothing is written before the search
// and the checks end, so a refused lock gives the insertion up with nothing to undo.
#include <cstdint>
#include <span>
#include <vector>

#include "cavity_face.hpp"
#include "dtlab/engine/tet_mesh.hpp"
#include "epoch_table.hpp"
#include "mesh_geometry.hpp"
#include "shared_mesh.hpp"

namespace dtlab::engine {

template <class K, class Sync>
class CavitySearch {
 public:
  enum class Grown { Done, GaveUp, NotStar };

  // verify_star: check that every new tetrahedron is positive (an inexact kernel).
  CavitySearch(const SharedMesh& mesh, MeshGeometry<K>& geometry, Sync& sync, bool verify_star)
      : mesh_(mesh), geometry_(geometry), sync_(sync), verify_star_(verify_star) {}

  // The cavity of p from live tetrahedron t, which contains p and is locked (when there are
  // locks). Done: cavity() and boundary() hold it, every tetrahedron in either locked. GaveUp: a
  // lock was refused. NotStar: t is not in conflict, or a new tetrahedron would not be positive
  // (checked with verify_star only).
  Grown grow(TetId t, VertexId p) {
    in_cavity_.clear();
    cavity_.clear();
    boundary_size_ = 0;
    if (!geometry_.in_conflict(mesh_.tets[t], p)) return Grown::NotStar;
    in_cavity_.insert(t, true);
    enter(t);
    for (std::size_t i = 0; i < cavity_.size(); ++i) {
      const TetId s = cavity_[i];
      const Tet& tet = mesh_.tets[s];
      for (int f = 0; f < 4; ++f) {
        const FaceRef out = tet.neighbor[static_cast<std::size_t>(f)];
        const TetId n = ref_tet(out);
        bool inside = false;
        if (const bool* seen = in_cavity_.find(n)) {
          inside = *seen;
        } else {
          if (!sync_.acquire(n)) return Grown::GaveUp;
          inside = geometry_.in_conflict(mesh_.tets[n], p);
          in_cavity_.insert(n, inside);
          if (inside) enter(n);
        }
        if (!inside) add_boundary({s, f, out});
      }
    }
    for (const CavityFace& b : boundary()) {
      if (verify_star_ && geometry_.orient_replaced(mesh_.tets[b.inside], b.face, p) <= 0)
        return Grown::NotStar;
    }
    return Grown::Done;
  }

  [[nodiscard]] const std::vector<TetId>& cavity() const { return cavity_; }
  // Hands the cavity to `other` (the replacement's list of old tetrahedra) by a swap of the
  // two vectors: both keep their memory, nothing is copied.
  void move_cavity_to(std::vector<TetId>& other) { cavity_.swap(other); }
  [[nodiscard]] std::span<const CavityFace> boundary() const {
    return {boundary_.data(), boundary_size_};
  }

 private:
  // t joins the cavity; its neighbours' records are fetched now, to be tested when t's turn
  // comes (the search's time goes mostly to first reads of the neighbours beyond the cavity).
  // The boundary grows by a store into memory kept from earlier insertions; only a larger cavity
  // than any before grows the vector. (push_back was a call per face, not inlined, in the
  // optimistic methods' build: about 3 % of their samples at 1M points.)
  void add_boundary(const CavityFace& face) {
    if (boundary_size_ == boundary_.size()) [[unlikely]] {
      boundary_.resize(2 * boundary_size_ + 64);
    }
    boundary_[boundary_size_++] = face;
  }

  void enter(TetId t) {
    cavity_.push_back(t);
    const Tet& tet = mesh_.tets[t];
    for (const FaceRef r : tet.neighbor) mesh_.tets.prefetch(ref_tet(r));
  }

  const SharedMesh& mesh_;
  MeshGeometry<K>& geometry_;
  Sync& sync_;
  bool verify_star_;
  EpochTable<TetId, bool> in_cavity_;  // the tetrahedra tested: in conflict or not
  std::vector<TetId> cavity_;
  std::vector<CavityFace> boundary_;  // the first boundary_size_ entries
  std::size_t boundary_size_ = 0;
};

}  // namespace dtlab::engine
