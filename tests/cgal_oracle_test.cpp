// CGAL's Delaunay_triangulation_3 as oracle. General position: identical sets of tetrahedra.
// Degenerate inputs: dtlab validates, and the number of tetrahedra and the exact total volume
// match CGAL's (both use a lexicographic symbolic perturbation, so the sets are compared too and
// the agreement is printed).
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_rational.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "dtlab/engine/triangulate.hpp"
#include "dtlab/engine/validator.hpp"
#include "dtlab/generators/generators.hpp"

namespace dtlab::test {
namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, Epick>;
using Tds = CGAL::Triangulation_data_structure_3<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_3<Epick, Tds>;
// Plain exact rationals (not the lazy kernel, whose expression DAG grows with every addition).
using ExactKernel = CGAL::Simple_cartesian<CGAL::Exact_rational>;
using predicates::Point3;

std::vector<io::Tetrahedron> sorted_set(std::vector<io::Tetrahedron> tets) {
  for (auto& t : tets) std::sort(t.begin(), t.end());
  std::sort(tets.begin(), tets.end());
  return tets;
}

std::vector<io::Tetrahedron> cgal_delaunay(const std::vector<Point3>& pts) {
  std::vector<std::pair<Epick::Point_3, std::uint32_t>> input;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    input.push_back({{pts[i].x, pts[i].y, pts[i].z}, static_cast<std::uint32_t>(i)});
  }
  Delaunay dt(input.begin(), input.end());
  std::vector<io::Tetrahedron> out;
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
    out.push_back(
        {c->vertex(0)->info(), c->vertex(1)->info(), c->vertex(2)->info(), c->vertex(3)->info()});
  }
  return out;
}

ExactKernel::FT total_volume(const std::vector<Point3>& pts,
                             const std::vector<io::Tetrahedron>& tets) {
  ExactKernel::FT sum = 0;
  for (const auto& t : tets) {
    auto p = [&](std::uint32_t i) { return ExactKernel::Point_3(pts[i].x, pts[i].y, pts[i].z); };
    sum += CGAL::volume(p(t[0]), p(t[1]), p(t[2]), p(t[3]));
  }
  return sum;
}

TEST(CgalOracle, GeneralPositionIdenticalTetrahedra) {
  for (const std::string family : {"uniform", "normal", "cluster"}) {
    for (const std::uint64_t seed : {1u, 2u, 3u}) {
      const auto pts = generators::generate(family, 3000, seed).points;
      const auto ours = engine::triangulate(pts, {}).tetrahedra;
      EXPECT_EQ(sorted_set(ours), sorted_set(cgal_delaunay(pts))) << family << " seed " << seed;
    }
  }
}

TEST(CgalOracle, DegenerateInputsValidateAndMatchCountAndVolume) {
  for (const std::string family :
       {"grid", "sphere", "cospherical", "planes", "duplicates", "near-duplicates", "lattice"}) {
    const auto pts = generators::generate(family, 1500, 5).points;
    const auto ours = engine::triangulate(pts, {}).tetrahedra;
    const auto report = engine::validate(pts, ours);
    EXPECT_TRUE(report.valid()) << family << ": " << report.json();
    const auto theirs = cgal_delaunay(pts);
    EXPECT_EQ(ours.size(), theirs.size()) << family;
    EXPECT_TRUE(total_volume(pts, ours) == total_volume(pts, theirs)) << family;
    const bool same = sorted_set(ours) == sorted_set(theirs);
    std::printf("%-16s %zu tetrahedra, same set as CGAL: %s\n", family.c_str(), ours.size(),
                same ? "yes" : "no");
  }
}

}  // namespace
}  // namespace dtlab::test
