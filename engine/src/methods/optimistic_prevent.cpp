// optimistic-prevent's run (optimistic_prevent.hpp): the optimistic worker loop with PreventSync.
#include "methods/optimistic_prevent.hpp"

#include "methods/optimistic_worker.hpp"

namespace dtlab::engine {

std::vector<Tetrahedron> run_optimistic_prevent(const MethodInput& input,
                                                TriangulationStats& stats) {
  return run_optimistic<PreventSync>(input, stats);
}

}  // namespace dtlab::engine
