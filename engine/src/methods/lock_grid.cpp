// The lock-grid method (lock_grid.hpp): per-cell locks on a spatial grid instead of a lock word
// per tetrahedron, each thread inserting its block of the points (the walk mode's distribution)
// on the worker loop of the optimistic methods; a point given up retries later.
#include "methods/lock_grid.hpp"

#include <stdexcept>

#include "methods/kernel_dispatch.hpp"
#include "methods/optimistic_worker.hpp"

namespace dtlab::engine {

std::vector<Tetrahedron> run_lock_grid(const MethodInput& input, TriangulationStats& stats) {
  return with_kernel(input.options, [&]<class K>() {
    // The store keeps a word a slot for the aliveness bit alone (nobody owns it: the cells are
    // the locks), read with the record's cache line: against a byte array beside the records,
    // 1M uniform points by cavities took 8.7 s on one thread instead of 7.4 (medians of 3,
    // docs/performance-log.md).
    ParallelRun<K> run(input, stats, std::max(1, input.options.threads), /*lock_words=*/true);
    if (input.options.lock_grid_cells > 256) {
      throw std::invalid_argument(
          "lock_grid_cells (--grid-cells) must be 1 to 256, or 0 to choose");
    }
    const int per_axis = input.options.lock_grid_cells > 0
                             ? static_cast<int>(input.options.lock_grid_cells)
                             : LockGrid::cells_per_axis(input.input_count, run.threads);
    const LockGrid grid(input.points, input.input_count, per_axis);
    stats.lock_grid_cells = static_cast<std::uint64_t>(per_axis);
    insert_with_policies(
        run,
        [&](int i, ThreadStats& counters) {
          return LockGridSync(run.mesh, grid, static_cast<std::uint32_t>(i + 1), counters,
                              run.table.stop, run.options.stress);
        },
        [](int, const LockGridSync&) {});
    return run.output(run.finish());
  });
}

}  // namespace dtlab::engine
