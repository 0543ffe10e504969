// CGAL's Delaunay_triangulation_3 on dtlab's points, each vertex carrying its input id: with
// Epick (exact predicates) and with Simple_cartesian<double> (every predicate in plain doubles).
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/version.h>

#include <cstdint>
#include <utility>

#include "peer_tools.hpp"

namespace dtlab::experiments {
namespace {

template <class Kernel>
PeerMesh triangulate_with(const std::vector<predicates::Point3>& points) {
  using Vb = CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, Kernel>;
  using Cb = CGAL::Delaunay_triangulation_cell_base_3<Kernel>;
  using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb>;
  using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Tds>;
  std::vector<std::pair<typename Kernel::Point_3, std::uint32_t>> input;
  input.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    input.emplace_back(typename Kernel::Point_3(points[i].x, points[i].y, points[i].z),
                       static_cast<std::uint32_t>(i));
  }
  // A failed CGAL assertion throws (CGAL's default); uncaught, it would end the caller's program.
  try {
    const Delaunay dt(input.begin(), input.end());
    if (dt.dimension() < 3) {
      throw PeerRefused("CGAL built a triangulation of dimension " +
                        std::to_string(dt.dimension()) + ": no tetrahedra");
    }
    PeerMesh mesh;
    mesh.tetrahedra.reserve(dt.number_of_finite_cells());
    for (const auto cell : dt.finite_cell_handles()) {
      mesh.tetrahedra.push_back({cell->vertex(0)->info(), cell->vertex(1)->info(),
                                 cell->vertex(2)->info(), cell->vertex(3)->info()});
    }
    return mesh;
  } catch (const CGAL::Failure_exception& e) {
    throw PeerCrashed(std::string("CGAL: ") + e.what());
  }
}

}  // namespace

std::string cgal_version() {
  return "CGAL " CGAL_VERSION_STR;
}

PeerMesh run_cgal_peer(const std::vector<predicates::Point3>& points, bool exact_predicates) {
  if (exact_predicates) {
    return triangulate_with<CGAL::Exact_predicates_inexact_constructions_kernel>(points);
  }
  return triangulate_with<CGAL::Simple_cartesian<double>>(points);
}

}  // namespace dtlab::experiments
