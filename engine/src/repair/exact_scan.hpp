#pragma once
// Star splaying's exact scan of a mesh after a run (splay_repair.cpp): every non-Delaunay face
// (infinite tetrahedra included: a reflex hull edge), every flat or inverted finite tetrahedron
// and, on a mesh not built exactly, every hull vertex whose boundary does not close around it
// convexly, whose vertices are the stars' seeds.
#include <cstdint>
#include <vector>

#include "mesh/shared_mesh.hpp"

namespace dtlab::engine {

// What the exact scan of one range of live tetrahedra found: the vertices to splay from.
struct ScanFindings {
  std::vector<VertexId> to_seed;
  std::uint64_t bad_tetrahedra = 0;
  std::uint64_t non_delaunay_faces = 0;
  // Hull vertices where a neighbour on the boundary lies beyond one of the vertex's hull faces
  // (or the ring of infinite tetrahedra around it does not close): convex at every edge, the
  // boundary can still wind twice around a vertex, which no face test sees.
  std::uint64_t reflex_hull_vertices = 0;
};

// The scan of `live` (the listing's order) on `parts` threads, one finding per thread. One side
// of a face decides on an exactly built mesh (`exact_mesh`), and on any mesh where the lower
// tetrahedron is finite and positively oriented, the apex across is none of its points and the two
// see one triangle oppositely; elsewhere an inexact kernel's mesh has its face tested from both
// sides, since its two tetrahedra need not agree.
std::vector<ScanFindings> exact_scan(const SharedMesh& mesh, const std::vector<TetId>& live,
                                     bool exact_mesh, int parts);

}  // namespace dtlab::engine
