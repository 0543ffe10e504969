// CGAL's Delaunay_triangulation_3 as oracle (tests/cgal_reference.hpp). dtlab and CGAL both break
// cospherical and cocircular ties by the lexicographic symbolic perturbation of the lifting map
// (docs/predicates.md), so the perturbed Delaunay tetrahedralization is unique and the two sets of
// tetrahedra must be equal on every generator family, degenerate ones included (grids, spheres,
// exact duplicates, ...). Duplicates: both sides name each set of duplicate points by its lowest
// input index. Families without a tetrahedralization (decided by CGAL's dimension, not by a list)
// must be refused by dtlab.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cgal_reference.hpp"
#include "dtlab/engine/repair.hpp"
#include "dtlab/engine/triangulate.hpp"
#include "dtlab/engine/validator.hpp"
#include "dtlab/generators/generators.hpp"

namespace dtlab::test {
namespace {

std::string show(const std::vector<engine::Tetrahedron>& tets, std::size_t limit) {
  std::ostringstream out;
  for (std::size_t i = 0; i < tets.size() && i < limit; ++i) {
    out << " (" << tets[i][0] << " " << tets[i][1] << " " << tets[i][2] << " " << tets[i][3] << ")";
  }
  if (tets.size() > limit) out << " ...";
  return out.str();
}

// Equality of the sorted sets, with a short account of the difference instead of two dumps of
// thousands of tetrahedra.
::testing::AssertionResult same_tetrahedra(const std::vector<engine::Tetrahedron>& ours,
                                           const std::vector<engine::Tetrahedron>& cgal) {
  const auto a = engine::canonical_tetrahedra(ours);
  const auto b = engine::canonical_tetrahedra(cgal);
  if (a == b) return ::testing::AssertionSuccess();
  std::vector<engine::Tetrahedron> only_ours;
  std::vector<engine::Tetrahedron> only_cgal;
  std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(only_ours));
  std::set_difference(b.begin(), b.end(), a.begin(), a.end(), std::back_inserter(only_cgal));
  return ::testing::AssertionFailure()
         << "dtlab " << a.size() << " tetrahedra, CGAL " << b.size() << "; only dtlab's "
         << only_ours.size() << ":" << show(only_ours, 8) << "; only CGAL's " << only_cgal.size()
         << ":" << show(only_cgal, 8);
}

TEST(CgalReference, DimensionAndDuplicates) {
  EXPECT_EQ(cgal_dimension({}), -1);
  EXPECT_EQ(cgal_dimension({{1, 2, 3}, {1, 2, 3}}), 0);
  EXPECT_EQ(cgal_dimension({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {0, 0, 0}}), 1);
  EXPECT_EQ(cgal_dimension({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 3, 0}}), 2);
  EXPECT_EQ(cgal_dimension({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}), 3);
  EXPECT_TRUE(cgal_delaunay({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}).empty());
  // One tetrahedron, every corner given twice (and 0.0 as -0.0 once): named by the lowest index.
  const std::vector<Point3> repeated{{0, 0, 1},    {1, 0, 0}, {0, 0, 0}, {0, 1, 0},
                                     {-0.0, 0, 1}, {0, 1, 0}, {1, 0, 0}, {0, 0, 0}};
  EXPECT_EQ(engine::canonical_tetrahedra(cgal_delaunay(repeated)),
            (std::vector<engine::Tetrahedron>{{0, 1, 2, 3}}));
  EXPECT_EQ(engine::canonical_tetrahedra(engine::triangulate(repeated, {}).tetrahedra),
            (std::vector<engine::Tetrahedron>{{0, 1, 2, 3}}));
  EXPECT_FALSE(all_finite({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, std::nan("")}}));
  EXPECT_THROW(cgal_dimension({{0, 0, 0}, {0, 0, std::numeric_limits<double>::infinity()}}),
               std::invalid_argument);
}

// Every family, two sizes, three seeds (the seed also drives dtlab's insertion order). The
// seedless families (grid, lattice) run once per size. Cavity insertion runs with every cavity
// checked (check_cavities): no cavity may fail to be a star around its point with this kernel.
void every_family_against_cgal(engine::Location location,
                               engine::Insertion insertion = engine::Insertion::Flips,
                               engine::Method method = engine::Method::Sequential) {
  int compared = 0;
  std::vector<std::string> refused;
  for (const std::string& family : generators::families()) {
    for (const std::int64_t n : {200, 2000}) {
      std::vector<Point3> previous;
      for (const std::uint64_t seed : {1u, 2u, 3u}) {
        const auto pts = generators::generate(family, n, seed).points;
        if (pts == previous) continue;
        previous = pts;
        engine::TriangulateOptions options;
        options.seed = seed;
        options.location = location;
        options.insertion = insertion;
        options.check_cavities = true;
        options.method = method;
        if (method != engine::Method::Sequential) {
          options.threads = 2;
          options.points_per_part = 32;  // partitioned: these sets cut into parts
          options.lock_grid_cells = 3;   // lock-grid: cells the threads share
        }
        const std::string what = family + ":" + std::to_string(n) + " seed " + std::to_string(seed);
        if (cgal_dimension(pts) < 3) {
          EXPECT_THROW(engine::triangulate(pts, options), engine::TriangulationError) << what;
          EXPECT_TRUE(cgal_delaunay(pts).empty()) << what;
          refused.push_back(what);
          continue;
        }
        const auto result = engine::triangulate(pts, options);
        EXPECT_TRUE(same_tetrahedra(result.tetrahedra, cgal_delaunay(pts))) << what;
        EXPECT_EQ(result.stats.cavity.fallbacks, 0u) << what;
        if (insertion == engine::Insertion::Cavity) {
          // Every point but the first four and the duplicates entered by its cavity.
          EXPECT_EQ(result.stats.cavity.insertions + result.stats.duplicates + 4, pts.size())
              << what;
        }
        ++compared;
      }
    }
  }
  std::printf(
      "compared with CGAL: %d point sets; no tetrahedralization (CGAL dimension < 3, "
      "refused by dtlab): %zu\n",
      compared, refused.size());
  for (const auto& r : refused) std::printf("  refused: %s\n", r.c_str());
  EXPECT_GT(compared, 0);
}

// canonical_tetrahedra keeps orientation: the 24 orderings of one tetrahedron's ids fall into
// two classes, the even permutations (one canonical form) and the odd ones (the other). Parity is
// counted here by inversions, independently of the sorting network that computes it there.
TEST(CanonicalTetrahedra, SameIdsCompareEqualExactlyWhenTheOrientationAgrees) {
  engine::Tetrahedron t{7, 3, 9, 1};
  const engine::Tetrahedron given = t;
  const auto reference = engine::canonical_tetrahedra({given});
  std::sort(t.begin(), t.end());
  int orderings = 0;
  do {
    int inversions = 0;  // of t against the order as given
    for (std::size_t i = 0; i < 4; ++i) {
      for (std::size_t j = i + 1; j < 4; ++j) {
        const auto at = [&given](std::uint32_t id) {
          return std::find(given.begin(), given.end(), id) - given.begin();
        };
        if (at(t[i]) > at(t[j])) ++inversions;
      }
    }
    const bool same_orientation = inversions % 2 == 0;
    EXPECT_EQ(engine::canonical_tetrahedra({t}) == reference, same_orientation)
        << t[0] << " " << t[1] << " " << t[2] << " " << t[3];
    ++orderings;
  } while (std::next_permutation(t.begin(), t.end()));
  EXPECT_EQ(orderings, 24);
}

// The oracle comparison sees orientation: dtlab's mesh equals CGAL's, and the same mesh with one
// tetrahedron inverted (two ids exchanged), or turned by an even permutation, is compared as such.
TEST(CgalOracle, AnInvertedTetrahedronIsADifference) {
  const auto points = generators::generate("uniform", 300, 3).points;
  auto ours = engine::triangulate(points, {}).tetrahedra;
  const auto cgal = cgal_delaunay(points);
  ASSERT_TRUE(same_tetrahedra(ours, cgal));
  auto turned = ours;
  std::rotate(turned[10].begin() + 1, turned[10].begin() + 2, turned[10].end());  // even
  EXPECT_TRUE(same_tetrahedra(turned, cgal));
  std::swap(ours[10][0], ours[10][1]);
  EXPECT_FALSE(same_tetrahedra(ours, cgal));
}

// The paper's auxiliary tetrahedron (200 x the bounding box here) loses the hull tetrahedra whose
// circumspheres reach one of its corners. The count the engine reports is checked against CGAL's
// mesh: what the run kept is a subset of CGAL's tetrahedra, and the rest of CGAL's are the loss.
// A unit cube with its corner (1, 1, 0) moved to (1.1, 1.1, -1e-6) has a sliver on its bottom,
// (0,0,0) (1,0,0) (0,1,0) and the moved corner, whose circumsphere is centred about 1.1e5 below
// it (h = (rho^2 + z^2 - 1/2) / 2z for the fourth point at height z and distance rho from the
// circle's centre, rho^2 = 0.72) and holds every corner of the auxiliary tetrahedron below the
// box: a loss there is certain.
TEST(AuxTet, LostHullTetrahedraAreCountedAgainstCgal) {
  std::vector<Point3> sliver_cube;
  for (const double x : {0.0, 1.0}) {
    for (const double y : {0.0, 1.0}) {
      for (const double z : {0.0, 1.0}) {
        const bool moved = x == 1 && y == 1 && z == 0;
        sliver_cube.push_back(moved ? Point3{1.1, 1.1, -1e-6} : Point3{x, y, z});
      }
    }
  }
  struct Case {
    std::string name;
    std::vector<Point3> points;
  };
  for (const Case& c : {Case{"uniform:2000", generators::generate("uniform", 2000, 4).points},
                        Case{"cube with a sliver", sliver_cube}}) {
    engine::TriangulateOptions options;
    options.bounding = engine::Bounding::AuxTet;
    const auto run = engine::triangulate(c.points, options);
    const auto kept = engine::canonical_tetrahedra(run.tetrahedra);
    const auto cgal = engine::canonical_tetrahedra(cgal_delaunay(c.points));
    std::vector<engine::Tetrahedron> extra;
    std::set_difference(kept.begin(), kept.end(), cgal.begin(), cgal.end(),
                        std::back_inserter(extra));
    EXPECT_TRUE(extra.empty()) << c.name << ": not CGAL's:" << show(extra, 8);
    const auto lost = static_cast<std::int64_t>(cgal.size() - (kept.size() - extra.size()));
    EXPECT_EQ(run.stats.hull_tetrahedra_lost, lost) << c.name;
    std::printf("aux-tet on %s: %lld of CGAL's %zu tetrahedra lost\n", c.name.c_str(),
                static_cast<long long>(lost), cgal.size());
    // Losing some leaves a non-convex union, which the validator reports.
    EXPECT_EQ(engine::validate(c.points, run.tetrahedra).valid(), lost == 0) << c.name;
    if (c.name != "uniform:2000") {
      EXPECT_GT(lost, 0) << c.name;
    }
  }
}

TEST(CgalOracle, EveryFamilyIdenticalTetrahedra) {
  every_family_against_cgal(engine::Location::Dag);
}

// The walk mode (BRIO and Hilbert order, visibility walk, slots reused) on the same sets.
TEST(CgalOracle, EveryFamilyIdenticalTetrahedraInWalkMode) {
  every_family_against_cgal(engine::Location::Walk);
}

// Bowyer-Watson insertion (--insertion cavity) on the same sets.
TEST(CgalOracle, EveryFamilyIdenticalTetrahedraByCavities) {
  every_family_against_cgal(engine::Location::Walk, engine::Insertion::Cavity);
}

// The partitioned method on 2 threads, parts of 32 points, both insertions, the same sets.
TEST(CgalOracle, EveryFamilyIdenticalTetrahedraPartitioned) {
  every_family_against_cgal(engine::Location::Walk, engine::Insertion::Flips,
                            engine::Method::Partitioned);
  every_family_against_cgal(engine::Location::Walk, engine::Insertion::Cavity,
                            engine::Method::Partitioned);
}

// The lock grid on 2 threads, 3 cells per axis, both insertions, the same sets.
TEST(CgalOracle, EveryFamilyIdenticalTetrahedraLockGrid) {
  every_family_against_cgal(engine::Location::Walk, engine::Insertion::Flips,
                            engine::Method::LockGrid);
  every_family_against_cgal(engine::Location::Walk, engine::Insertion::Cavity,
                            engine::Method::LockGrid);
}

// Star splaying (issue 12) against CGAL after each of its three uses, on every family with a
// tetrahedralization: burglary then --repair and --repair=flips-splay (2 and 4 threads, random
// delays while locks are held), the fast kernel then --repair, and dtlab repair (engine::repair)
// from the fast kernel's mesh and from nothing.
TEST(CgalOracle, EveryFamilyRepairedIdenticalTetrahedra) {
  int compared = 0;
  for (const std::string& family : generators::families()) {
    const auto pts = generators::generate(family, 300, 7).points;
    if (cgal_dimension(pts) < 3) continue;
    const auto cgal = cgal_delaunay(pts);
    for (const int threads : {2, 4}) {
      for (const auto repair : {engine::Repair::Splay, engine::Repair::FlipsThenSplay}) {
        engine::TriangulateOptions burglary;
        burglary.method = engine::Method::Burglary;
        burglary.threads = threads;
        burglary.stress = true;
        burglary.repair = repair;
        EXPECT_TRUE(same_tetrahedra(engine::triangulate(pts, burglary).tetrahedra, cgal))
            << family << " burglary " << threads << " + repair " << engine::to_string(repair);
      }
    }
    engine::TriangulateOptions fast;
    fast.kernel = engine::KernelKind::Fast;
    std::vector<engine::Tetrahedron> fast_mesh;
    try {
      fast_mesh = engine::triangulate(pts, fast).tetrahedra;
      fast.repair = engine::Repair::Splay;
      EXPECT_TRUE(same_tetrahedra(engine::triangulate(pts, fast).tetrahedra, cgal))
          << family << " fast + repair";
    } catch (const engine::TriangulationError& e) {
      // The fast kernel's own refusal (a first tetrahedron it sees as flat) leaves no mesh.
      EXPECT_NE(std::string(e.what()).find("flat under this kernel"), std::string::npos)
          << e.what();
    }
    engine::SplayStats stats;
    EXPECT_TRUE(same_tetrahedra(engine::repair(pts, fast_mesh, stats), cgal))
        << family << " dtlab repair of the fast kernel's mesh";
    EXPECT_TRUE(same_tetrahedra(engine::repair(pts, {}, stats), cgal))
        << family << " dtlab repair from no tetrahedra";
    ++compared;
  }
  EXPECT_GT(compared, 0);
}

}  // namespace
}  // namespace dtlab::test
