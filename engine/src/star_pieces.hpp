#pragma once
// Star splaying from an arbitrary list of tetrahedra can end with stars that agree but fall apart
// into pieces: a lone input tetrahedron whose four vertices meet no other one keeps its four
// stars to itself, each one a tetrahedron and its hull, consistent and locally Delaunay, and no
// disagreement ever reaches the rest. Every piece is then the Delaunay tetrahedralization of its
// own vertices, and they overlap. The bridge between a piece and the rest is the closest pair of
// points across it (x in the piece, y outside): its closed diametral ball holds no other point
// (a point z there is nearer to both x and y than they are to each other, so (z, y) or (x, z)
// would be a closer pair across), so xy is an edge of the Delaunay tetrahedralization of every
// subset that holds x and y, the perturbed one included. Once x and y know each other, their
// stars keep the edge whatever they learn later: the pieces stay joined (docs/design.md).
#include <utility>
#include <vector>

#include "dtlab/engine/tet_mesh.hpp"
#include "dtlab/predicates/point.hpp"
#include "star_splaying.hpp"

namespace dtlab::engine {

// The pieces of the active stars over `vertices` (distinct points, every one active): which
// vertices reach which through the stars' tetrahedra. For each piece but the largest, its
// closest pair across (exact distances; ties broken by ids), as (vertex in the piece, vertex
// outside). Empty when the stars are one piece.
std::vector<std::pair<VertexId, VertexId>> bridges_between_pieces(
    const std::vector<predicates::Point3>& points, const std::vector<VertexId>& vertices,
    const StarSplayer& splayer);

}  // namespace dtlab::engine
