#pragma once
// The engine's entry point: the Delaunay tetrahedralization of a point set by randomized
// incremental insertion (Kohout and Kolingerova 2003), with the kernel, method, location and
// insertion that the options choose (docs/design.md).
#include <stdexcept>
#include <vector>

#include "dtlab/engine/options.hpp"
#include "dtlab/engine/stats.hpp"
#include "dtlab/engine/tetrahedron.hpp"
#include "dtlab/predicates/point.hpp"

namespace dtlab::engine {

using predicates::Point3;

struct Triangulation {
  std::vector<Tetrahedron> tetrahedra;  // finite, positively oriented, input point ids
  TriangulationStats stats;
  std::vector<Point3> points;  // the input, handed back by the overload that takes it by move
};

// The input has no tetrahedralization (fewer than 4 distinct points, all coplanar) or a NaN or
// infinite coordinate, or the run could not finish (too many points, a first tetrahedron the fast
// kernel sees as flat, the watchdog). The adaptive, filtered and exact kernels decide every finite
// double input exactly: no input is refused for its magnitudes.
class TriangulationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The run could not finish on an input that has a tetrahedralization: the watchdog stopped a
// parallel run, or the tetrahedron store reached its limit. Not a fault of the input.
class RunFailed : public TriangulationError {
 public:
  using TriangulationError::TriangulationError;
};

// A run stopped through options.monitor->cancel: no mesh.
class RunCancelled : public TriangulationError {
 public:
  RunCancelled() : TriangulationError("the run was cancelled") {}
};

Triangulation triangulate(const std::vector<Point3>& points, const TriangulateOptions& options);
// The same on points the caller gives up: the engine scales and reorders them in place instead of
// copying them (24 bytes a point less at the run's peak) and returns them unchanged in
// Triangulation::points. When it throws, `points` holds them as given (unless memory runs out
// while they are put back: the reordering is undone through a second array).
Triangulation triangulate(std::vector<Point3>&& points, const TriangulateOptions& options);

// The tetrahedra in a canonical form for comparing meshes, orientation kept: each one's ids in
// ascending order when that order is an even permutation of its own, else ascending with the last
// two swapped; then the list sorted. Two tetrahedra on the same four ids compare equal exactly when
// they have the same orientation, so an inverted tetrahedron makes two meshes differ.
std::vector<Tetrahedron> canonical_tetrahedra(std::vector<Tetrahedron> tets);

}  // namespace dtlab::engine
