// A test of the engine's internals: it includes headers from engine/src (dtlab_internal_test).
// Star splaying (issue 12): a vertex's star, the repair of any tetrahedron list, and the local
// repair of the engine's mesh. The reference is the engine's own exact sequential result, the
// unique perturbed Delaunay tetrahedralization (cgal_oracle_test compares the repairs with CGAL).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <random>

#include "dtlab/engine/point_set_info.hpp"
#include "dtlab/engine/repair.hpp"
#include "dtlab/engine/triangulate.hpp"
#include "dtlab/engine/validator.hpp"
#include "dtlab/generators/generators.hpp"
#include "insertion/inserter.hpp"
#include "repair/splay_repair.hpp"
#include "repair/star_pieces.hpp"
#include "repair/vertex_star.hpp"
#include "repair/walked_mesh_stars.hpp"

namespace dtlab::test {
namespace {

using engine::Quad;
using engine::VertexId;
using predicates::Point3;

const char* const kFamilies[] = {
    "uniform",         "normal",     "cluster", "grid",    "sphere", "cospherical",
    "near-duplicates", "duplicates", "planes",  "lattice", "tiny",   "huge"};

// Offering every point to a vertex's star gives its star in the Delaunay tetrahedralization.
TEST(VertexStar, OfferingEveryPointGivesTheDelaunayStar) {
  for (const std::string family : {"uniform", "grid", "sphere", "cospherical"}) {
    const auto points = generators::generate(family, 300, 2).points;
    const auto delaunay = engine::triangulate(points, {}).tetrahedra;
    for (const VertexId v : {0U, 17U, 123U, 299U}) {
      // Three points not coplanar with v start the star.
      std::array<VertexId, 3> abc{};
      std::vector<std::uint32_t> order{v};
      for (VertexId w = 0; w < points.size(); ++w) {
        if (w != v) order.push_back(w);
      }
      const auto simplex = engine::find_simplex(points, order).simplex;
      ASSERT_TRUE(simplex.has_value());
      ASSERT_EQ((*simplex)[0], v);
      abc = {(*simplex)[1], (*simplex)[2], (*simplex)[3]};
      engine::VertexStar star;
      star.start(points, v, abc[0], abc[1], abc[2]);
      std::vector<Quad> removed;
      engine::StarScratch scratch;
      for (VertexId w = 0; w < points.size(); ++w) star.offer(points, w, removed, scratch);
      std::vector<engine::Tetrahedron> finite;
      for (const Quad& q : star.tetrahedra()) {
        EXPECT_NE(std::find(q.begin(), q.end(), v), q.end());
        if (std::find(q.begin(), q.end(), engine::kInfiniteVertex) == q.end()) {
          finite.push_back(q);
          EXPECT_GT(predicates::AdaptiveKernel::orient3d(points[q[0]], points[q[1]], points[q[2]],
                                                         points[q[3]]),
                    0);
        }
      }
      std::vector<engine::Tetrahedron> expected;
      for (const auto& t : delaunay) {
        if (std::find(t.begin(), t.end(), v) != t.end()) expected.push_back(t);
      }
      EXPECT_EQ(engine::canonical_tetrahedra(finite), engine::canonical_tetrahedra(expected))
          << family << " vertex " << v;
    }
  }
}

// From nothing, from garbage and from the Delaunay mesh itself: always the Delaunay mesh.
TEST(SplayTetrahedra, AnyStartGivesTheDelaunayMesh) {
  for (const std::string family : kFamilies) {
    const auto points = generators::generate(family, 250, 3).points;
    const auto expected = engine::canonical_tetrahedra(engine::triangulate(points, {}).tetrahedra);
    std::mt19937_64 rng(7);
    std::vector<engine::Tetrahedron> garbage;
    for (int i = 0; i < 300; ++i) {
      engine::Tetrahedron t{};
      for (auto& v : t) v = static_cast<VertexId>(rng() % points.size());
      garbage.push_back(t);  // repeated ids, inverted, overlapping: anything
    }
    for (const auto& [name, start] :
         {std::pair<std::string, std::vector<engine::Tetrahedron>>{"nothing", {}},
          {"garbage", garbage},
          {"delaunay", expected}}) {
      engine::SplayStats stats;
      const auto repaired = engine::repair(points, start, stats);
      EXPECT_EQ(engine::canonical_tetrahedra(repaired), expected) << family << " from " << name;
      EXPECT_TRUE(engine::validate(points, repaired).valid()) << family << " from " << name;
    }
  }
}

// The stars are built on several threads (StarSplayer::activate_all): the counts and the mesh
// are those of one thread, from garbage (points no tetrahedron uses: their near points come from
// the grid, built by whichever thread asks first) and from a broken mesh.
TEST(SplayTetrahedra, EveryThreadCountBuildsTheSameStars) {
  const auto points = generators::generate("near-duplicates", 3000, 4).points;
  std::mt19937_64 rng(11);
  std::vector<engine::Tetrahedron> garbage;
  for (int i = 0; i < 1500; ++i) {
    engine::Tetrahedron t{};
    for (auto& v : t) v = static_cast<VertexId>(rng() % points.size());
    garbage.push_back(t);
  }
  engine::TriangulateOptions fast;
  fast.kernel = engine::KernelKind::Fast;
  const auto broken = engine::triangulate(points, fast).tetrahedra;
  for (const auto& start : {garbage, broken}) {
    std::vector<engine::SplayStats> all_stats;
    std::vector<std::vector<engine::Tetrahedron>> results;
    std::vector<engine::Tetrahedron> repaired;
    for (const int threads : {1, 3}) {
      engine::SplayStats stats;
      repaired = engine::repair(points, start, stats, threads);
      results.push_back(engine::canonical_tetrahedra(repaired));
      all_stats.push_back(stats);
    }
    EXPECT_GT(all_stats[0].stars, 1000U);
    EXPECT_EQ(all_stats[0].stars, all_stats[1].stars);
    EXPECT_EQ(all_stats[0].offers, all_stats[1].offers);
    EXPECT_EQ(all_stats[0].changes, all_stats[1].changes);
    EXPECT_EQ(all_stats[0].bridges, all_stats[1].bridges);
    EXPECT_EQ(results[0], results[1]);
    const auto report = engine::validate(points, repaired);
    EXPECT_TRUE(report.is_perturbed_delaunay()) << report.json();
  }
}

// Stars that agree can fall apart into pieces: lone tetrahedra whose vertices meet no other
// input tetrahedron keep their stars to themselves, each piece the Delaunay mesh of its own
// vertices (a fuzzer found one: 4 points of 100 in a piece, 497 tetrahedra instead of 523). Each
// piece is bridged by its closest pair to the rest until one piece holds every vertex.
TEST(SplayTetrahedra, PiecesOfAgreeingStarsAreJoined) {
  for (const std::string family : {"uniform", "grid", "sphere", "cospherical"}) {
    const auto points = generators::generate(family, 300, 4).points;
    const auto delaunay = engine::triangulate(points, {}).tetrahedra;
    const auto expected = engine::canonical_tetrahedra(delaunay);
    // Three lone tetrahedra: Delaunay ones (so not flat), on disjoint vertices from 50 up (the
    // pool offered to stars that do not span 3D is the first points), chosen so that every other
    // vertex keeps an input tetrahedron (one left with none would look for near vertices). No
    // other input tetrahedron has their vertices, so no other star ever learns of them.
    std::vector<engine::Tetrahedron> lone;
    auto in_lone = [&](VertexId v) {
      return std::any_of(lone.begin(), lone.end(), [&](const auto& q) {
        return std::find(q.begin(), q.end(), v) != q.end();
      });
    };
    auto rest = [&] {
      std::vector<engine::Tetrahedron> kept;
      for (const auto& t : delaunay) {
        if (std::none_of(t.begin(), t.end(), in_lone)) kept.push_back(t);
      }
      return kept;
    };
    for (const auto& t : delaunay) {
      if (lone.size() == 3 || *std::min_element(t.begin(), t.end()) < 50 ||
          std::any_of(t.begin(), t.end(), in_lone)) {
        continue;
      }
      lone.push_back(t);
      std::vector<char> kept_vertex(points.size(), 0);
      for (const auto& k : rest()) {
        for (const VertexId v : k) kept_vertex[v] = 1;
      }
      for (VertexId v = 0; v < points.size(); ++v) {
        if (kept_vertex[v] == 0 && !in_lone(v)) {
          lone.pop_back();
          break;
        }
      }
    }
    ASSERT_EQ(lone.size(), 3u) << family;
    std::vector<engine::Tetrahedron> start = rest();
    for (const auto& q : lone) start.push_back(q);
    engine::SplayStats stats;
    const auto repaired = engine::repair(points, start, stats);
    EXPECT_GT(stats.bridges, 0u) << family;
    EXPECT_EQ(engine::canonical_tetrahedra(repaired), expected) << family;
    EXPECT_TRUE(engine::validate(points, repaired).valid()) << family;
  }
}

// The bridges are the true closest pairs across, against a brute force over every pair: pieces
// interleaved in space (blocks of a coarse grid), two halves (large pieces), a piece of one
// vertex, and many pieces of one vertex (where the searches' stopping rule decides).
TEST(StarPieces, ClosestPairsAcrossAreTheBruteForceOnes) {
  for (const std::string family : {"uniform", "cluster", "grid"}) {
    const auto points = generators::generate(family, 3000, 9).points;
    std::vector<VertexId> vertices;
    {
      std::vector<std::pair<std::array<double, 3>, VertexId>> seen;
      for (VertexId v = 0; v < points.size(); ++v) {
        seen.push_back({{points[v].x, points[v].y, points[v].z}, v});
      }
      std::sort(seen.begin(), seen.end());
      for (std::size_t i = 0; i < seen.size(); ++i) {
        if (i == 0 || seen[i].first != seen[i - 1].first) vertices.push_back(seen[i].second);
      }
      std::sort(vertices.begin(), vertices.end());
    }
    Point3 lo = points[vertices[0]];
    Point3 hi = lo;
    for (const VertexId v : vertices) {
      lo = {std::min(lo.x, points[v].x), std::min(lo.y, points[v].y), std::min(lo.z, points[v].z)};
      hi = {std::max(hi.x, points[v].x), std::max(hi.y, points[v].y), std::max(hi.z, points[v].z)};
    }
    auto block = [&](double x, double l, double h) {
      return h > l ? static_cast<int>(4 * (x - l) / (h - l)) : 0;
    };
    const std::vector<std::pair<std::string, std::function<int(VertexId)>>> labelings{
        {"blocks",
         [&](VertexId v) {
           const Point3& p = points[v];
           return (block(p.x, lo.x, hi.x) + 3 * block(p.y, lo.y, hi.y) +
                   7 * block(p.z, lo.z, hi.z)) %
                  5;
         }},
        {"halves", [&](VertexId v) { return points[v].x < (lo.x + hi.x) / 2 ? 0 : 1; }},
        {"one vertex", [&](VertexId v) { return v == vertices[vertices.size() / 2] ? 1 : 0; }},
        // Pieces of one vertex each, whose bridge is the vertex's nearest neighbour: a search that
        // stops a shell early misses it wherever it lies in the next shell.
        {"singletons", [&](VertexId v) { return v % 37 == 5 ? static_cast<int>(v) : -1; }}};
    for (const auto& [name, label] : labelings) {
      // A piece is named by its lowest vertex.
      std::map<int, VertexId> name_of;
      for (const VertexId v : vertices) name_of.emplace(label(v), v);
      std::vector<VertexId> piece(points.size(), engine::kInfiniteVertex);
      for (const VertexId v : vertices) piece[v] = name_of.at(label(v));
      const auto bridges = engine::closest_pairs_across(points, vertices, piece);
      ASSERT_EQ(bridges.size(), name_of.size() - 1) << family << " " << name;
      auto squared = [&](VertexId a, VertexId b) {
        const double dx = points[a].x - points[b].x;
        const double dy = points[a].y - points[b].y;
        const double dz = points[a].z - points[b].z;
        return dx * dx + dy * dy + dz * dz;
      };
      for (const auto& [x, y] : bridges) {
        ASSERT_NE(piece[x], piece[y]) << family << " " << name;
        double brute = std::numeric_limits<double>::infinity();
        for (const VertexId a : vertices) {
          if (piece[a] != piece[x]) continue;
          for (const VertexId b : vertices) {
            if (piece[b] != piece[x]) brute = std::min(brute, squared(a, b));
          }
        }
        EXPECT_EQ(squared(x, y), brute) << family << " " << name << " piece " << piece[x];
      }
    }
  }
}

// Two tetrahedra that meet at one vertex only, all seven points used: the validator calls the
// list mesh_consistent() (closed boundary, Euler characteristic 1, no overlap), but the star of
// the shared vertex falls apart into two fans that no walk joins, so the repair may not start
// from walks there. Its boundary is two spheres, it does not cover the hull, and the walk around
// the shared vertex finds half its tetrahedra: each of the local path's checks refuses it, so
// every vertex is splayed, and the result is the Delaunay mesh. (When only the walks' count was
// checked after mesh_consistent(), skipping that check made this case return a wrong mesh.)
TEST(SplayTetrahedra, ListsPinchedAtAVertexAreSplayedEverywhere) {
  const std::vector<Point3> points = {{0.01, 0.02, 0.03}, {1.0, 0.1, 0.2},   {1.1, 1.0, 0.05},
                                      {0.9, 0.15, 1.1},   {-1.0, 0.12, 0.3}, {-1.2, 1.1, 0.07},
                                      {-0.95, 0.2, 1.05}};
  auto positive = [&](engine::Tetrahedron t) {
    if (predicates::AdaptiveKernel::orient3d(points[t[0]], points[t[1]], points[t[2]],
                                             points[t[3]]) < 0) {
      std::swap(t[0], t[1]);
    }
    return t;
  };
  const std::vector<engine::Tetrahedron> pinched = {positive({0, 1, 2, 3}), positive({0, 4, 5, 6})};
  const engine::ValidationReport report = engine::validate(points, pinched);
  ASSERT_TRUE(report.mesh_consistent()) << report.json();  // what makes this case a trap
  engine::SplayStats stats;
  const auto repaired = engine::repair(points, pinched, stats);
  EXPECT_FALSE(stats.local);
  EXPECT_EQ(stats.stars, points.size());
  EXPECT_EQ(engine::canonical_tetrahedra(repaired),
            engine::canonical_tetrahedra(engine::triangulate(points, {}).tetrahedra));
}

// Equal points are one vertex of the repair: copies of generated points, and a point written with
// zeros of either sign (-0.0 == +0.0, though their bits differ).
TEST(SplayTetrahedra, EqualPointsAreOneVertex) {
  auto points = generators::generate("uniform", 60, 5).points;
  points.push_back({0.0, 0.0, 0.0});
  points.push_back({-0.0, 0.0, -0.0});
  points.push_back({0.0, -0.0, 0.0});
  points.push_back(points[3]);
  points.push_back(points[10]);
  const auto expected = engine::canonical_tetrahedra(engine::triangulate(points, {}).tetrahedra);
  engine::SplayStats stats;
  const auto repaired = engine::canonical_tetrahedra(engine::repair(points, {}, stats));
  EXPECT_EQ(repaired, expected);
  for (const auto& t : repaired) {
    for (const VertexId v : t) EXPECT_LE(v, 60U) << "a later copy of an equal point is a vertex";
  }
}

// Default options but for the location.
engine::TriangulateOptions located(engine::Location location) {
  engine::TriangulateOptions options;
  options.location = location;
  return options;
}

// The Delaunay mesh of `points` in the sequential engine (DAG mode unless asked, input order),
// and forced flips that break it: the broken meshes the local repair starts from. In walk mode
// dead slots are reused, so a vertex's lowest live tetrahedron can be any of its own.
struct BrokenMesh {
  engine::TriangulateOptions options;
  engine::TriangulationStats stats;
  engine::IncrementalDelaunay<predicates::AdaptiveKernel> dt;

  explicit BrokenMesh(const std::vector<Point3>& points,
                      engine::Location location = engine::Location::Dag)
      : options(located(location)), dt(points, options, stats) {
    std::vector<std::uint32_t> order(points.size());
    std::iota(order.begin(), order.end(), 0U);
    const auto first = *engine::find_simplex(points, order).simplex;
    dt.start(first[0], first[1], first[2], first[3]);
    for (const std::uint32_t v : order) {
      if (std::find(first.begin(), first.end(), v) == first.end()) dt.insert(v);
    }
  }
  // Flips `wanted` random faces (seeded), whatever the Delaunay test says; returns how many.
  // `interior`: only faces of tetrahedra whose neighbours and their neighbours are all finite, so
  // that every flip (S23, S32, S44) replaces finite tetrahedra by finite ones and the boundary
  // stays the hull's.
  int force_flips(int wanted, std::uint64_t seed, bool interior = false) {
    std::mt19937_64 rng(seed);
    int made = 0;
    for (int attempt = 0; made < wanted && attempt < 100000; ++attempt) {
      const auto t = static_cast<engine::TetId>(rng() % dt.mesh().tets.size());
      const int f = static_cast<int>(rng() % 4);
      if (!dt.mesh().tets.is_alive(t) || (interior && !finite_around(t, 2))) continue;
      made += dt.flip_face(t, f).empty() ? 0 : 1;
    }
    return made;
  }
  // Whether t and the tetrahedra up to `rings` faces away from it are finite.
  bool finite_around(engine::TetId t, int rings) {
    const engine::Tet& tet = dt.mesh().tets[t];
    if (tet.is_infinite()) return false;
    if (rings == 0) return true;
    return std::all_of(tet.neighbor.begin(), tet.neighbor.end(), [&](engine::FaceRef n) {
      return finite_around(engine::ref_tet(n), rings - 1);
    });
  }
};

// A list that is a consistent tetrahedralization (the engine's Delaunay mesh, and the same broken
// by forced flips) is repaired locally: from its non-Delaunay faces only, as burglary's mesh is,
// with few stars; the result is the Delaunay mesh, as splaying every vertex gives.
TEST(SplayTetrahedra, ConsistentListsAreRepairedLocally) {
  for (const std::string family : {"uniform", "grid", "cospherical"}) {
    const auto points = generators::generate(family, 3000, 6).points;
    const auto limit = static_cast<VertexId>(points.size());
    BrokenMesh broken(points);
    const auto delaunay = broken.dt.finite_tetrahedra(limit);
    const auto expected = engine::canonical_tetrahedra(delaunay);
    engine::SplayStats clean;
    EXPECT_EQ(engine::canonical_tetrahedra(engine::repair(points, delaunay, clean)), expected)
        << family;
    EXPECT_TRUE(clean.local) << family;
    EXPECT_EQ(clean.stars, 0U) << family;
    ASSERT_EQ(broken.force_flips(40, 9, true), 40) << family;
    const auto damaged = broken.dt.finite_tetrahedra(limit);
    ASSERT_TRUE(engine::validate(points, damaged).consistent()) << family;  // the hull kept
    engine::SplayStats local;
    EXPECT_EQ(engine::canonical_tetrahedra(engine::repair(points, damaged, local, 2)), expected)
        << family;
    EXPECT_TRUE(local.local) << family;
    EXPECT_GT(local.non_delaunay_faces, 0U) << family;
    EXPECT_GT(local.stars, 0U) << family;
    EXPECT_LT(local.stars, points.size() / 4) << family;
  }
}

// The scan and the stars' building on several threads find what they find on one: the same
// broken mesh (same forced flips), repaired with 1 and with 3 threads, gives the same counts,
// stars and tetrahedra.
TEST(SplaySharedMesh, ParallelScanFindsWhatOneThreadFinds) {
  const auto points = generators::generate("uniform", 6000, 8).points;
  const auto limit = static_cast<VertexId>(points.size());
  std::vector<std::vector<engine::Tetrahedron>> results;
  std::vector<engine::SplayStats> all_stats;
  for (const int threads : {1, 3}) {
    BrokenMesh broken(points);
    auto& dt = broken.dt;
    ASSERT_EQ(broken.force_flips(40, 11), 40);
    engine::SplayStats stats;
    engine::splay_shared_mesh(dt.mesh(), {}, true, threads, stats);
    EXPECT_EQ(stats.scan_threads, static_cast<std::uint64_t>(threads));
    EXPECT_TRUE(stats.stars_walked);  // the walks' per-thread scratch is what runs here
    EXPECT_TRUE(engine::validate(points, dt.finite_tetrahedra(limit)).valid()) << threads;
    results.push_back(engine::canonical_tetrahedra(dt.finite_tetrahedra(limit)));
    all_stats.push_back(stats);
  }
  EXPECT_GT(all_stats[0].non_delaunay_faces, 0U);
  EXPECT_EQ(all_stats[0].non_delaunay_faces, all_stats[1].non_delaunay_faces);
  EXPECT_EQ(all_stats[0].seeds, all_stats[1].seeds);
  EXPECT_GT(all_stats[0].seeds, 64U);  // enough for the stars to be built on several threads
  EXPECT_EQ(all_stats[0].stars, all_stats[1].stars);
  EXPECT_EQ(all_stats[0].offers, all_stats[1].offers);
  EXPECT_EQ(all_stats[0].changes, all_stats[1].changes);
  EXPECT_EQ(results[0], results[1]);
}

// Burglary's post-check hands the faces its validation rejected to the repair instead of a second
// scan. On the same damage (forced flips, interior and hull faces; ties on the grid and the
// cospherical points, where only the perturbation rejects a face), the validator's findings and
// the exact scan's must be the same faces and seeds, and give the same stars and mesh.
TEST(SplaySharedMesh, ValidatedFindingsAreTheScansFindings) {
  // What the damage held, over the families: faces only the perturbation rejects, and rejected
  // boundary edges (the infinite tetrahedra's faces), so that both kinds were compared.
  std::uint64_t rejected_ties = 0;
  std::uint64_t rejected_boundary_edges = 0;
  for (const std::string family : {"uniform", "grid", "cospherical"}) {
    const auto points = generators::generate(family, 3000, 3).points;
    const auto limit = static_cast<VertexId>(points.size());
    std::vector<engine::SplayStats> all_stats;
    std::vector<std::vector<engine::Tetrahedron>> results;
    for (const bool from_validation : {false, true}) {
      BrokenMesh broken(points);
      ASSERT_EQ(broken.force_flips(60, 21), 60) << family;
      const engine::ValidationReport report = engine::validate(
          points, broken.dt.finite_tetrahedra(limit), engine::ValidateWith::Adaptive, 1, true);
      ASSERT_TRUE(report.mesh_consistent()) << family << report.json();
      ASSERT_GT(report.perturbed_violations, 0U) << family;
      if (from_validation) {
        rejected_ties += report.tied_faces_against_perturbation;
        rejected_boundary_edges +=
            report.reflex_boundary_edges + report.flat_boundary_edges_against_perturbation;
      }
      // No equal points here: the output's names are the mesh's.
      const engine::ValidatedFindings found = engine::validated_findings(report, points.size(), {});
      ASSERT_EQ(found.vertices.size(), report.perturbed_violation_vertices.size());
      engine::SplayStats stats;
      engine::splay_shared_mesh(broken.dt.mesh(), {}, true, 2, stats,
                                from_validation ? &found : nullptr);
      EXPECT_EQ(stats.found_by_post_check, from_validation) << family;
      EXPECT_TRUE(
          engine::validate(points, broken.dt.finite_tetrahedra(limit)).is_perturbed_delaunay())
          << family;
      results.push_back(engine::canonical_tetrahedra(broken.dt.finite_tetrahedra(limit)));
      all_stats.push_back(stats);
    }
    EXPECT_EQ(all_stats[0].non_delaunay_faces, all_stats[1].non_delaunay_faces) << family;
    EXPECT_EQ(all_stats[0].seeds, all_stats[1].seeds) << family;
    EXPECT_EQ(all_stats[0].stars, all_stats[1].stars) << family;
    EXPECT_EQ(all_stats[0].tetrahedra_created, all_stats[1].tetrahedra_created) << family;
    EXPECT_EQ(results[0], results[1]) << family;
  }
  EXPECT_GT(rejected_ties, 0U);
  EXPECT_GT(rejected_boundary_edges, 0U);
}

// --repair=flips-splay: exact Lawson flips from the damaged faces first, star splaying from the
// faces they leave. The flips are stopped after 0, 5 and any number of flips, so the stars start
// from everything, from what a few flips left and from what all of them left: each time the
// unique mesh. With no flip, the faces handed on are the scan's, each once, and the stars those of
// splaying alone. Both locations: in walk mode the flips kill tetrahedra where the walks around
// the seeds started (slots reused), so the walks must start from the flips' new ones.
TEST(SplaySharedMesh, FlipsFirstHandTheFacesTheyLeaveToTheStars) {
  constexpr std::uint64_t kAll = std::numeric_limits<std::uint64_t>::max();
  std::uint64_t walk_starts_moved = 0;  // in walk mode
  for (const auto location : {engine::Location::Dag, engine::Location::Walk}) {
    for (const std::string family : {"uniform", "grid", "cospherical"}) {
      const auto points = generators::generate(family, 3000, 4).points;
      const auto limit = static_cast<VertexId>(points.size());
      BrokenMesh clean(points, location);
      const auto expected = engine::canonical_tetrahedra(clean.dt.finite_tetrahedra(limit));
      engine::SplayStats alone;  // splaying alone, from the same damage
      {
        BrokenMesh broken(points, location);
        ASSERT_EQ(broken.force_flips(60, 31), 60) << family;
        engine::splay_shared_mesh(broken.dt.mesh(), {}, true, 2, alone);
        ASSERT_EQ(engine::canonical_tetrahedra(broken.dt.finite_tetrahedra(limit)), expected)
            << family;
        EXPECT_FALSE(alone.flipped);
      }
      for (const std::uint64_t max_flips : {std::uint64_t{0}, std::uint64_t{5}, kAll}) {
        const std::string what = family + (location == engine::Location::Walk ? " walk" : " dag") +
                                 " max flips " + std::to_string(max_flips);
        BrokenMesh broken(points, location);
        ASSERT_EQ(broken.force_flips(60, 31), 60) << what;
        engine::TriangulationStats flip_stats;
        engine::NoSync no_sync;
        const engine::FlipPass flips = [&](const std::vector<engine::TetId>& at,
                                           std::vector<engine::TetId>& created,
                                           std::vector<Quad>& left) {
          engine::LawsonPass<predicates::AdaptiveKernel, engine::NoSync> lawson(
              broken.dt.mesh(), broken.options, flip_stats, no_sync);
          return lawson.flip_from(at, created, left, max_flips);
        };
        engine::SplayStats stats;
        engine::splay_shared_mesh(broken.dt.mesh(), {}, true, 2, stats, nullptr, &flips);
        EXPECT_TRUE(stats.flipped) << what;
        EXPECT_TRUE(
            engine::validate(points, broken.dt.finite_tetrahedra(limit)).is_perturbed_delaunay())
            << what;
        EXPECT_EQ(engine::canonical_tetrahedra(broken.dt.finite_tetrahedra(limit)), expected)
            << what;
        if (max_flips == 0) {
          EXPECT_EQ(stats.flips, 0U) << what;
          EXPECT_EQ(stats.faces_left, alone.non_delaunay_faces) << what;
          EXPECT_EQ(stats.seeds, alone.seeds) << what;
          EXPECT_EQ(stats.stars, alone.stars) << what;
        } else if (max_flips == 5) {
          EXPECT_EQ(stats.flips, 5U) << what;
          EXPECT_GT(stats.faces_left, 0U) << what;
          EXPECT_GT(stats.stars, 0U) << what;
        } else {
          // The forced flips are undone by flips where they can be: fewer faces left to the stars.
          EXPECT_GT(stats.flips, 0U) << what;
          EXPECT_LT(stats.faces_left, alone.non_delaunay_faces) << what;
          EXPECT_LT(stats.stars, alone.stars) << what;
        }
        if (location == engine::Location::Walk) walk_starts_moved += stats.walk_starts_moved;
      }
    }
  }
  // The flips killed some walk starts (slots reused in walk mode), so the walks from the new ones
  // ran: with the starts left dead they throw.
  EXPECT_GT(walk_starts_moved, 0U);
}

// The findings renamed to the mesh's vertices: the output names each set of equal points by its
// lowest index, the mesh by the point that was inserted; other vertices keep their ids.
TEST(SplaySharedMesh, ValidatedFindingsAreRenamedToTheInsertedPoints) {
  engine::ValidationReport report;
  report.perturbed_violations = 2;
  // Points 1, 4 and 6 are equal and 6 was inserted (the output calls it 1); points 2 and 5 are
  // equal and 2 was inserted (the output calls it 2); the others are alone.
  report.perturbed_violation_vertices = {0, 1, 2, 3, 1, 7, 2, 0};
  const std::vector<std::pair<VertexId, VertexId>> duplicates = {{1, 6}, {4, 6}, {5, 2}};
  const engine::ValidatedFindings found = engine::validated_findings(report, 8, duplicates);
  EXPECT_EQ(found.rejected_faces, 2U);
  EXPECT_EQ(found.vertices, (std::vector<VertexId>{0, 6, 2, 3, 6, 7, 2, 0}));
}

// The local repair of the engine's mesh: forced flips break it; splaying from the broken faces
// gives back the Delaunay mesh and touches only stars near them.
TEST(SplaySharedMesh, InjectedFlipsAreRepairedLocally) {
  const auto points = generators::generate("uniform", 2000, 5).points;
  BrokenMesh broken(points);
  auto& dt = broken.dt;
  const auto limit = static_cast<VertexId>(points.size());
  const auto expected = engine::canonical_tetrahedra(dt.finite_tetrahedra(limit));
  ASSERT_EQ(broken.force_flips(20, 3), 20);
  ASSERT_GT(engine::validate(points, dt.finite_tetrahedra(limit)).non_delaunay_faces, 0U);
  engine::SplayStats stats;
  engine::splay_shared_mesh(dt.mesh(), {}, true, 1, stats);
  EXPECT_GT(stats.non_delaunay_faces, 0U);
  EXPECT_EQ(engine::canonical_tetrahedra(dt.finite_tetrahedra(limit)), expected);
  EXPECT_TRUE(engine::validate(points, dt.finite_tetrahedra(limit)).valid());
  // Local: 20 flips touch a few dozen vertices, not the 2000.
  EXPECT_LT(stats.stars, 400U) << stats.stars;
  EXPECT_GT(stats.tetrahedra_created, 0U);
  // A Delaunay mesh is left alone: nothing found, nothing splayed.
  engine::SplayStats again;
  engine::splay_shared_mesh(dt.mesh(), {}, true, 2, again);
  EXPECT_EQ(again.non_delaunay_faces, 0U);
  EXPECT_EQ(again.stars, 0U);
  EXPECT_EQ(engine::canonical_tetrahedra(dt.finite_tetrahedra(limit)), expected);
}

// The two sources of the mesh's stars: walks around each vertex (an exactly built mesh) and
// incidence lists of the whole mesh (any mesh). The same damage, repaired from each, gives the
// same counts and the same Delaunay mesh; every star the walk finds is the listed one.
TEST(SplaySharedMesh, WalkedStarsAreTheListedStars) {
  const auto points = generators::generate("cospherical", 3000, 2).points;
  const auto limit = static_cast<VertexId>(points.size());
  std::vector<engine::SplayStats> all_stats;
  std::vector<std::vector<engine::Tetrahedron>> results;
  for (const bool exact_mesh : {true, false}) {
    BrokenMesh broken(points);
    ASSERT_EQ(broken.force_flips(30, 9), 30);
    engine::SplayStats stats;
    engine::splay_shared_mesh(broken.dt.mesh(), {}, exact_mesh, 2, stats);
    EXPECT_EQ(stats.stars_walked, exact_mesh);
    EXPECT_TRUE(engine::validate(points, broken.dt.finite_tetrahedra(limit)).valid());
    results.push_back(engine::canonical_tetrahedra(broken.dt.finite_tetrahedra(limit)));
    all_stats.push_back(stats);
  }
  EXPECT_GT(all_stats[0].non_delaunay_faces, 0U);
  EXPECT_EQ(all_stats[0].non_delaunay_faces, all_stats[1].non_delaunay_faces);
  EXPECT_EQ(all_stats[0].seeds, all_stats[1].seeds);
  EXPECT_EQ(results[0], results[1]);

  // Star by star, on a Delaunay mesh: the walk finds each vertex's tetrahedra, the listed ones.
  BrokenMesh mesh(points);
  const engine::SharedMesh& shared = mesh.dt.mesh();
  std::vector<engine::TetId> lowest(points.size(), engine::kNoTet);
  std::vector<std::vector<Quad>> listed(points.size());
  for (engine::TetId t = 0; t < shared.tets.size(); ++t) {
    if (!shared.tets.is_alive(t)) continue;
    for (const VertexId v : shared.tets[t].vertex) {
      if (v == engine::kInfiniteVertex) continue;
      lowest[v] = std::min(lowest[v], t);
      listed[v].push_back(shared.tets[t].vertex);
    }
  }
  const engine::WalkedMeshStars walked(shared, lowest);
  std::vector<Quad> found;
  for (VertexId v = 0; v < points.size(); ++v) {
    walked.tetrahedra_of(v, found);
    std::sort(found.begin(), found.end());
    std::sort(listed[v].begin(), listed[v].end());
    ASSERT_EQ(found, listed[v]) << "vertex " << v;
  }
}

// The walk's visited set: membership across growth, and a clear that forgets everything.
TEST(SplaySharedMesh, TetIdSetHoldsWhatWasInserted) {
  engine::TetIdSet set;
  for (int round = 0; round < 2; ++round) {
    for (engine::TetId t = 0; t < 5000; t += 3) EXPECT_TRUE(set.insert(t * 7919U)) << t;
    for (engine::TetId t = 0; t < 5000; ++t) EXPECT_EQ(set.insert(t * 7919U), t % 3 != 0) << t;
    set.clear();
  }
}

// Burglary's live marks are seeds only where the scan found damage: on an exactly built mesh that
// the scan proves Delaunay they are counted and left alone; with damage (or on a mesh an inexact
// kernel built, whose clean scan proves nothing) their vertices are splayed too.
TEST(SplaySharedMesh, MarksAreSeedsOnlyWhereTheScanFoundDamage) {
  const auto points = generators::generate("uniform", 2000, 6).points;
  const auto limit = static_cast<VertexId>(points.size());
  auto live_tetrahedra = [](const engine::SharedMesh& mesh, std::size_t wanted) {
    std::vector<engine::TetId> found;
    for (engine::TetId t = 0; t < mesh.tets.size() && found.size() < wanted; t += 7) {
      if (mesh.tets.is_alive(t)) found.push_back(t);
    }
    return found;
  };
  {
    BrokenMesh clean(points);
    const auto expected = engine::canonical_tetrahedra(clean.dt.finite_tetrahedra(limit));
    const auto marks = live_tetrahedra(clean.dt.mesh(), 30);
    ASSERT_EQ(marks.size(), 30U);
    engine::SplayStats proven;
    engine::splay_shared_mesh(clean.dt.mesh(), marks, true, 1, proven);
    EXPECT_EQ(proven.live_marks, 30U);
    EXPECT_FALSE(proven.marks_seeded);
    EXPECT_EQ(proven.seeds, 0U);
    EXPECT_EQ(proven.stars, 0U);
    engine::SplayStats inexact;
    engine::splay_shared_mesh(clean.dt.mesh(), marks, false, 1, inexact);
    EXPECT_TRUE(inexact.marks_seeded);
    EXPECT_GT(inexact.seeds, 0U);
    EXPECT_EQ(engine::canonical_tetrahedra(clean.dt.finite_tetrahedra(limit)), expected);
  }
  // The same damage (same forced flips) repaired without and with the marks: with them, more
  // seeds, and the same Delaunay mesh.
  std::vector<engine::SplayStats> damaged;
  for (const bool with_marks : {false, true}) {
    BrokenMesh broken(points);
    const auto expected = engine::canonical_tetrahedra(broken.dt.finite_tetrahedra(limit));
    ASSERT_EQ(broken.force_flips(5, 4), 5);
    const auto marks = live_tetrahedra(broken.dt.mesh(), 30);
    engine::SplayStats stats;
    engine::splay_shared_mesh(broken.dt.mesh(), with_marks ? marks : std::vector<engine::TetId>{},
                              true, 1, stats);
    EXPECT_GT(stats.non_delaunay_faces, 0U);
    EXPECT_EQ(engine::canonical_tetrahedra(broken.dt.finite_tetrahedra(limit)), expected);
    damaged.push_back(stats);
  }
  EXPECT_FALSE(damaged[0].marks_seeded);
  EXPECT_TRUE(damaged[1].marks_seeded);
  EXPECT_EQ(damaged[1].live_marks, 30U);
  EXPECT_EQ(damaged[0].non_delaunay_faces, damaged[1].non_delaunay_faces);
  EXPECT_GT(damaged[1].seeds, damaged[0].seeds);
}

// --repair after the fast kernel, every method: the exact Delaunay mesh on every family, the
// families where the fast kernel breaks the mesh included (runs whose exact scan found something
// to repair are counted and required, and the refusals are few).
TEST(SplayRepair, FastKernelThenRepairGivesTheDelaunayMesh) {
  int runs = 0;
  int repaired = 0;  // the fast kernel's mesh was broken: non-Delaunay, bad or missing vertices
  int refused = 0;
  for (const std::string family : kFamilies) {
    const auto points = generators::generate(family, 1500, 4).points;
    const auto expected = engine::canonical_tetrahedra(engine::triangulate(points, {}).tetrahedra);
    for (const auto method : {engine::Method::Sequential, engine::Method::OptimisticDetect,
                              engine::Method::Burglary, engine::Method::Batch}) {
      engine::TriangulateOptions options;
      options.kernel = engine::KernelKind::Fast;
      options.method = method;
      options.threads = method == engine::Method::Sequential ? 1 : 2;
      options.repair = engine::Repair::Splay;
      const std::string what = family + " " + engine::to_string(method);
      engine::Triangulation result;
      try {
        result = engine::triangulate(points, options);
      } catch (const engine::TriangulationError& e) {
        // The fast kernel's own refusal (a first tetrahedron it sees as flat) is allowed.
        EXPECT_NE(std::string(e.what()).find("flat under this kernel"), std::string::npos)
            << what << ": " << e.what();
        ++refused;
        continue;
      }
      ++runs;
      const engine::SplayStats& splay = result.stats.splay;
      EXPECT_TRUE(splay.done) << what;
      EXPECT_EQ(engine::canonical_tetrahedra(result.tetrahedra), expected) << what;
      if (splay.non_delaunay_faces + splay.bad_tetrahedra + splay.reflex_hull_vertices +
              splay.missing_vertices >
          0) {
        ++repaired;
      }
    }
  }
  std::printf("fast kernel then star splaying: %d runs, %d with a broken mesh, %d refused\n", runs,
              repaired, refused);
  EXPECT_GE(repaired, 3);
  EXPECT_LE(refused, runs / 4);
}

}  // namespace
}  // namespace dtlab::test
