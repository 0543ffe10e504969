#pragma once
// Burglary's sequential post-check (paper Sect. 5), after its threads: the exact validator's count
// of what the run left (non-Delaunay faces, reflex boundary edges), and with options.repair the
// repair: star splaying (--repair, --repair=flips-splay: exact Lawson flips first), or the
// paper's Lawson flips on the marked tetrahedra, then on every tetrahedron (--repair=flips), which
// can get stuck in 3D, then a sequential rebuild as an explicit, reported last resort
// (--repair=rebuild). Every stage's count goes into stats.post_check.
#include <utility>
#include <vector>

#include "mesh/shared_mesh.hpp"
#include "methods/method_input.hpp"

namespace dtlab::engine {

// The finite tetrahedra after the check (and the repair), from the mesh `run` built. `marks`: the
// tetrahedra burglary's victims marked suspicious; `duplicates`: (skipped point, its vertex).
template <class K>
std::vector<Tetrahedron> post_check(SharedMesh& mesh, const std::vector<TetId>& marks,
                                    const std::vector<std::pair<VertexId, VertexId>>& duplicates,
                                    const MethodInput& run, TriangulationStats& stats);

}  // namespace dtlab::engine
