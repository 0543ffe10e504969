#pragma once
// CGAL's Delaunay_triangulation_3 (exact predicates, inexact constructions; range insertion with
// its spatial sort) timed on dtlab's points: the peer of the `compare` study. Only
// cgal_engine.cpp includes CGAL.
#include <cstdint>
#include <vector>

#include "dtlab/predicates/point.hpp"

namespace dtlab::experiments {

struct CgalRun {
  double seconds = 0.0;  // converting the points and building the triangulation
  std::uint64_t finite_cells = 0;
};

// threads == 1: the sequential triangulation; more: CGAL's parallel mode (TBB, a 50^3 lock grid
// over the points' box, as CGAL's documentation builds it). Throws std::runtime_error when this
// build has no TBB and threads > 1.
CgalRun run_cgal(const std::vector<predicates::Point3>& points, int threads);
bool cgal_parallel_available();

}  // namespace dtlab::experiments
