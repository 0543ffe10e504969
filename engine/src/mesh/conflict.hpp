#pragma once
// The one conflict test of insertion, legalization and star splaying: whether point p lies
// strictly inside the (perturbed) circumsphere of the positively oriented tetrahedron q, the
// vertex at infinity included. A point conflicts with the infinite tetrahedron (a, b, c, inf) iff
// it lies beyond the plane abc, or on it and inside the circle abc (insertion/inserter.hpp).
#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

#include "dtlab/predicates/perturbation.hpp"
#include "dtlab/predicates/point.hpp"
#include "mesh/tet_store.hpp"

namespace dtlab::engine {

template <class K>
bool in_conflict(const std::vector<predicates::Point3>& points, const Quad& q, VertexId p) {
  // kInfiniteVertex is the largest id: the maximum says whether it is there, without a branch
  // per vertex.
  if (std::max(std::max(q[0], q[1]), std::max(q[2], q[3])) != kInfiniteVertex) [[likely]] {
    return predicates::insphere_perturbed<K>(points[q[0]], points[q[1]], points[q[2]], points[q[3]],
                                             points[p]) > 0;
  }
  int inf = 3;
  while (q[static_cast<std::size_t>(inf)] != kInfiniteVertex) --inf;
  // kFaceVertex lists the face with the opposite (infinite) vertex on its negative side;
  // reversed, the infinite vertex lies on the positive side, as the predicate expects.
  const auto& f = kFaceVertex[static_cast<std::size_t>(inf)];
  return predicates::infinite_insphere_perturbed<K>(
             points[q[static_cast<std::size_t>(f[0])]], points[q[static_cast<std::size_t>(f[2])]],
             points[q[static_cast<std::size_t>(f[1])]], points[p]) > 0;
}

}  // namespace dtlab::engine
