// A test of the engine's internals: it includes headers from engine/src (dtlab_internal_test).
// The walk mode (--location walk): its insertion order (a Hilbert curve inside BRIO rounds), and
// its result, which must be the same unique tetrahedralization as the DAG mode's for every kernel
// that is exact, on every generator family, with the dead slots reused.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <numeric>
#include <string>
#include <vector>

#include "dtlab/engine/triangulate.hpp"
#include "dtlab/engine/validator.hpp"
#include "dtlab/generators/generators.hpp"
#include "location/insertion_order.hpp"

namespace dtlab::test {
namespace {

using engine::KernelKind;
using engine::Location;

// The curve visits every cell of the 2^bits grid once, and consecutive cells share a face.
TEST(InsertionOrder, HilbertKeysWalkTheGridThroughFaces) {
  for (unsigned bits = 1; bits <= 6; ++bits) {
    const std::uint32_t side = 1u << bits;
    std::vector<std::array<std::uint32_t, 3>> by_key(static_cast<std::size_t>(side) * side * side,
                                                     {side, side, side});
    for (std::uint32_t x = 0; x < side; ++x) {
      for (std::uint32_t y = 0; y < side; ++y) {
        for (std::uint32_t z = 0; z < side; ++z) {
          const std::uint64_t key = engine::hilbert_key(x, y, z, bits);
          ASSERT_LT(key, by_key.size()) << bits;
          EXPECT_EQ(by_key[key][0], side) << "key " << key << " given twice, bits " << bits;
          by_key[key] = {x, y, z};
        }
      }
    }
    for (std::size_t k = 1; k < by_key.size(); ++k) {
      int distance = 0;
      for (int a = 0; a < 3; ++a) {
        distance += std::abs(static_cast<int>(by_key[k][a]) - static_cast<int>(by_key[k - 1][a]));
      }
      EXPECT_EQ(distance, 1) << "keys " << k - 1 << " and " << k << ", bits " << bits;
    }
  }
}

// The curve on a coarser grid is the finer curve's prefix: the key of a cell's coarse cell (its
// coordinates shifted right) is its key shifted right by three bits a level. The automaton's
// derivation rests on it (hilbert_curve.hpp).
TEST(InsertionOrder, HilbertKeyOnFewerBitsIsThePrefixOfTheFinerKey) {
  for (unsigned bits = 2; bits <= 10; ++bits) {
    for (unsigned dropped = 1; dropped < bits; ++dropped) {
      for (std::uint32_t i = 0; i < 4000; ++i) {
        // Cells spread through the grid (a multiplicative hash of i per axis).
        const std::uint32_t mask = (1u << bits) - 1;
        const std::uint32_t x = (i * 2654435761u >> 7) & mask;
        const std::uint32_t y = (i * 2246822519u >> 9) & mask;
        const std::uint32_t z = (i * 3266489917u >> 11) & mask;
        ASSERT_EQ(engine::hilbert_key_by_transforms(x, y, z, bits) >> (3 * dropped),
                  engine::hilbert_key_by_transforms(x >> dropped, y >> dropped, z >> dropped,
                                                    bits - dropped))
            << x << " " << y << " " << z << ", bits " << bits << ", dropped " << dropped;
      }
    }
  }
}

// The automaton derived from the definition gives the definition's keys: on every cell of the
// grids up to 64^3, and on cells spread through the finer grids up to the walk mode's 2^21.
TEST(InsertionOrder, HilbertAutomatonGivesTheDefinitionsKeys) {
  EXPECT_EQ(engine::kHilbertStates.states(), 24);  // the curve's orientations
  for (unsigned bits = 1; bits <= 6; ++bits) {
    const std::uint32_t side = 1u << bits;
    for (std::uint32_t x = 0; x < side; ++x) {
      for (std::uint32_t y = 0; y < side; ++y) {
        for (std::uint32_t z = 0; z < side; ++z) {
          ASSERT_EQ(engine::hilbert_key(x, y, z, bits),
                    engine::hilbert_key_by_transforms(x, y, z, bits))
              << x << " " << y << " " << z << ", bits " << bits;
        }
      }
    }
  }
  for (unsigned bits = 7; bits <= engine::kHilbertBits; ++bits) {
    const std::uint32_t mask = (1u << bits) - 1;
    for (std::uint32_t i = 0; i < 20000; ++i) {
      const std::uint32_t x = (i * 2654435761u >> 3) & mask;
      const std::uint32_t y = (i * 2246822519u >> 5) & mask;
      const std::uint32_t z = (i * 3266489917u >> 1) & mask;
      ASSERT_EQ(engine::hilbert_key(x, y, z, bits),
                engine::hilbert_key_by_transforms(x, y, z, bits))
          << x << " " << y << " " << z << ", bits " << bits;
    }
    // The grid's corners and the cells beside its middle, where every level's bit changes.
    for (const std::uint32_t c : {0u, mask, mask / 2, mask / 2 + 1}) {
      ASSERT_EQ(engine::hilbert_key(c, mask - c, c, bits),
                engine::hilbert_key_by_transforms(c, mask - c, c, bits));
    }
  }
}

// The sort along the curve is stable: equal points (equal keys) stay in the random order, so the
// order depends on the seed and the points alone.
TEST(InsertionOrder, EqualKeysKeepTheRandomOrder) {
  const auto points = generators::generate("duplicates", 6000, 2).points;
  const auto random = engine::random_order(points.size(), 5);
  std::vector<std::size_t> position(points.size());
  for (std::size_t i = 0; i < random.size(); ++i) position[random[i]] = i;
  auto brio = random;
  engine::brio_hilbert_order(points, brio);
  std::size_t ties = 0;
  for (std::size_t i = 1; i < brio.size(); ++i) {
    const bool same_round = (i >= points.size() / 2) == (i - 1 >= points.size() / 2);
    if (same_round && points[brio[i]] == points[brio[i - 1]]) {
      ++ties;
      EXPECT_LT(position[brio[i - 1]], position[brio[i]]) << i;
    }
  }
  EXPECT_GT(ties, 100u);
}

// BRIO keeps the rounds of the random order (as sets) and sorts each along the curve.
TEST(InsertionOrder, BrioRoundsAreTheRandomOrdersHalvesSortedAlongTheCurve) {
  const auto points = generators::generate("uniform", 5000, 4).points;
  const auto random = engine::random_order(points.size(), 7);
  auto brio = random;
  engine::brio_hilbert_order(points, brio);
  std::vector<std::size_t> ends{points.size()};
  while (ends.back() > engine::kFirstRound) ends.push_back(ends.back() / 2);
  ends.push_back(0);
  std::reverse(ends.begin(), ends.end());
  for (std::size_t r = 0; r + 1 < ends.size(); ++r) {
    std::vector<std::uint32_t> a(random.begin() + static_cast<std::ptrdiff_t>(ends[r]),
                                 random.begin() + static_cast<std::ptrdiff_t>(ends[r + 1]));
    std::vector<std::uint32_t> b(brio.begin() + static_cast<std::ptrdiff_t>(ends[r]),
                                 brio.begin() + static_cast<std::ptrdiff_t>(ends[r + 1]));
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b) << "round " << r;
  }
  // Along the curve consecutive points are close: the mean step of the last round is far below
  // the random order's (about 0.5 of the unit cube for uniform points).
  auto mean_step = [&](const std::vector<std::uint32_t>& order) {
    double sum = 0;
    for (std::size_t i = points.size() / 2 + 1; i < points.size(); ++i) {
      const auto& p = points[order[i]];
      const auto& q = points[order[i - 1]];
      sum += std::sqrt((p.x - q.x) * (p.x - q.x) + (p.y - q.y) * (p.y - q.y) +
                       (p.z - q.z) * (p.z - q.z));
    }
    return sum / static_cast<double>(points.size() / 2 - 1);
  };
  EXPECT_LT(mean_step(brio), 0.2 * mean_step(random));
  auto again = random;
  engine::brio_hilbert_order(points, again);
  EXPECT_EQ(again, brio);
}

// The threads that share the keys and the rounds' sorts change nothing: on rounds large enough to
// be split (100,000 points: the last rounds have 50,000 and 25,000), with equal points among
// them, the order is the one-thread order.
TEST(InsertionOrder, TheOrderDoesNotDependOnTheThreadCount) {
  for (const std::string family : {"uniform", "duplicates", "grid"}) {
    const auto points = generators::generate(family, 100000, 3).points;
    const auto random = engine::random_order(points.size(), 11);
    auto one = random;
    engine::brio_hilbert_order(points, one, 1);
    for (const int threads : {2, 3, 8}) {
      auto several = random;
      engine::brio_hilbert_order(points, several, threads);
      EXPECT_EQ(several, one) << family << " " << threads;
    }
  }
}

// The driver hands the BRIO order the curve's cube of all the points, read in their own order
// (beside the shuffle) instead of in the random order: the same order, also with negative zeros
// on the box's faces. And the frame given is the one used: a moved cube gives another order.
TEST(InsertionOrder, TheInputsFrameGivesTheSameOrder) {
  for (const std::string family : {"uniform", "duplicates", "grid"}) {
    auto points = generators::generate(family, 20000, 5).points;
    for (std::size_t i = 0; i < points.size(); i += 97) points[i].x = i % 2 == 0 ? 0.0 : -0.0;
    const auto random = engine::random_order(points.size(), 13);
    auto found = random;
    engine::brio_hilbert_order(points, found, 2);
    for (const int threads : {1, 2}) {
      auto given = random;
      const engine::HilbertFrame frame = engine::hilbert_frame(points, points.size(), threads);
      engine::brio_hilbert_order(points, given, threads, &frame);
      EXPECT_EQ(given, found) << family << " " << threads;
    }
    auto other = random;
    engine::HilbertFrame moved = engine::hilbert_frame(points, points.size());
    moved.lo.x -= moved.extent / 3;
    engine::brio_hilbert_order(points, other, 2, &moved);
    EXPECT_NE(other, found) << family;
  }
}

// Every family, every exact kernel: the walk mode gives the DAG mode's tetrahedra, never needs
// its fallback, and keeps no DAG: the store holds about the live tetrahedra, not the history.
TEST(WalkMode, EveryFamilyEveryExactKernelGivesTheDagModesMesh) {
  int compared = 0;
  for (const std::string& family : generators::families()) {
    const auto points = generators::generate(family, 1500, 3).points;
    engine::TriangulateOptions dag;
    dag.seed = 5;
    std::vector<engine::Tetrahedron> expected;
    try {
      expected = engine::canonical_tetrahedra(engine::triangulate(points, dag).tetrahedra);
    } catch (const engine::TriangulationError&) {
      engine::TriangulateOptions walk = dag;
      walk.location = Location::Walk;
      EXPECT_THROW(engine::triangulate(points, walk), engine::TriangulationError) << family;
      continue;
    }
    for (const KernelKind kernel :
         {KernelKind::Adaptive, KernelKind::Filtered, KernelKind::Exact}) {
      engine::TriangulateOptions walk = dag;
      walk.location = Location::Walk;
      walk.kernel = kernel;
      const auto result = engine::triangulate(points, walk);
      const std::string what = family + " " + engine::to_string(kernel);
      EXPECT_EQ(engine::canonical_tetrahedra(result.tetrahedra), expected) << what;
      EXPECT_EQ(result.stats.walk_fallbacks, 0u) << what;
      EXPECT_EQ(result.stats.dag_nodes, 0u) << what;
      EXPECT_GT(result.stats.location_steps, 0u) << what;
      // Live finite and infinite tetrahedra, plus at most one run of fresh slots and the free
      // slots of the largest insertion; a DAG would hold several times the tetrahedra.
      EXPECT_LT(result.stats.store_slots, 2 * result.tetrahedra.size() + 200) << what;
      ++compared;
    }
  }
  EXPECT_GT(compared, 30);
}

// The paper's auxiliary tetrahedron works the same way in walk mode.
TEST(WalkMode, AuxiliaryTetrahedronGivesTheDagModesMesh) {
  const auto points = generators::generate("uniform", 3000, 2).points;
  engine::TriangulateOptions dag;
  dag.bounding = engine::Bounding::AuxTet;
  engine::TriangulateOptions walk = dag;
  walk.location = Location::Walk;
  const auto a = engine::triangulate(points, dag);
  const auto b = engine::triangulate(points, walk);
  EXPECT_EQ(engine::canonical_tetrahedra(b.tetrahedra), engine::canonical_tetrahedra(a.tetrahedra));
  EXPECT_EQ(b.stats.hull_tetrahedra_lost, a.stats.hull_tetrahedra_lost);
}

// The fast kernel walks too; on exactly representable, non-degenerate input it is right, and on
// any input it ends (its walk may cycle: then it falls back to testing every tetrahedron).
TEST(WalkMode, FastKernelEndsAndIsRightWhereItsArithmeticIs) {
  const auto points = generators::generate("uniform", 3000, 6).points;
  engine::TriangulateOptions walk;
  walk.location = Location::Walk;
  walk.kernel = KernelKind::Fast;
  const auto result = engine::triangulate(points, walk);
  EXPECT_TRUE(engine::validate(points, result.tetrahedra).valid());
  for (const std::string family : {"grid", "cospherical", "near-duplicates"}) {
    const auto hard = generators::generate(family, 2000, 6).points;
    const auto r = engine::triangulate(hard, walk);
    EXPECT_EQ(r.stats.inserted + r.stats.duplicates + r.stats.abandoned_insertions, hard.size())
        << family;
  }
}

}  // namespace
}  // namespace dtlab::test
