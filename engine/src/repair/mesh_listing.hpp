#pragma once
// The shared mesh read for star splaying (splay_repair.cpp): its live tetrahedra in the exact
// scan's order with the lowest live tetrahedron at each vertex, and every vertex's tetrahedra from
// incidence lists (for a mesh whose stars a walk cannot find).
#include <cstdint>
#include <vector>

#include "mesh/shared_mesh.hpp"
#include "repair/star_splaying.hpp"

namespace dtlab::engine {

// The shared mesh as MeshStars: every live tetrahedron at each vertex, from an incidence list
// (not a walk over neighbours: a broken mesh's star need not be connected through its faces).
// Built by up to four threads, each over one range of `live` with its own counts (so each list
// keeps the order of `live`, whatever the thread count).
class SharedMeshStars : public MeshStars {
 public:
  SharedMeshStars(const SharedMesh& mesh, const std::vector<TetId>& live, int threads);
  void tetrahedra_of(VertexId x, std::vector<Quad>& out) const override;

 private:
  const SharedMesh& mesh_;
  std::vector<std::uint32_t> first_;
  std::vector<TetId> of_;
};

// The live tetrahedra in the exact scan's order, and the lowest live tetrahedron at each vertex
// (kNoTet: no vertex), where a walk around the vertex can start.
struct LiveTetrahedra {
  std::vector<TetId> ordered;
  std::vector<TetId> lowest_tetrahedron;
};

// The live tetrahedra of `mesh` on `parts` threads (mesh_listing.cpp); `ordered` false: the
// lowest tetrahedra alone (no list), where no scan is to run.
LiveTetrahedra live_tetrahedra(const SharedMesh& mesh, int parts, bool ordered);

}  // namespace dtlab::engine
