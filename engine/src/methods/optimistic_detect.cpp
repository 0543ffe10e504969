// optimistic-detect's run (optimistic_detect.hpp): the optimistic worker loop with DetectSync.
#include "methods/optimistic_detect.hpp"

#include "methods/optimistic_worker.hpp"

namespace dtlab::engine {

std::vector<Tetrahedron> run_optimistic_detect(const MethodInput& input,
                                               TriangulationStats& stats) {
  return run_optimistic<DetectSync>(input, stats);
}

}  // namespace dtlab::engine
