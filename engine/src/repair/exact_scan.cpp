// Star splaying's exact scan (exact_scan.hpp).
#include "repair/exact_scan.hpp"

#include <algorithm>
#include <atomic>
#include <cstdint>

#include "dtlab/predicates/kernels.hpp"
#include "mesh/conflict.hpp"
#include "support/parallel_ranges.hpp"

namespace dtlab::engine {
namespace {

using Exact = predicates::AdaptiveKernel;

// Whether face f of t and face g of u are one triangle with opposite orientations, as the two
// tetrahedra across a face of a combinatorially consistent mesh see it. Then, where the five points
// are distinct, t's test of u's apex and u's test of t's apex are the sign of one lifted
// determinant, ties broken alike by the perturbation, whatever u's orientation (docs/design.md,
// "The exact scan's sides").
bool seen_oppositely(const Tet& t, std::size_t f, const Tet& u, std::size_t g) {
  const auto& mine = kFaceVertex[f];
  const auto& theirs = kFaceVertex[g];
  const VertexId p = t.vertex[static_cast<std::size_t>(mine[0])];
  const VertexId q = t.vertex[static_cast<std::size_t>(mine[1])];
  const VertexId r = t.vertex[static_cast<std::size_t>(mine[2])];
  for (std::size_t s = 0; s < 3; ++s) {
    if (u.vertex[static_cast<std::size_t>(theirs[s])] != p) continue;
    return u.vertex[static_cast<std::size_t>(theirs[(s + 1) % 3])] == r &&
           u.vertex[static_cast<std::size_t>(theirs[(s + 2) % 3])] == q;
  }
  return false;
}

// Point p differs from each of q's four points (coordinates, not ids: an input's equal points
// are distinct vertices until the repair merges them).
bool distinct_from_all(const std::vector<Point3>& points, const Quad& q, VertexId p) {
  const Point3& a = points[p];
  return std::none_of(q.begin(), q.end(), [&](VertexId v) {
    const Point3& b = points[v];
    return a.x == b.x && a.y == b.y && a.z == b.z;
  });
}

// Hull vertices with more infinite tetrahedra around them than this are seeded, not tested.
constexpr std::size_t kTestedHullDegree = 128;

// The infinite tetrahedra around the edge from hull vertex v to the vertex at infinity, starting
// at t, into `ring`; false when the ring does not close within `longest` steps (the live
// tetrahedra's count: a mesh the fast kernel broke).
bool ring_at_infinity(const SharedMesh& mesh, TetId t, VertexId v, std::vector<TetId>& ring,
                      std::size_t longest) {
  ring.clear();
  TetId current = t;
  TetId previous = kNoTet;
  while (ring.size() < longest) {
    ring.push_back(current);
    const Tet& tet = mesh.tets[current];
    TetId next = kNoTet;
    for (std::size_t i = 0; i < 4; ++i) {
      const VertexId w = tet.vertex[i];
      if (w == v || w == kInfiniteVertex) continue;
      const TetId across = ref_tet(tet.neighbor[i]);
      if (across != previous) {
        next = across;
        break;
      }
    }
    previous = current;
    current = next;
    if (current == t) return true;
    if (current == kNoTet || !mesh.tets[current].is_infinite()) return false;
  }
  return false;
}

// Whether the boundary closes convexly around hull vertex v: no neighbour of v on the boundary
// lies beyond (is in conflict with) one of v's infinite tetrahedra. Every edge convex, the
// boundary's link of v is a locally convex spherical polygon; it winds once around v exactly when
// each of its vertices lies on the inner side of each of its edges' great circles (a polygon that
// winds twice, a spherical pentagram, has a vertex outside some edge's circle). The ring's vertices
// go into `around`, to be seeded when the test fails. (On a flat stretch of hull the neighbours lie
// on the faces' planes and the conflict test is the in-circle one: there this is the Delaunay
// condition of the hull's triangulation, not a proof of a single winding.)
void collect_around(const SharedMesh& mesh, const std::vector<TetId>& ring, VertexId v,
                    std::vector<VertexId>& around) {
  around.clear();
  for (const TetId r : ring) {
    for (const VertexId w : mesh.tets[r].vertex) {
      if (w != v && w != kInfiniteVertex) around.push_back(w);
    }
  }
  std::sort(around.begin(), around.end());
  around.erase(std::unique(around.begin(), around.end()), around.end());
}

bool convex_around(const SharedMesh& mesh, const std::vector<TetId>& ring, VertexId v,
                   std::vector<VertexId>& around) {
  collect_around(mesh, ring, v, around);
  for (const TetId r : ring) {
    const Quad& q = mesh.tets[r].vertex;
    for (const VertexId w : around) {
      if (std::find(q.begin(), q.end(), w) != q.end()) continue;
      if (in_conflict<Exact>(mesh.points, q, w)) return false;
    }
  }
  return true;
}

}  // namespace

std::vector<ScanFindings> exact_scan(const SharedMesh& mesh, const std::vector<TetId>& live,
                                     bool exact_mesh, int parts) {
  const std::vector<Point3>& points = mesh.points;
  std::vector<ScanFindings> findings(static_cast<std::size_t>(std::max(parts, 1)));
  // Hull vertices checked already (inexact meshes only): the first infinite tetrahedron to reach
  // one claims it, so each ring is walked and tested once. Relaxed: the flag hands over no data.
  std::vector<std::atomic<std::uint8_t>> claimed(exact_mesh ? 0 : points.size());
  in_parallel_ranges(live.size(), parts, [&](std::size_t begin, std::size_t end, std::size_t part) {
    ScanFindings& found = findings[part];
    std::vector<TetId> ring;
    std::vector<VertexId> around;
    auto note_quad = [&](const Quad& q) {
      for (const VertexId v : q) {
        if (v != kInfiniteVertex) found.to_seed.push_back(v);
      }
    };
    // Each neighbour record is a cache miss (its slot is anywhere in the store): they are
    // requested a few tetrahedra ahead, and those tetrahedra's own records further ahead, so
    // the misses overlap instead of queueing one behind the other. So are the points: a
    // tetrahedron's vertices lie far apart in the point array (different BRIO rounds after a
    // walk, the input's order in DAG mode).
    constexpr std::size_t kRecordsAhead = 16;
    constexpr std::size_t kNeighboursAhead = 8;
    constexpr std::size_t kApexAhead = 4;
    for (std::size_t k = begin; k < end; ++k) {
      if (k + kRecordsAhead < end) __builtin_prefetch(&mesh.tets[live[k + kRecordsAhead]]);
      if (k + kNeighboursAhead < end) {
        const TetId ahead = live[k + kNeighboursAhead];
        for (const FaceRef n : mesh.tets[ahead].neighbor) {
          if (ref_tet(n) > ahead) __builtin_prefetch(&mesh.tets[ref_tet(n)]);
        }
        for (const VertexId v : mesh.tets[ahead].vertex) {
          if (v != kInfiniteVertex) __builtin_prefetch(&points[v]);
        }
      }
      if (k + kApexAhead < end) {
        const TetId ahead = live[k + kApexAhead];
        for (const FaceRef n : mesh.tets[ahead].neighbor) {
          if (ref_tet(n) <= ahead) continue;
          const VertexId apex = mesh.tets[ref_tet(n)].vertex[static_cast<std::size_t>(ref_face(n))];
          if (apex != kInfiniteVertex) __builtin_prefetch(&points[apex]);
        }
      }
      const TetId i = live[k];
      const Tet& t = mesh.tets[i];
      const bool positive =
          !t.is_infinite() && Exact::orient3d(points[t.vertex[0]], points[t.vertex[1]],
                                              points[t.vertex[2]], points[t.vertex[3]]) > 0;
      if (!t.is_infinite() && !positive) {
        ++found.bad_tetrahedra;
        note_quad(t.vertex);
      }
      // Each hull vertex of an inexact mesh, once. (An exactly built mesh is combinatorially
      // consistent, burglary's too, so its hull needs no more than the face tests: a reflex hull
      // edge is a non-Delaunay infinite face. Winding twice around a vertex takes an inexact
      // kernel's wrong orientations.)
      if (t.is_infinite() && !exact_mesh) {
        for (const VertexId v : t.vertex) {
          if (v == kInfiniteVertex || claimed[v].exchange(1, std::memory_order_relaxed) != 0) {
            continue;
          }
          const bool closed = ring_at_infinity(mesh, i, v, ring, live.size());
          if (closed && ring.size() > kTestedHullDegree) {
            // k^2 tests would cost too much: splayed instead, which is always sound.
            collect_around(mesh, ring, v, around);
            found.to_seed.push_back(v);
            found.to_seed.insert(found.to_seed.end(), around.begin(), around.end());
            continue;
          }
          if (closed && convex_around(mesh, ring, v, around)) continue;
          ++found.reflex_hull_vertices;
          found.to_seed.push_back(v);
          if (closed) found.to_seed.insert(found.to_seed.end(), around.begin(), around.end());
        }
      }
      for (std::size_t f = 0; f < 4; ++f) {
        const TetId other = ref_tet(t.neighbor[f]);
        if (other < i) continue;  // each face once
        const Tet& u = mesh.tets[other];
        const VertexId apex = u.vertex[static_cast<std::size_t>(ref_face(t.neighbor[f]))];
        const VertexId mine = t.vertex[f];
        const bool one_side =
            apex != kInfiniteVertex &&
            (exact_mesh ||
             (positive && distinct_from_all(points, t.vertex, apex) &&
              seen_oppositely(t, f, u, static_cast<std::size_t>(ref_face(t.neighbor[f])))));
        const bool bad =
            (apex != kInfiniteVertex && in_conflict<Exact>(points, t.vertex, apex)) ||
            (!one_side && mine != kInfiniteVertex && in_conflict<Exact>(points, u.vertex, mine));
        if (bad) {
          ++found.non_delaunay_faces;
          note_quad(t.vertex);
          note_quad(u.vertex);
        }
      }
    }
  });
  return findings;
}

}  // namespace dtlab::engine
