// The validator on several threads (engine/src/validator.cpp): the report, per-tetrahedron flags
// included, is the same for every thread count, on meshes large enough for every parallel step to
// split (valid ones, the fast kernel's broken ones, and ones broken on purpose), and its counters
// agree with the independent exact recount (tests/validator_recount.hpp). The broken-on-purpose
// meshes also check the volume from faces (exact_volume.hpp) at scale: tetrahedra taken out leave
// less volume than the hull, tetrahedra listed twice more.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "dtlab/engine/triangulate.hpp"
#include "dtlab/engine/validator.hpp"
#include "dtlab/generators/generators.hpp"
#include "validator_recount.hpp"

namespace dtlab::test {
namespace {

using engine::Tetrahedron;
using engine::ValidateWith;
using engine::ValidationReport;
using predicates::Point3;

struct NamedMesh {
  std::string name;
  std::vector<Point3> points;
  std::vector<Tetrahedron> tets;
};

std::vector<NamedMesh> meshes() {
  std::vector<NamedMesh> out;
  engine::TriangulateOptions exact;
  for (const std::string family : {"uniform", "sphere", "grid"}) {
    auto points = generators::generate(family, 4000, 3).points;
    auto tets = engine::triangulate(points, exact).tetrahedra;
    out.push_back({family, std::move(points), std::move(tets)});
  }
  engine::TriangulateOptions fast;
  fast.kernel = engine::KernelKind::Fast;
  for (const std::string family : {"cospherical", "near-duplicates"}) {
    auto points = generators::generate(family, 3000, 2).points;
    auto tets = engine::triangulate(points, fast).tetrahedra;
    out.push_back({"fast " + family, std::move(points), std::move(tets)});
  }
  const NamedMesh& base = out.front();
  NamedMesh holes{"uniform with holes", base.points, {}};
  for (std::size_t i = 0; i < base.tets.size(); ++i) {
    if (i % 97 != 5) holes.tets.push_back(base.tets[i]);
  }
  NamedMesh doubled{"uniform with tetrahedra twice", base.points, base.tets};
  for (std::size_t i = 3; i < base.tets.size(); i += 101) doubled.tets.push_back(base.tets[i]);
  NamedMesh scrambled{"uniform scrambled", base.points, base.tets};
  for (std::size_t i = 0; i < scrambled.tets.size(); i += 89) {
    std::swap(scrambled.tets[i][0], scrambled.tets[i][1]);  // inverted
  }
  scrambled.tets[7][2] = static_cast<std::uint32_t>(base.points.size());  // out of range
  scrambled.tets[11][3] = scrambled.tets[11][0];                          // a repeated vertex
  out.push_back(std::move(holes));
  out.push_back(std::move(doubled));
  out.push_back(std::move(scrambled));
  return out;
}

TEST(ValidatorThreads, TheReportDoesNotDependOnTheThreadCount) {
  for (const NamedMesh& m : meshes()) {
    SCOPED_TRACE(m.name);
    // Below 4096 tetrahedra (kParallelMinimum) the steps over them would run on one thread.
    ASSERT_GT(m.tets.size(), std::size_t{4096}) << "too small for the steps to split";
    const ValidationReport one = engine::validate(m.points, m.tets, ValidateWith::Adaptive, 1);
    for (const int threads : {2, 3, 4}) {
      const ValidationReport many =
          engine::validate(m.points, m.tets, ValidateWith::Adaptive, threads);
      EXPECT_EQ(many.json(), one.json()) << threads << " threads";
      EXPECT_EQ(many.non_delaunay_flags, one.non_delaunay_flags) << threads << " threads";
    }
    const ExactRecount exact = exact_recount(m.points, m.tets);
    EXPECT_EQ(one.invalid_tetrahedra, exact.invalid_tetrahedra);
    EXPECT_EQ(one.non_positive_orientation, exact.non_positive_orientation);
    EXPECT_EQ(one.non_manifold_faces, exact.non_manifold_faces);
    EXPECT_EQ(one.interior_faces, exact.interior_faces);
    EXPECT_EQ(one.boundary_faces, exact.boundary_faces);
    // The recount decides these two only when no tetrahedron is inverted: on every exactly built
    // mesh here but the scrambled one (the fast kernel's may have inverted ones, or not), so the
    // comparison is not skipped by accident.
    if (m.name.rfind("fast ", 0) != 0) {
      ASSERT_EQ(exact.non_positive_orientation == 0, m.name != "uniform scrambled");
    }
    if (exact.non_positive_orientation == 0) {
      EXPECT_EQ(one.inconsistent_faces, exact.inconsistent_faces);
      EXPECT_EQ(one.non_delaunay_faces, exact.non_delaunay_faces);
    }
    if (m.name == "uniform" || m.name == "sphere" || m.name == "grid") {
      EXPECT_TRUE(one.valid()) << one.json();
    }
    if (m.name == "uniform with holes") {
      EXPECT_EQ(one.volume_mismatch, 1u);
      EXPECT_EQ(one.volume_excess, 0u);
    }
    if (m.name == "uniform with tetrahedra twice") {
      EXPECT_EQ(one.volume_mismatch, 1u);
      EXPECT_EQ(one.volume_excess, 1u);
      EXPECT_GT(one.non_manifold_faces, 0u);
    }
    if (m.name == "uniform scrambled") {
      EXPECT_EQ(one.invalid_tetrahedra, 2u);
      EXPECT_GT(one.non_positive_orientation, 0u);
    }
  }
}

}  // namespace
}  // namespace dtlab::test
