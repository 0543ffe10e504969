#pragma once
// What all inserting threads share: the points, the tetrahedron store (mesh and DAG), the DAG
// roots and the interior point O. Written by one thread in start(), read-only afterwards except
// for the store, whose records follow the locking rules of docs/design.md.
#include <algorithm>
#include <atomic>
#include <utility>
#include <vector>

#include "dtlab/engine/triangulate.hpp"
#include "dtlab/predicates/kernels.hpp"
#include "mesh/tet_store.hpp"

namespace dtlab::engine {

struct SharedMesh {
  explicit SharedMesh(const std::vector<Point3>& input) : points(input) {}

  const std::vector<Point3>& points;
  mutable TetStore tets;  // mutable: take_finite_tetrahedra releases it
  std::vector<TetId> roots;
  predicates::Tetrahedron4 first{};  // O is the centroid of these four points...
  Point3 origin{0, 0, 0};            // ...or this point, strictly inside them, when
  bool origin_is_point = false;      // origin_is_point

  // Live finite tetrahedra whose vertices are all below `vertex_limit` (so not auxiliary), in
  // slot order. Each set of duplicate points is named by its lowest input index, whichever of
  // them was inserted, so that the output does not depend on the insertion order.
  std::vector<Tetrahedron> finite_tetrahedra(
      VertexId vertex_limit, const std::vector<std::pair<VertexId, VertexId>>& duplicates,
      int threads = 1) const {
    return collect(vertex_limit, duplicates, false, threads);
  }
  // The same, releasing the store's blocks as they are read: the output does not coexist with
  // the whole store (docs/performance.md, "Measured choices"). The store is unusable
  // afterwards; the last thing a run does.
  std::vector<Tetrahedron> take_finite_tetrahedra(
      VertexId vertex_limit, const std::vector<std::pair<VertexId, VertexId>>& duplicates,
      int threads = 1) {
    return collect(vertex_limit, duplicates, true, threads);
  }

 private:
  // The store's blocks are counted, then copied, by `threads` threads (shared_mesh.cpp).
  std::vector<Tetrahedron> collect(VertexId vertex_limit,
                                   const std::vector<std::pair<VertexId, VertexId>>& duplicates,
                                   bool release, int threads) const;
};

// Neighbour references are read by walking threads that hold no lock, so a published record's
// are written with release (after the tetrahedron they name is complete) and read with acquire
// (plain moves on x86). A new record, unreachable until the outside's references to it are
// stored, is written by plain stores (tet_replacement.hpp).
inline FaceRef load_neighbor(const Tet& tet, int f) {
  return std::atomic_ref<FaceRef>(const_cast<FaceRef&>(tet.neighbor[static_cast<std::size_t>(f)]))
      .load(std::memory_order_acquire);
}
inline void store_neighbor(Tet& tet, int f, FaceRef r) {
  std::atomic_ref<FaceRef>(tet.neighbor[static_cast<std::size_t>(f)])
      .store(r, std::memory_order_release);
}

}  // namespace dtlab::engine
