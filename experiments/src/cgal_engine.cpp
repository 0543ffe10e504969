#include "dtlab/experiments/cgal_engine.hpp"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <chrono>
#include <stdexcept>
#ifdef DTLAB_HAS_CGAL_TBB
#include <tbb/global_control.h>
#endif

namespace dtlab::experiments {
namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;

template <class Concurrency>
using Tds = CGAL::Triangulation_data_structure_3<CGAL::Triangulation_vertex_base_3<Epick>,
                                                 CGAL::Delaunay_triangulation_cell_base_3<Epick>,
                                                 Concurrency>;

}  // namespace

bool cgal_parallel_available() {
#ifdef DTLAB_HAS_CGAL_TBB
  return true;
#else
  return false;
#endif
}

CgalRun run_cgal(const std::vector<predicates::Point3>& points, int threads) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<Epick::Point_3> cgal_points;
  cgal_points.reserve(points.size());
  for (const auto& p : points) cgal_points.emplace_back(p.x, p.y, p.z);
  CgalRun run;
  if (threads <= 1) {
    const CGAL::Delaunay_triangulation_3<Epick, Tds<CGAL::Sequential_tag>> dt(cgal_points.begin(),
                                                                              cgal_points.end());
    run.finite_cells = dt.number_of_finite_cells();
  } else {
#ifdef DTLAB_HAS_CGAL_TBB
    using Dt = CGAL::Delaunay_triangulation_3<Epick, Tds<CGAL::Parallel_tag>>;
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(threads));
    CGAL::Bbox_3 box;
    for (const auto& p : cgal_points) box += p.bbox();
    typename Dt::Lock_data_structure locking(box, 50);
    const Dt dt(cgal_points.begin(), cgal_points.end(), &locking);
    run.finite_cells = dt.number_of_finite_cells();
#else
    throw std::runtime_error("this build has no TBB: CGAL's parallel mode is not available");
#endif
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

}  // namespace dtlab::experiments
