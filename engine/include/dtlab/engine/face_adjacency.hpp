#pragma once
// What a tetrahedron list says about its faces, besides the tetrahedra: which tetrahedron lies
// across each face and which faces bound the mesh. The Python binding's `neighbors` and
// `convex_hull`, and TetGen's .neigh and .face files, come from here.
#include <array>
#include <cstdint>
#include <vector>

#include "dtlab/engine/tetrahedron.hpp"
#include "dtlab/predicates/point.hpp"

namespace dtlab::engine {

struct FaceAdjacency {
  // neighbors[t][i]: the tetrahedron across the face of t opposite its vertex i, or -1 where t is
  // the only tetrahedron on that face (scipy's and TetGen's convention).
  std::vector<std::array<std::int32_t, 4>> neighbors;
  // The faces on one tetrahedron only, ordered by (tetrahedron, opposite vertex), each turned so
  // that it faces away from its tetrahedron: for a positively oriented one (orient3d > 0, the
  // engine's output) (b - a) x (c - a) points out of it. On a Delaunay mesh, the convex hull.
  std::vector<std::array<std::uint32_t, 3>> boundary_faces;
  std::vector<std::uint32_t> boundary_face_tetrahedra;  // the tetrahedron of each boundary face
};

// Throws std::invalid_argument for a vertex id not below point_count, more than (2^31 - 1) / 4
// tetrahedra (a face's slot, tetrahedron * 4 + vertex, is a 32-bit id), or a face on more than
// two tetrahedra (no mesh has one).
FaceAdjacency face_adjacency(const std::vector<Tetrahedron>& tets, std::size_t point_count);

// The tetrahedra turned positive where they are negative (two ids swapped), for lists from tools
// that do not orient theirs (Qhull): flat ones stay as they are, for the validator to count.
// Decided exactly (adaptive kernel). Returns how many were turned. Throws std::invalid_argument
// when a point has a NaN or infinite coordinate (no sign is defined there).
std::uint64_t orient_positively(const std::vector<predicates::Point3>& points,
                                std::vector<Tetrahedron>& tets);

}  // namespace dtlab::engine
