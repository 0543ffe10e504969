#pragma once
// Star splaying from an arbitrary list of tetrahedra can end with stars that agree but fall apart
// into pieces: a lone input tetrahedron whose four vertices meet no other one keeps its four
// stars to itself, each one a tetrahedron and its hull, consistent and locally Delaunay, and no
// disagreement ever reaches the rest. Every piece is then the Delaunay tetrahedralization of its
// own vertices, and pieces can overlap. The bridge between a piece and the rest is the closest pair
// of points across it (x in the piece, y outside): its closed diametral ball holds no other point
// (a point z there is nearer to both x and y than they are to each other, so (z, y) or (x, z)
// would be a closer pair across), so xy is an edge of the Delaunay tetrahedralization of every
// subset that holds x and y, the perturbed one included. Once x and y know each other, their
// stars keep the edge whatever they learn later. The next round's pieces should be this round's
// joined by the bridges (each piece's stars reach all its vertices, as its Delaunay
// tetrahedralization does); the caller checks that their number falls (docs/design.md).
#include <utility>
#include <vector>

#include "dtlab/predicates/point.hpp"
#include "mesh/tet_store.hpp"
#include "repair/star_splaying.hpp"

namespace dtlab::engine {

// The piece of each vertex of `vertices` (every one active): the lowest id among the vertices it
// reaches through the stars' tetrahedra; kInfiniteVertex for the other points.
std::vector<VertexId> pieces_of_stars(std::size_t point_count,
                                      const std::vector<VertexId>& vertices,
                                      const StarSplayer& splayer);

// For each piece but the largest (of equal ones, the one named by the lower id), its closest pair
// across: the pair (vertex in the piece, vertex in another) of least exact squared distance,
// ties broken by the ids. `vertices` are distinct points; `piece` names each one's piece. Empty
// when there is one piece.
std::vector<std::pair<VertexId, VertexId>> closest_pairs_across(
    const std::vector<predicates::Point3>& points, const std::vector<VertexId>& vertices,
    const std::vector<VertexId>& piece);

}  // namespace dtlab::engine
