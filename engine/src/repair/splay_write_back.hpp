#pragma once
// The last step of star splaying on the engine's mesh (splay_repair.cpp): the active stars'
// tetrahedra replace every live tetrahedron at an active vertex, through the store's one write
// path (mesh/topology_commit.hpp).
#include <vector>

#include "dtlab/engine/stats.hpp"
#include "mesh/shared_mesh.hpp"
#include "repair/star_splaying.hpp"
#include "repair/walked_mesh_stars.hpp"

namespace dtlab::engine {

// `canonical`: each point's vertex (equal points one); `live`: the live tetrahedra, read where
// `walked` (the walks around a vertex of a consistent mesh) is null. Counts go to `stats`.
void write_back(SharedMesh& mesh, StarSplayer& splayer, const std::vector<VertexId>& canonical,
                const std::vector<TetId>& live, const WalkedMeshStars* walked, SplayStats& stats);

}  // namespace dtlab::engine
