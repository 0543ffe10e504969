#pragma once
// CGAL as the independent reference of the tests and the fuzz harnesses (target
// dtlab_cgal_reference, defined in the top-level CMakeLists.txt so that tests/, property_tests/
// and fuzz/ can all link it). No CGAL header here: only cgal_reference.cpp includes CGAL.
//
// Both functions take finite coordinates only and throw std::invalid_argument for a NaN or an
// infinite one (check all_finite first: such an input never reaches CGAL).
#include <vector>

#include "dtlab/io/mesh_writers.hpp"
#include "dtlab/predicates/point.hpp"

namespace dtlab::test {

using predicates::Point3;

// True when every coordinate is finite.
bool all_finite(const std::vector<Point3>& points);

// The affine dimension of the point set as CGAL's Triangulation_3 with exact predicates
// (Exact_predicates_inexact_constructions_kernel) reports it: -1 for no point, 0 when all points
// coincide, 1 collinear, 2 coplanar, 3 otherwise. A tetrahedralization exists iff it is 3.
int cgal_dimension(const std::vector<Point3>& points);

// The finite cells of CGAL's Delaunay_triangulation_3 (exact predicates; CGAL breaks cospherical
// ties by the same lexicographic symbolic perturbation as dtlab, so the result is the unique
// perturbed Delaunay tetrahedralization), as input indices: each set of duplicate points is named
// by its lowest input index, as dtlab names it. Empty when cgal_dimension(points) < 3. Vertex
// order within a tetrahedron is CGAL's (positively oriented); compare sorted sets.
std::vector<io::Tetrahedron> cgal_delaunay(const std::vector<Point3>& points);

}  // namespace dtlab::test
