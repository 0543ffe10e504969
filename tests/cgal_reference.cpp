// CGAL as the tests' and fuzz harnesses' reference (cgal_reference.hpp). CGAL's headers stay in
// this translation unit.
#include "cgal_reference.hpp"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_3.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>

namespace dtlab::test {
namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangulation = CGAL::Triangulation_3<Epick>;
using Delaunay = CGAL::Delaunay_triangulation_3<Epick>;

void require_finite(const std::vector<Point3>& points, const char* function) {
  if (!all_finite(points)) {
    throw std::invalid_argument(std::string(function) + ": a coordinate is NaN or infinite");
  }
}

// Exact coordinates as a map key. Finite doubles only, so < is a strict weak order; 0.0 and -0.0
// are one key, as they are one point for CGAL and for dtlab (Point3's ==).
using Key = std::tuple<double, double, double>;

}  // namespace

bool all_finite(const std::vector<Point3>& points) {
  for (const Point3& p : points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
  }
  return true;
}

int cgal_dimension(const std::vector<Point3>& points) {
  require_finite(points, "cgal_dimension");
  // Inserting more points never lowers the dimension: stop as soon as it is 3.
  Triangulation t;
  Triangulation::Vertex_handle hint;
  for (const Point3& p : points) {
    hint = t.insert(Epick::Point_3(p.x, p.y, p.z), hint);
    if (t.dimension() == 3) break;
  }
  return t.dimension();
}

std::vector<io::Tetrahedron> cgal_delaunay(const std::vector<Point3>& points) {
  require_finite(points, "cgal_delaunay");
  // The lowest input index of every distinct point: CGAL keeps one vertex per set of duplicates,
  // so its vertices are mapped back through their exact coordinates (no vertex info needed).
  std::map<Key, std::uint32_t> lowest;
  std::vector<Epick::Point_3> input;
  input.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Point3& p = points[i];
    lowest.emplace(Key{p.x, p.y, p.z}, static_cast<std::uint32_t>(i));  // keeps the first (lowest)
    input.emplace_back(p.x, p.y, p.z);
  }
  const Delaunay dt(input.begin(), input.end());
  std::vector<io::Tetrahedron> out;
  if (dt.dimension() < 3) return out;
  out.reserve(dt.number_of_finite_cells());
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
    io::Tetrahedron t{};
    for (int k = 0; k < 4; ++k) {
      const Epick::Point_3& q = c->vertex(k)->point();
      t[static_cast<std::size_t>(k)] = lowest.at(Key{q.x(), q.y(), q.z()});
    }
    out.push_back(t);
  }
  return out;
}

}  // namespace dtlab::test
