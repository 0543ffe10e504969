#pragma once
// dtlab repair: the Delaunay tetrahedralization of a point set from any tetrahedralization of it
// (or any list of tetrahedra on it), by star splaying with exact predicates (docs/design.md).
#include <vector>

#include "dtlab/engine/triangulate.hpp"
#include "dtlab/engine/validator.hpp"

namespace dtlab::engine {

// Every vertex id must be below points.size() (the readers check it). Throws TriangulationError
// when the points have a NaN or infinite coordinate or span less than 3D. Duplicate points are
// named by their lowest index, as in triangulate(). `threads` build the stars (kAllThreads: one per
// hardware thread); the result and the counts are the same for every count. A list that is
// already a consistent tetrahedralization of distinct points is repaired locally, from its
// non-Delaunay faces (stats.local); any other list by splaying every vertex.
std::vector<Tetrahedron> repair(const std::vector<Point3>& points,
                                const std::vector<Tetrahedron>& tets, SplayStats& stats,
                                int threads = 1);

}  // namespace dtlab::engine
