// The lock-grid method (engine/src/methods/lock_grid.hpp): its grid, its wait-or-give-up rule,
// and whole runs that must wait and give up and still give the unique tetrahedralization.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "dtlab/engine/methods.hpp"
#include "dtlab/engine/triangulate.hpp"
#include "dtlab/generators/generators.hpp"
#include "methods/lock_grid.hpp"
#include "undo_check.hpp"

namespace dtlab::test {
namespace {

using engine::LockGrid;
using engine::LockGridSync;
using engine::Method;
using engine::TetId;
using engine::ThreadStats;
using predicates::Point3;

// The cells split the bounding box evenly on each axis, the box's far faces in the last cells,
// and a span beyond the largest double (halved before it is divided) does not overflow.
TEST(ParallelMethods, LockGridCellsSplitTheBoundingBox) {
  const std::vector<Point3> points{{0, 0, 0}, {4, 4, 4}, {0.9, 1.1, 3.99}, {2, 0, 4}};
  const LockGrid grid(points, points.size(), 4);
  EXPECT_EQ(grid.per_axis(), 4);
  const auto cell = [](int x, int y, int z) {
    return static_cast<std::uint32_t>((z * 4 + y) * 4 + x);
  };
  EXPECT_EQ(grid.cell_of(0), cell(0, 0, 0));
  EXPECT_EQ(grid.cell_of(1), cell(3, 3, 3));
  EXPECT_EQ(grid.cell_of(2), cell(0, 1, 3));
  EXPECT_EQ(grid.cell_of(3), cell(2, 0, 3));
  const std::vector<Point3> wide{{-1.5e308, 0, 0}, {1.5e308, 1, 1}, {0, 0.5, 0.5}};
  const LockGrid wide_grid(wide, wide.size(), 2);
  EXPECT_EQ(wide_grid.cell_of(0), 0u);
  EXPECT_EQ(wide_grid.cell_of(1), 7u);
  EXPECT_EQ(wide_grid.cell_of(2), 7u);  // 0 is the middle on x: the upper cell
  // The automatic size: about 256 points a cell, at least 2 cbrt(threads) per axis (rounded up)
  // on several threads.
  EXPECT_EQ(LockGrid::cells_per_axis(1'000'000, 2), 16);
  EXPECT_EQ(LockGrid::cells_per_axis(100, 1), 1);
  EXPECT_EQ(LockGrid::cells_per_axis(100, 2), 3);
  EXPECT_EQ(LockGrid::cells_per_axis(100, 16), 6);
  EXPECT_EQ(LockGrid::cells_per_axis(100'000'000, 2), 73);
}

// A thread holds a tetrahedron by the cells of its finite vertices. A second thread that finds a
// cell held by a lower id (higher priority) gives up at once; the lower id waits for a higher
// one (counted), until the cell is free or the run is stopped. Commit lets every cell go.
TEST(ParallelMethods, LockGridSyncHoldsCellsAndWaitsOnlyForHigherIds) {
  const std::vector<Point3> points{{0, 0, 0}, {0.1, 0, 0}, {0, 0.1, 0}, {0, 0, 0.1}, {1, 1, 1}};
  engine::SharedMesh mesh(points);
  mesh.tets.keep_children(false);
  mesh.tets.keep_lock_words(true);  // as the method's store: the aliveness bit in the word
  const TetId near = mesh.tets.allocate();
  mesh.tets[near].vertex = {0, 1, 2, engine::kInfiniteVertex};  // cell 0 alone
  const TetId far = mesh.tets.allocate();
  mesh.tets[far].vertex = {4, 1, 2, 3};  // cells 7 and 0
  const LockGrid grid(points, points.size(), 2);
  for (engine::VertexId v = 0; v < 4; ++v) ASSERT_EQ(grid.cell_of(v), 0u);
  ASSERT_EQ(grid.cell_of(4), 7u);
  std::atomic<bool> stop{false};
  ThreadStats first_stats;
  ThreadStats second_stats;
  LockGridSync first(mesh, grid, 1, first_stats, stop);
  LockGridSync second(mesh, grid, 2, second_stats, stop);

  ASSERT_TRUE(first.acquire(near));
  EXPECT_EQ(grid.word(0).load(), 1u);
  EXPECT_TRUE(first.acquire(near));   // held already: no second take
  EXPECT_FALSE(second.acquire(far));  // cell 0 is thread 1's: thread 2 gives up
  EXPECT_EQ(second_stats.waits, 0u);
  second.rollback();
  EXPECT_EQ(grid.word(7).load(), 0u);  // what it had taken before the refusal is let go
  first.commit();
  EXPECT_EQ(grid.word(0).load(), 0u);

  ASSERT_TRUE(second.acquire(far));
  // Thread 1 has priority: it waits for thread 2's cells, here until the stop (whether the stop
  // comes before its first look or during its wait, it counts one wait).
  bool got = true;
  std::thread waiter([&] { got = first.acquire(near); });
  std::this_thread::sleep_for(std::chrono::milliseconds(10));
  stop = true;
  waiter.join();
  EXPECT_FALSE(got);
  EXPECT_EQ(first_stats.waits, 1u);
  first.rollback();
  second.commit();
  EXPECT_EQ(grid.word(0).load(), 0u);
  EXPECT_EQ(grid.word(7).load(), 0u);
}

// The lock-grid method's give-ups after flips leave the mesh as it was (undo_check.hpp), in the
// store the method runs on (aliveness in the word beside each record), and let go of every cell:
// each try finds a random fifth of the cells held by a thread of higher priority (id 1; this one
// is 2), so that flips are refused after others were written; uniform and grid points (S44 and
// S22 flips undone), slots reused after the epochs as in the method.
TEST(ParallelMethods, LockGridRollbackRestoresTheMeshAfterFlips) {
  for (const std::string family : {"uniform", "grid"}) {
    const auto points = simplex_first(generators::generate(family, 1500, 7).points);
    engine::SharedMesh mesh(points);
    mesh.tets.keep_children(false);
    mesh.tets.keep_lock_words(true);
    const LockGrid grid(points, points.size(), 6);
    const std::uint32_t cells = 6 * 6 * 6;
    std::atomic<bool> stop{false};
    ThreadStats stats;
    LockGridSync sync(mesh, grid, 2, stats, stop);
    // As the method's threads: dead slots reused after the epochs.
    engine::EpochDomain epochs(1);
    engine::SlotReclaimer reclaimer(epochs, 0);
    std::mt19937 rng(11);
    const auto counts = check_give_ups_undo(
        points, mesh, sync, 500,
        [&](engine::VertexId v, bool refuse) {
          for (std::uint32_t cell = 0; cell < cells; ++cell) {
            // Nothing of this thread's is held between tries: every cell free, or the other's.
            EXPECT_NE(grid.word(cell).load(), 2u) << cell;
            grid.word(cell).store(refuse && rng() % 5 == 0 ? 1 : 0);
          }
          if (refuse) grid.word(grid.cell_of(v)).store(0);
        },
        &reclaimer);
    EXPECT_GT(counts.give_ups, 500) << family;
    EXPECT_GT(counts.after_flips, 100) << family;
    if (family == "grid") {
      EXPECT_GT(counts.after_s44_or_s22, 50);
    }
  }
}

// Whole runs on grids of 2 and 3 cells per axis, so that the threads meet in cells: the unique
// mesh with both insertions and the exact kernels, nothing abandoned, the grid reported, and
// both outcomes of a conflict taken (a wait by a lower id, a give-up by a higher one; whether a
// flips give-up had written anything is not counted: the undo itself is the test above).
TEST(ParallelMethods, LockGridWaitsAndGivesUpAndGivesTheUniqueMesh) {
  std::uint64_t waits = 0;
  std::uint64_t give_ups[2] = {0, 0};
  for (const std::string family : {"uniform", "grid", "sphere", "cospherical", "duplicates"}) {
    const auto points = generators::generate(family, 700, 4).points;
    const auto expected = engine::canonical_tetrahedra(engine::triangulate(points, {}).tetrahedra);
    for (const auto kernel :
         {engine::KernelKind::Adaptive, engine::KernelKind::Filtered, engine::KernelKind::Exact}) {
      if (kernel == engine::KernelKind::Exact && family != "uniform") continue;  // GMP: slow
      for (const auto insertion : {engine::Insertion::Flips, engine::Insertion::Cavity}) {
        for (const int threads : {2, 4}) {
          engine::TriangulateOptions options;
          options.location = engine::Location::Walk;
          options.insertion = insertion;
          options.kernel = kernel;
          options.method = Method::LockGrid;
          options.threads = threads;
          options.stress = true;
          options.lock_grid_cells = threads == 2 ? 2 : 3;
          options.distribution =
              threads == 2 ? engine::Distribution::Dynamic : engine::Distribution::Blocks;
          const auto result = engine::triangulate(points, options);
          const std::string what = family + " " + engine::to_string(insertion) + " " +
                                   engine::to_string(kernel) + " " + std::to_string(threads);
          EXPECT_EQ(result.stats.abandoned_insertions, 0u) << what;
          EXPECT_EQ(result.stats.lock_grid_cells, options.lock_grid_cells) << what;
          EXPECT_EQ(engine::canonical_tetrahedra(result.tetrahedra), expected) << what;
          for (const ThreadStats& t : result.stats.threads) {
            waits += t.waits;
            give_ups[insertion == engine::Insertion::Cavity ? 1 : 0] += t.give_ups;
          }
        }
      }
    }
  }
  EXPECT_GT(waits, 0u);
  EXPECT_GT(give_ups[0], 0u);
  EXPECT_GT(give_ups[1], 0u);
}

// Without --grid-cells the size comes from the point count and threads, and is reported.
TEST(ParallelMethods, LockGridChoosesAndReportsItsSize) {
  const auto points = generators::generate("uniform", 12000, 3).points;
  engine::TriangulateOptions options;
  options.location = engine::Location::Walk;
  options.method = Method::LockGrid;
  options.threads = 2;
  const auto result = engine::triangulate(points, options);
  EXPECT_EQ(result.stats.lock_grid_cells,
            static_cast<std::uint64_t>(LockGrid::cells_per_axis(points.size(), 2)));
  EXPECT_EQ(result.stats.lock_grid_cells, 4u);
  EXPECT_EQ(engine::canonical_tetrahedra(result.tetrahedra),
            engine::canonical_tetrahedra(engine::triangulate(points, {}).tetrahedra));
}

// More than 256 cells per axis (the CLI's bound) is refused through the library too: the cell
// index would overflow an int beyond 1,290.
TEST(ParallelMethods, LockGridRefusesMoreThan256CellsPerAxis) {
  engine::TriangulateOptions options;
  options.method = Method::LockGrid;
  options.location = engine::Location::Walk;
  options.threads = 2;
  options.lock_grid_cells = 257;
  const auto points = generators::generate("uniform", 100, 1).points;
  try {
    (void)engine::triangulate(points, options);
    ADD_FAILURE() << "257 cells per axis accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("must be 1 to 256"), std::string::npos) << e.what();
  }
  options.lock_grid_cells = 256;
  EXPECT_EQ(engine::triangulate(points, options).stats.lock_grid_cells, 256u);
}

}  // namespace
}  // namespace dtlab::test
