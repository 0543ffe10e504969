#pragma once
// dtlab repair: the Delaunay tetrahedralization of a point set from any tetrahedralization of it
// (or any list of tetrahedra on it), by star splaying with exact predicates (docs/design.md).
#include <vector>

#include "dtlab/engine/triangulate.hpp"

namespace dtlab::engine {

// Every vertex id must be below points.size() (the readers check it). Throws TriangulationError
// when the points have a NaN or infinite coordinate or span less than 3D. Duplicate points are
// named by their lowest index, as in triangulate().
std::vector<Tetrahedron> repair(const std::vector<Point3>& points,
                                const std::vector<Tetrahedron>& tets, SplayStats& stats);

}  // namespace dtlab::engine
