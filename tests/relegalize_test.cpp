// A test of the engine's internals: it includes headers from engine/src (dtlab_internal_test).
// Burglary's repair, tested on its own: Lawson flips (IncrementalDelaunay::relegalize) on a
// Delaunay mesh into which non-Delaunay faces were injected by forced flips. The repair must find
// them from the marks (the injected flips' tetrahedra, or DAG nodes above them) and give back the
// unique Delaunay tetrahedralization; without the right marks it must leave them.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "dtlab/engine/point_set_info.hpp"
#include "dtlab/engine/validator.hpp"
#include "dtlab/generators/generators.hpp"
#include "insertion/inserter.hpp"

namespace dtlab::test {
namespace {

using engine::IncrementalDelaunay;
using engine::NoSync;
using engine::SharedMesh;
using engine::TetId;
using engine::VertexId;
using predicates::Point3;
using Dt = IncrementalDelaunay<predicates::AdaptiveKernel, NoSync>;

// A Delaunay mesh of `points` built in a SharedMesh the test can reach, plus forced flips.
class Relegalize : public ::testing::Test {
 protected:
  void build(const std::string& family, std::size_t n, std::uint64_t seed) {
    points = generators::generate(family, n, seed).points;
    mesh = std::make_unique<SharedMesh>(points);
    dt = std::make_unique<Dt>(*mesh, options, stats, sync);
    std::vector<std::uint32_t> order(points.size());
    std::iota(order.begin(), order.end(), 0U);
    const auto first = engine::find_simplex(points, order).simplex;
    ASSERT_TRUE(first.has_value());
    dt->start((*first)[0], (*first)[1], (*first)[2], (*first)[3]);
    for (const std::uint32_t v : order) {
      if (std::find(first->begin(), first->end(), v) != first->end()) continue;
      ASSERT_NE(dt->insert(v), Dt::Outcome::Abandoned);
    }
    ASSERT_TRUE(engine::validate(points, tets()).valid());
    delaunay = engine::canonical_tetrahedra(tets());
  }

  [[nodiscard]] std::vector<engine::Tetrahedron> tets() const {
    return dt->finite_tetrahedra(static_cast<VertexId>(points.size()));
  }

  // Forces flips of random faces of finite tetrahedra until `wanted` flips were made; returns the
  // tetrahedra they created (some die again under later flips: DAG nodes, as burglary's marks).
  std::vector<TetId> inject(int wanted, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::vector<TetId> created;
    int made = 0;
    for (int attempt = 0; made < wanted && attempt < 100 * wanted; ++attempt) {
      const auto t = static_cast<TetId>(rng() % mesh->tets.size());
      const engine::Tet& tet = mesh->tets[t];
      if (!mesh->tets.is_alive(t) || tet.is_infinite()) continue;
      const auto fresh = dt->flip_face(t, static_cast<int>(rng() % 4));
      if (fresh.empty()) continue;
      created.insert(created.end(), fresh.begin(), fresh.end());
      ++made;
    }
    EXPECT_EQ(made, wanted);
    return created;
  }

  std::vector<Point3> points;
  engine::TriangulateOptions options;
  engine::TriangulationStats stats;
  NoSync sync;
  std::unique_ptr<SharedMesh> mesh;
  std::unique_ptr<Dt> dt;
  std::vector<engine::Tetrahedron> delaunay;
};

TEST_F(Relegalize, ForcedFlipsBreakTheDelaunayProperty) {
  build("uniform", 400, 3);
  inject(10, 1);
  const auto report = engine::validate(points, tets());
  EXPECT_TRUE(report.consistent()) << report.json();  // still a triangulation of the hull
  EXPECT_GT(report.non_delaunay_faces, 0U);
}

TEST_F(Relegalize, FlipsOnTheMarksRestoreTheDelaunayMesh) {
  for (const std::string family : {"uniform", "normal", "cluster"}) {
    for (const std::uint64_t seed : {1U, 2U, 3U}) {
      build(family, 500, seed);
      const auto marks = inject(25, seed);
      ASSERT_GT(engine::validate(points, tets()).non_delaunay_faces, 0U);
      EXPECT_GT(dt->relegalize(marks, false), 0U);
      const auto report = engine::validate(points, tets());
      EXPECT_TRUE(report.valid()) << family << " seed " << seed << report.json();
      EXPECT_EQ(engine::canonical_tetrahedra(tets()), delaunay) << family << " seed " << seed;
    }
  }
}

// The marks may be dead DAG nodes: relegalize descends to the live tetrahedra below them. Here
// the marks are one forced flip's tetrahedra, and a second forced flip replaced one of them.
TEST_F(Relegalize, MarksAboveTheLiveTetrahedraAreFollowedDown) {
  build("uniform", 500, 7);
  std::vector<TetId> marks;
  for (TetId t = 0; t < mesh->tets.size() && marks.empty(); ++t) {
    if (!mesh->tets.is_alive(t) || mesh->tets[t].is_infinite()) continue;
    for (int f = 0; f < 4 && marks.empty(); ++f) marks = dt->flip_face(t, f);
  }
  ASSERT_FALSE(marks.empty());
  const std::vector<TetId> first = marks;
  bool again = false;
  for (const TetId t : first) {
    for (int f = 0; f < 4 && !again; ++f) {
      // Not back across the faces the first flip created (that would undo it).
      const TetId other = engine::ref_tet(mesh->tets[t].neighbor[static_cast<std::size_t>(f)]);
      if (std::find(first.begin(), first.end(), other) != first.end()) continue;
      again = !dt->flip_face(t, f).empty();
    }
    if (again) break;
  }
  ASSERT_TRUE(again);
  std::size_t dead = 0;
  for (const TetId t : marks) dead += mesh->tets.is_alive(t) ? 0 : 1;
  ASSERT_GT(dead, 0U);
  ASSERT_GT(engine::validate(points, tets()).non_delaunay_faces, 0U);
  EXPECT_GT(dt->relegalize(marks, false), 0U);
  EXPECT_EQ(engine::canonical_tetrahedra(tets()), delaunay);
}

// Marks that miss the broken faces repair nothing; the sweep over every tetrahedron does.
TEST_F(Relegalize, WrongMarksLeaveTheFacesAndTheSweepFindsThem) {
  build("uniform", 500, 11);
  inject(25, 11);
  EXPECT_EQ(dt->relegalize({}, false), 0U);
  const std::uint64_t left = engine::validate(points, tets()).non_delaunay_faces;
  EXPECT_GT(left, 0U);
  EXPECT_GT(dt->relegalize({}, true), 0U);
  EXPECT_TRUE(engine::validate(points, tets()).valid());
  EXPECT_EQ(engine::canonical_tetrahedra(tets()), delaunay);
}

// Hull faces too: forced flips next to the vertex at infinity make the hull non-convex (reflex
// boundary edges), and the flips on the marks make it convex again.
TEST_F(Relegalize, HullFlipsAreRepaired) {
  build("sphere", 300, 5);
  std::mt19937_64 rng(5);
  std::vector<TetId> marks;
  int made = 0;
  for (int attempt = 0; made < 10 && attempt < 100000; ++attempt) {
    const auto t = static_cast<TetId>(rng() % mesh->tets.size());
    const engine::Tet& tet = mesh->tets[t];
    if (!mesh->tets.is_alive(t) || !tet.is_infinite()) continue;
    // A face between two infinite tetrahedra is a hull edge's: flipping it changes the hull.
    const int inf = tet.index_of(engine::kInfiniteVertex);
    const int f = static_cast<int>((static_cast<std::uint64_t>(inf) + 1 + rng() % 3) % 4);
    const auto fresh = dt->flip_face(t, f);
    if (fresh.empty()) continue;
    marks.insert(marks.end(), fresh.begin(), fresh.end());
    ++made;
  }
  ASSERT_GT(made, 0);
  const auto broken = engine::validate(points, tets());
  EXPECT_GT(broken.reflex_boundary_edges, 0U) << broken.json();
  EXPECT_TRUE(broken.mesh_consistent()) << broken.json();
  dt->relegalize(marks, false);
  EXPECT_TRUE(engine::validate(points, tets()).valid());
  EXPECT_EQ(engine::canonical_tetrahedra(tets()), delaunay);
}

}  // namespace
}  // namespace dtlab::test
