// A test of the engine's internals: it includes headers from engine/src (dtlab_internal_test).
// Subdivisions and swaps on hand-built configurations, bad input, and the validator catching
// each kind of broken mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "dtlab/engine/point_set_info.hpp"
#include "dtlab/engine/triangulate.hpp"
#include "dtlab/engine/validator.hpp"
#include "dtlab/generators/generators.hpp"
#include "dtlab/predicates/kernels.hpp"
#include "insertion/inserter.hpp"
#include "validator_recount.hpp"

namespace dtlab::test {
namespace {

using engine::IncrementalDelaunay;
using engine::TriangulateOptions;
using engine::TriangulationStats;
using predicates::AdaptiveKernel;
using predicates::Point3;
using Dt = IncrementalDelaunay<AdaptiveKernel>;

// The corner tetrahedron plus one more point, inserted by hand.
struct OnePointFixture {
  explicit OnePointFixture(Point3 p)
      : points{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, p}, dt(points, options, stats) {
    dt.start(0, 1, 2, 3);
    outcome = dt.insert(4);
    tets = dt.finite_tetrahedra(5);
  }
  std::vector<Point3> points;
  TriangulateOptions options;
  TriangulationStats stats;
  Dt dt;
  Dt::Outcome outcome;
  std::vector<engine::Tetrahedron> tets;

  void expect_valid_with(std::size_t count) const {
    EXPECT_EQ(tets.size(), count);
    for (const auto& t : tets) {
      EXPECT_EQ(AdaptiveKernel::orient3d(points[t[0]], points[t[1]], points[t[2]], points[t[3]]),
                1);
    }
    EXPECT_TRUE(engine::validate(points, tets).valid()) << engine::validate(points, tets).json();
  }
};

TEST(Subdivision, OneToFourInside) {
  OnePointFixture f({0.125, 0.25, 0.25});
  EXPECT_EQ(f.outcome, Dt::Outcome::Inserted);
  f.expect_valid_with(4);
  for (const auto& t : f.tets) EXPECT_NE(std::find(t.begin(), t.end(), 4u), t.end());
}

TEST(Subdivision, TwoToSixOnAFace) {
  OnePointFixture f({0.25, 0.25, 0.0});  // on the hull face z = 0: 3 finite + 3 infinite
  EXPECT_EQ(f.outcome, Dt::Outcome::Inserted);
  f.expect_valid_with(3);
}

TEST(Subdivision, KToTwoKOnAnEdge) {
  OnePointFixture f({0.5, 0.0, 0.0});  // on edge (0, 1)
  EXPECT_EQ(f.outcome, Dt::Outcome::Inserted);
  f.expect_valid_with(2);
}

TEST(Subdivision, DuplicateIsDetected) {
  OnePointFixture f({1.0, 0.0, 0.0});
  EXPECT_EQ(f.outcome, Dt::Outcome::Duplicate);
  f.expect_valid_with(1);
}

TEST(Swaps, S23WhenTheNewPointIsInsideANeighbourSphere) {
  // Beyond face x+y+z=1 but inside the corner tetrahedron's circumsphere: the face between
  // (face, p) and the corner tetrahedron is illegal and S23 makes three tetrahedra around
  // the edge from the origin to p.
  OnePointFixture f({0.4, 0.4, 0.4});
  EXPECT_EQ(f.outcome, Dt::Outcome::Inserted);
  EXPECT_GE(f.stats.flips.s23, 1u);
  f.expect_valid_with(3);
}

TEST(Swaps, NoSwapWhenOutsideTheSphere) {
  OnePointFixture f({2.0, 2.0, 2.0});
  EXPECT_EQ(f.outcome, Dt::Outcome::Inserted);
  f.expect_valid_with(2);
}

TEST(Swaps, GridDataNeedsS22AndS44) {
  TriangulateOptions options;
  const auto points = generators::generate("grid", 125, 1).points;
  const auto result = engine::triangulate(points, options);
  EXPECT_GT(result.stats.flips.s44, 0u);
  EXPECT_GT(result.stats.flips.s22, 0u);
  EXPECT_GT(result.stats.flips.s32, 0u);
  EXPECT_TRUE(engine::validate(points, result.tetrahedra).valid());
}

// Every split and flip links the new tetrahedra directly from their sources (2->6, k->2k, S44
// and S22 through TetReplacement::link_from_sources); the validator rebuilds adjacency from the
// output and would not see a wrong reference, so the store's own references are checked here:
// across every face of every live tetrahedron, the neighbour points back and has the same three
// vertices. Grid points on the lattice make every kind of split and flip.
TEST(Swaps, NeighbourReferencesStayMutual) {
  for (const auto location : {engine::Location::Walk, engine::Location::Dag}) {
    const auto points = generators::generate("grid", 512, 1).points;
    TriangulateOptions options;
    options.location = location;
    TriangulationStats stats;
    Dt dt(points, options, stats);
    std::vector<std::uint32_t> order(points.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::uint32_t>(i);
    const auto first = *engine::find_simplex(points, order).simplex;
    dt.start(first[0], first[1], first[2], first[3]);
    for (const std::uint32_t v : order) {
      if (std::find(first.begin(), first.end(), v) == first.end()) dt.insert(v);
    }
    EXPECT_GT(stats.flips.s44, 0u);
    EXPECT_GT(stats.flips.s22, 0u);
    const auto& tets = dt.mesh().tets;
    std::size_t live = 0;
    for (engine::TetId t = 0; t < tets.size(); ++t) {
      if (!tets.is_alive(t)) continue;
      ++live;
      for (int f = 0; f < 4; ++f) {
        const engine::FaceRef across = tets[t].neighbor[static_cast<std::size_t>(f)];
        const engine::TetId other = engine::ref_tet(across);
        ASSERT_LT(other, tets.size());
        ASSERT_TRUE(tets.is_alive(other)) << t << " " << f;
        EXPECT_EQ(tets[other].neighbor[static_cast<std::size_t>(engine::ref_face(across))],
                  engine::face_ref(t, f));
        auto face = [&](engine::TetId id, int g) {
          std::vector<engine::VertexId> v;
          for (int i = 0; i < 4; ++i) {
            if (i != g) v.push_back(tets[id].vertex[static_cast<std::size_t>(i)]);
          }
          std::sort(v.begin(), v.end());
          return v;
        };
        EXPECT_EQ(face(t, f), face(other, engine::ref_face(across)));
      }
    }
    EXPECT_GT(live, points.size());
  }
}

TEST(BadInput, NoTetrahedralizationIsAnError) {
  TriangulateOptions options;
  EXPECT_THROW(engine::triangulate({}, options), engine::TriangulationError);
  EXPECT_THROW(engine::triangulate({{0, 0, 0}, {1, 1, 1}, {0, 0, 0}}, options),
               engine::TriangulationError);
  EXPECT_THROW(engine::triangulate(generators::generate("coplanar", 50, 1).points, options),
               engine::TriangulationError);
  EXPECT_THROW(engine::triangulate(generators::generate("collinear", 50, 1).points, options),
               engine::TriangulationError);
  // Four distinct points, each repeated: one tetrahedron, duplicates counted.
  std::vector<Point3> repeated{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  repeated.insert(repeated.end(), repeated.begin(), repeated.end());
  const auto r = engine::triangulate(repeated, options);
  EXPECT_EQ(r.tetrahedra.size(), 1u);
  EXPECT_EQ(r.stats.duplicates, 4u);
}

TEST(RangeScaling, LosslessAndExpansionRangeByExponent) {
  using engine::adaptive_range_scaling;
  const engine::RangeScaling none = adaptive_range_scaling(0.0, 0.0);
  EXPECT_EQ(none.exponent, 0);
  EXPECT_TRUE(none.lossless);
  EXPECT_TRUE(none.within_expansion_range);
  const engine::RangeScaling unit = adaptive_range_scaling(1.0, 0.5);
  EXPECT_EQ(unit.exponent, 99);
  EXPECT_TRUE(unit.lossless);
  EXPECT_TRUE(unit.within_expansion_range);
  // The smallest subnormal next to 1: scaled by 2^99 it stays normal, but far below 2^-120.
  const engine::RangeScaling denormal = adaptive_range_scaling(1.0, 4.94e-324);
  EXPECT_EQ(denormal.exponent, 99);
  EXPECT_TRUE(denormal.lossless);
  EXPECT_FALSE(denormal.within_expansion_range);
  // Lossless exactly while the scaled smallest magnitude stays >= 2^-1022.
  EXPECT_TRUE(adaptive_range_scaling(0x1p47, 0x1p-1074).lossless);   // 2^-1074 * 2^52
  EXPECT_FALSE(adaptive_range_scaling(0x1p48, 0x1p-1074).lossless);  // 2^-1074 * 2^51
  EXPECT_FALSE(adaptive_range_scaling(1e300, 1e-300).lossless);
  EXPECT_FALSE(adaptive_range_scaling(1e300, 1e-300).within_expansion_range);
  // At the edges of the expansion range after scaling: 2^-120 inside, 2^-121 outside.
  EXPECT_TRUE(adaptive_range_scaling(0x1p99, 0x1p-120).within_expansion_range);
  EXPECT_FALSE(adaptive_range_scaling(0x1p99, 0x1p-121).within_expansion_range);
}

// adaptive, filtered and exact decide every finite double exactly (adaptive and filtered hand what
// their expansion arithmetic cannot take to GMP): no input is refused for its magnitudes, and all
// three give the same tetrahedra.
TEST(WideMagnitudes, AreTriangulatedExactlyByEveryExactKernel) {
  std::vector<std::pair<std::string, std::vector<Point3>>> cases;
  cases.push_back(
      {"1e-300 next to 1", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1e-300, 0.5, 0.5}}});
  // An 8^3 grid on [0,1]^3, one coordinate the smallest subnormal: scaled losslessly, outside
  // the expansion range.
  std::vector<Point3> grid;
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 8; ++j) {
      for (int k = 0; k < 8; ++k) grid.push_back({i / 7.0, j / 7.0, k / 7.0});
    }
  }
  grid[0].x = 4.94e-324;
  cases.push_back({"grid with a subnormal", grid});
  // 1e300 next to subnormals: no lossless scaling exists, the points are taken as they are.
  cases.push_back({"1e300 and subnormals",
                   {{0, 0, 0},
                    {1e300, 0, 0},
                    {0, 1e300, 0},
                    {0, 0, 1e300},
                    {4.94e-324, 3e299, 3e299},
                    {1e300, 1e300, 1e300},
                    {1e-310, 1e300, 2e299},
                    {5e299, 5e299, 1e-323}}});
  for (const auto& [what, points] : cases) {
    EXPECT_FALSE(engine::analyze(points).within_expansion_range) << what;
    TriangulateOptions options;
    options.kernel = engine::KernelKind::Exact;
    const auto exact = engine::triangulate(points, options);
    EXPECT_TRUE(engine::validate(points, exact.tetrahedra).valid()) << what;
    for (const auto kernel : {engine::KernelKind::Adaptive, engine::KernelKind::Filtered}) {
      options.kernel = kernel;
      const auto r = engine::triangulate(points, options);
      EXPECT_EQ(r.stats.inserted + r.stats.duplicates, points.size())
          << what << " " << engine::to_string(kernel);
      EXPECT_EQ(r.stats.scale_exponent, exact.stats.scale_exponent);
      const auto report = engine::validate(points, r.tetrahedra);
      EXPECT_TRUE(report.valid()) << what << " " << engine::to_string(kernel) << report.json();
      EXPECT_EQ(engine::canonical_tetrahedra(r.tetrahedra),
                engine::canonical_tetrahedra(exact.tetrahedra))
          << what << " " << engine::to_string(kernel);
    }
  }
  EXPECT_EQ(engine::triangulate(grid, {}).stats.scale_exponent, 99);
  EXPECT_EQ(engine::triangulate(cases.back().second, {}).stats.scale_exponent, 0);
  // Uniformly tiny or huge inputs are rescaled exactly and stay in the expansion range.
  for (const std::string family : {"tiny", "huge"}) {
    const auto pts = generators::generate(family, 300, 3).points;
    EXPECT_TRUE(engine::analyze(pts).within_expansion_range) << family;
    for (const auto kernel : {engine::KernelKind::Adaptive, engine::KernelKind::Filtered}) {
      TriangulateOptions options;
      options.kernel = kernel;
      EXPECT_TRUE(engine::validate(pts, engine::triangulate(pts, options).tetrahedra).valid())
          << family << " " << engine::to_string(kernel);
    }
  }
}

TEST(BadInput, AnAuxiliaryTetrahedronBeyondDoubleIsRefused) {
  // Not scaled (no lossless scaling exists), and 200 x 1e307 overflows.
  const std::vector<Point3> points{
      {0, 0, 0}, {1e307, 0, 0}, {0, 1e307, 0}, {0, 0, 1e307}, {4.94e-324, 1e306, 1e306}};
  TriangulateOptions options;
  options.bounding = engine::Bounding::AuxTet;
  EXPECT_THROW(engine::triangulate(points, options), engine::TriangulationError);
  options.bounding = engine::Bounding::Infinite;
  EXPECT_TRUE(engine::validate(points, engine::triangulate(points, options).tetrahedra).valid());
}

// The fast kernel finishes on degenerate families (its mesh may be wrong), and the validator
// reports what is wrong with it: its counters equal an independent exact recount (GMP signs, a
// face map, geometric sides; tests/validator_recount.hpp).
TEST(FastKernel, FinishesAndTheValidatorReportsItsErrorsExactly) {
  TriangulateOptions options;
  options.kernel = engine::KernelKind::Fast;
  int compared_with_errors = 0;
  for (const std::string family : {"sphere", "cospherical", "near-duplicates", "grid"}) {
    const auto pts = generators::generate(family, 3000, 2).points;
    const auto r = engine::triangulate(pts, options);
    const auto report = engine::validate(pts, r.tetrahedra);
    const auto exact = exact_recount(pts, r.tetrahedra);
    std::printf(
        "fast kernel on %s:3000: %llu abandoned, valid %d, non-Delaunay faces %llu, "
        "non-positive tetrahedra %llu\n",
        family.c_str(), static_cast<unsigned long long>(r.stats.abandoned_insertions),
        report.valid(), static_cast<unsigned long long>(report.non_delaunay_faces),
        static_cast<unsigned long long>(report.non_positive_orientation));
    EXPECT_EQ(report.points, pts.size()) << family;
    EXPECT_EQ(report.tetrahedra, r.tetrahedra.size()) << family;
    EXPECT_EQ(report.invalid_tetrahedra, exact.invalid_tetrahedra) << family;
    EXPECT_EQ(report.non_positive_orientation, exact.non_positive_orientation) << family;
    EXPECT_EQ(report.non_manifold_faces, exact.non_manifold_faces) << family;
    EXPECT_EQ(report.interior_faces, exact.interior_faces) << family;
    EXPECT_EQ(report.boundary_faces, exact.boundary_faces) << family;
    // The recount decides these two only where no tetrahedron is inverted; the families that
    // took this branch with faces to count are counted, so it cannot be skipped throughout.
    if (exact.non_positive_orientation == 0) {
      EXPECT_EQ(report.inconsistent_faces, exact.inconsistent_faces) << family;
      EXPECT_EQ(report.non_delaunay_faces, exact.non_delaunay_faces) << family;
      if (exact.non_delaunay_faces > 0) ++compared_with_errors;
    }
  }
  EXPECT_GE(compared_with_errors, 1) << "no wrong mesh had its face counters compared";
}

// The validator must fail each broken mesh, for the reason that breaks it.
class ValidatorCatches : public ::testing::Test {
 protected:
  void SetUp() override {
    points = generators::generate("uniform", 300, 11).points;
    tets = engine::triangulate(points, {}).tetrahedra;
    ASSERT_TRUE(engine::validate(points, tets).valid());
  }
  std::vector<Point3> points;
  std::vector<engine::Tetrahedron> tets;
};

TEST_F(ValidatorCatches, InvertedTetrahedron) {
  std::swap(tets[7][0], tets[7][1]);
  const auto r = engine::validate(points, tets);
  EXPECT_FALSE(r.valid());
  EXPECT_EQ(r.non_positive_orientation, 1u);
  EXPECT_GE(r.inconsistent_faces, 1u);
}

TEST_F(ValidatorCatches, MissingTetrahedron) {
  tets.erase(tets.begin() + 100);
  const auto r = engine::validate(points, tets);
  EXPECT_FALSE(r.consistent());
}

TEST_F(ValidatorCatches, RepeatedTetrahedron) {
  tets.push_back(tets[3]);
  EXPECT_GT(engine::validate(points, tets).non_manifold_faces, 0u);
}

TEST_F(ValidatorCatches, BadVertexIds) {
  tets[0][1] = tets[0][0];
  tets[1][2] = 100000;
  EXPECT_EQ(engine::validate(points, tets).invalid_tetrahedra, 2u);
}

TEST(Validator, NonDelaunayPairIsCounted) {
  // Five points in convex position where the 2-tetrahedron split is not Delaunay (the 3-split
  // around the edge from the origin to p is, see Swaps.S23...).
  const std::vector<Point3> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.4, 0.4, 0.4}};
  const std::vector<engine::Tetrahedron> two{{0, 1, 2, 3}, {1, 2, 3, 4}};
  // Orient the second one positively.
  std::vector<engine::Tetrahedron> tets = two;
  if (AdaptiveKernel::orient3d(p[1], p[2], p[3], p[4]) < 0) std::swap(tets[1][0], tets[1][1]);
  const auto r = engine::validate(p, tets);
  EXPECT_TRUE(r.consistent()) << r.json();
  EXPECT_EQ(r.non_delaunay_faces, 1u);
  EXPECT_FALSE(r.valid());
}

TEST(Validator, NonConvexUnionIsCaught) {
  // Two tetrahedra of a valid 3-split missing the third: the union is not the convex hull.
  const std::vector<Point3> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.4, 0.4, 0.4}};
  auto r = engine::triangulate(p, {});
  ASSERT_EQ(r.tetrahedra.size(), 3u);
  r.tetrahedra.pop_back();
  const auto report = engine::validate(p, r.tetrahedra);
  EXPECT_GT(report.reflex_boundary_edges, 0u);
  EXPECT_FALSE(report.valid());
}

// Neighbour references are 4 * tet + face in 32 bits: the store refuses the 2^30-th slot rather
// than let a reference wrap (4 * 2^30 is 0 in 32 bits).
TEST(StoreLimit, TheLastIdBelow2To30IsTheLastSlot) {
  using engine::TetStore;
  TetStore store;
  store.skip_to_for_testing(TetStore::kMaxTets - 2);
  EXPECT_EQ(store.allocate(), TetStore::kMaxTets - 2);
  const engine::TetId last = store.allocate();
  EXPECT_EQ(last, TetStore::kMaxTets - 1);
  EXPECT_EQ(engine::ref_tet(engine::face_ref(last, 3)), last);
  EXPECT_EQ(engine::ref_face(engine::face_ref(last, 3)), 3);
  EXPECT_THROW(store.allocate(), engine::StoreFull);
  EXPECT_EQ(store.size(), TetStore::kMaxTets);
  EXPECT_NE(engine::ref_tet(engine::face_ref(static_cast<engine::TetId>(TetStore::kMaxTets), 0)),
            TetStore::kMaxTets);  // what the refusal prevents
}

TEST(StoreLimit, ASequentialRunThatNeedsMoreStopsWithAClearError) {
  const auto points = generators::generate("uniform", 2000, 1).points;
  TriangulateOptions options;
  options.max_tetrahedra = 5000;
  try {
    (void)engine::triangulate(points, options);
    FAIL() << "no error";
  } catch (const engine::TriangulationError& e) {
    EXPECT_NE(std::string(e.what()).find("store is full: 5000"), std::string::npos) << e.what();
  }
  options.max_tetrahedra = 0;  // the default limit fits
  EXPECT_TRUE(engine::validate(points, engine::triangulate(points, options).tetrahedra).valid());
}

TEST(MovedInput, ComesBackUnchangedWithTheSameMesh) {
  // The engine scales and (sequential walk) reorders moved points in place; it must hand them back
  // bit for bit, and the mesh must be the one the copying overload makes. Tiny magnitudes are
  // scaled up by 2^k, duplicates are renamed after the reordering, the auxiliary points dropped.
  auto tiny = generators::generate("uniform", 600, 3).points;
  for (Point3& p : tiny) p = {std::ldexp(p.x, -600), std::ldexp(p.y, -600), std::ldexp(p.z, -600)};
  const std::vector<std::vector<Point3>> inputs{generators::generate("duplicates", 800, 2).points,
                                                tiny, generators::generate("grid", 729, 1).points};
  for (const auto& original : inputs) {
    for (const auto location : {engine::Location::Walk, engine::Location::Dag}) {
      for (const auto method : {engine::Method::Sequential, engine::Method::OptimisticDetect}) {
        for (const auto bounding : {engine::Bounding::Infinite, engine::Bounding::AuxTet}) {
          TriangulateOptions options;
          options.location = location;
          options.method = method;
          options.threads = method == engine::Method::Sequential ? 1 : 2;
          options.bounding = bounding;
          const auto copied = engine::triangulate(original, options);
          std::vector<Point3> moved = original;
          const auto result = engine::triangulate(std::move(moved), options);
          const std::string what = std::string(engine::to_string(location)) + " " +
                                   engine::to_string(method) + " " + engine::to_string(bounding);
          EXPECT_TRUE(result.points == original) << what;
          if (method == engine::Method::Sequential) {
            EXPECT_EQ(result.tetrahedra, copied.tetrahedra) << what;
          } else {  // the threads' interleaving orders the output differently; the set is unique
            EXPECT_EQ(engine::canonical_tetrahedra(result.tetrahedra),
                      engine::canonical_tetrahedra(copied.tetrahedra))
                << what;
          }
          if (bounding == engine::Bounding::Infinite) {  // aux-tet may lose hull tetrahedra
            EXPECT_TRUE(engine::validate(original, result.tetrahedra).valid()) << what;
          }
        }
      }
    }
  }
}

TEST(MovedInput, AnErrorLeavesThePointsAsTheyWere) {
  // Thrown after the points were scaled and reordered: the store's limit.
  auto original = generators::generate("uniform", 2000, 1).points;
  for (Point3& p : original) p = {std::ldexp(p.x, 300), std::ldexp(p.y, 300), p.z};
  for (const auto location : {engine::Location::Walk, engine::Location::Dag}) {
    TriangulateOptions options;
    options.location = location;
    options.max_tetrahedra = 5000;
    std::vector<Point3> moved = original;
    EXPECT_THROW((void)engine::triangulate(std::move(moved), options), engine::TriangulationError);
    EXPECT_TRUE(moved == original) << engine::to_string(location);
  }
}

}  // namespace
}  // namespace dtlab::test
