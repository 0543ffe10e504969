#pragma once
// The engine's orientation and insphere tests on the shared mesh, with the vertex at infinity
// (an orientation with it is minus the orientation with the interior point O: see
// insertion/inserter.hpp), counted in predicate_calls. One object per inserting thread.
#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>

#include "mesh/conflict.hpp"
#include "mesh/shared_mesh.hpp"
#include "mesh/tet_store.hpp"

namespace dtlab::engine {

template <class K>
class MeshGeometry {
 public:
  explicit MeshGeometry(const SharedMesh& mesh) : mesh_(mesh) {}

  // Only finite vertices are looked up: the infinite vertex never reaches a point lookup.
  [[nodiscard]] const Point3& point(VertexId v) const { return mesh_.points[v]; }

  int orient(const Quad& q) {
    ++predicate_calls_;
    // kInfiniteVertex is the largest id (as in in_conflict): no branch per vertex.
    if (std::max(std::max(q[0], q[1]), std::max(q[2], q[3])) != kInfiniteVertex) [[likely]] {
      return K::orient3d(point(q[0]), point(q[1]), point(q[2]), point(q[3]));
    }
    int inf = 3;
    while (q[static_cast<std::size_t>(inf)] != kInfiniteVertex) --inf;
    // orient(q) = -orient(q with inf -> O); move O to the last slot (a swap: one more sign).
    Quad r = q;
    std::swap(r[static_cast<std::size_t>(inf)], r[3]);
    const int s = mesh_.origin_is_point
                      ? K::orient3d(point(r[0]), point(r[1]), point(r[2]), mesh_.origin)
                      : K::orient3d_centroid(point(r[0]), point(r[1]), point(r[2]), mesh_.first);
    return inf == 3 ? -s : s;
  }

  // Orientation of tetrahedron t with its vertex at position i replaced by v.
  int orient_replaced(const Tet& t, int i, VertexId v) {
    Quad q = t.vertex;
    q[static_cast<std::size_t>(i)] = v;
    return orient(q);
  }

  // Whether p lies strictly inside the (perturbed) circumsphere of t (conflict.hpp).
  bool in_conflict(const Tet& t, VertexId p) {
    ++predicate_calls_;
    return engine::in_conflict<K>(mesh_.points, t.vertex, p);
  }

  // p inside or on the boundary of t; `o` receives the four orientations.
  bool contains(TetId t, VertexId p, std::array<int, 4>& o) {
    const Tet& tet = mesh_.tets[t];
    for (int i = 0; i < 4; ++i) {
      o[static_cast<std::size_t>(i)] = orient_replaced(tet, i, p);
      if (o[static_cast<std::size_t>(i)] < 0) return false;
    }
    return true;
  }

  [[nodiscard]] std::uint64_t predicate_calls() const { return predicate_calls_; }

 private:
  const SharedMesh& mesh_;
  std::uint64_t predicate_calls_ = 0;
};

}  // namespace dtlab::engine
