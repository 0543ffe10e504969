// Burglary's run (burglary.hpp): the optimistic worker loop with BurglarySync, then the
// sequential post-check on the marks its victims left (methods/burglary_post_check.hpp).
#include "methods/burglary.hpp"

#include "methods/burglary_post_check.hpp"
#include "methods/kernel_dispatch.hpp"
#include "methods/optimistic_worker.hpp"

namespace dtlab::engine {

std::vector<Tetrahedron> run_burglary(const MethodInput& input, TriangulationStats& stats) {
  return with_kernel(input.options, [&]<class K>() {
    ParallelRun<K> run(input, stats, std::max(1, input.options.threads));
    std::vector<std::vector<TetId>> suspicious(static_cast<std::size_t>(run.threads));
    insert_optimistically<BurglarySync>(run, [&](int i, const BurglarySync& sync) {
      suspicious[static_cast<std::size_t>(i)] = sync.suspicious();
    });
    const auto duplicates = run.finish();
    std::vector<TetId> marks;
    for (const auto& m : suspicious) marks.insert(marks.end(), m.begin(), m.end());
    return post_check<K>(run.mesh, marks, duplicates, input, stats);
  });
}

}  // namespace dtlab::engine
