// Star splaying on the engine's shared mesh after a run (burglary's marks, the fast kernel's
// errors): the exact scan or the validation's findings, the flips first where asked, the stars,
// and the write-back (docs/design.md). `dtlab repair` of a list is list_repair.cpp.
#include "splay_repair.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <numeric>
#include <stdexcept>

#include "dtlab/engine/validator.hpp"
#include "dtlab/predicates/kernels.hpp"
#include "insertion_order.hpp"
#include "parallel_ranges.hpp"
#include "splay_common.hpp"
#include "star_splaying.hpp"
#include "walked_mesh_stars.hpp"

namespace dtlab::engine {
namespace {

using Clock = std::chrono::steady_clock;
using Exact = predicates::AdaptiveKernel;

// The shared mesh as MeshStars: every live tetrahedron at each vertex, from an incidence list
// (not a walk over neighbours: a broken mesh's star need not be connected through its faces).
// Built by up to four threads, each over one range of `live` with its own counts (so each list
// keeps the order of `live`, whatever the thread count).
class SharedMeshStars : public MeshStars {
 public:
  SharedMeshStars(const SharedMesh& mesh, const std::vector<TetId>& live, int threads)
      : mesh_(mesh), first_(mesh.points.size() + 1, 0) {
    const std::size_t n = mesh.points.size();
    const int parts = std::clamp(threads, 1, 4);
    std::vector<std::vector<std::uint32_t>> at(static_cast<std::size_t>(parts));
    in_parallel_ranges(live.size(), parts,
                       [&](std::size_t begin, std::size_t end, std::size_t part) {
                         std::vector<std::uint32_t>& count = at[part];
                         count.assign(n, 0);
                         for (std::size_t i = begin; i < end; ++i) {
                           for (const VertexId v : mesh.tets[live[i]].vertex) {
                             if (v != kInfiniteVertex) ++count[v];
                           }
                         }
                       });
    // Each part's count becomes where its first tetrahedron at v goes.
    std::uint32_t next = 0;
    for (std::size_t v = 0; v < n; ++v) {
      first_[v] = next;
      for (auto& count : at) {
        if (count.empty()) continue;  // a part that had no range (a short list runs as one)
        const std::uint32_t here = count[v];
        count[v] = next;
        next += here;
      }
    }
    first_[n] = next;
    of_.resize(next);
    in_parallel_ranges(live.size(), parts,
                       [&](std::size_t begin, std::size_t end, std::size_t part) {
                         std::vector<std::uint32_t>& place = at[part];
                         for (std::size_t i = begin; i < end; ++i) {
                           for (const VertexId v : mesh.tets[live[i]].vertex) {
                             if (v != kInfiniteVertex) of_[place[v]++] = live[i];
                           }
                         }
                       });
  }
  void tetrahedra_of(VertexId x, std::vector<Quad>& out) const override {
    out.clear();
    for (std::uint32_t i = first_[x]; i < first_[x + 1]; ++i)
      out.push_back(mesh_.tets[of_[i]].vertex);
  }

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

// The scan's blocks: the cells of a 2^k x 2^k x 2^k grid over the points' bounding box, numbered
// along the Hilbert curve (consecutive blocks are face-adjacent cells): k is the largest (at most
// 7) with 8^k cells for at least 4 points each, so a cell holds 4 to 32 points on uniform data
// (30 at 1M points; cells of 4 measured the same). A tetrahedron belongs to the cell of its lowest
// vertex.
struct ScanCells {
  std::vector<std::uint32_t> of_point;
  std::size_t count = 1;
};

ScanCells scan_cells(const std::vector<Point3>& points, int parts) {
  ScanCells cells;
  cells.of_point.assign(points.size(), 0);
  if (points.empty()) return cells;
  unsigned bits = 1;
  while (bits < 7 && (std::size_t{1} << (3 * (bits + 1))) <= points.size() / 4) ++bits;
  cells.count = std::size_t{1} << (3 * bits);
  Point3 lo = points[0];
  Point3 hi = points[0];
  for (const Point3& p : points) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  const double side = static_cast<double>(std::uint32_t{1} << bits);
  auto scale = [side](double extent) { return extent > 0 ? side / extent : 0.0; };
  const std::array<double, 3> per_unit = {scale(hi.x - lo.x), scale(hi.y - lo.y),
                                          scale(hi.z - lo.z)};
  const double last = side - 1;
  auto cell_of = [last](double value, double low, double unit) {
    const double at = (value - low) * unit;  // NaN where an extent overflowed: cell 0
    return at > 0 ? static_cast<std::uint32_t>(std::min(at, last)) : std::uint32_t{0};
  };
  in_parallel_ranges(points.size(), parts, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i) {
      const Point3& p = points[i];
      cells.of_point[i] = static_cast<std::uint32_t>(
          hilbert_key(cell_of(p.x, lo.x, per_unit[0]), cell_of(p.y, lo.y, per_unit[1]),
                      cell_of(p.z, lo.z, per_unit[2]), bits));
    }
  });
  return cells;
}

// One counting sort over the store (DAG nodes included, about 50 slots per point in DAG mode), on
// the run's threads: each thread counts the live tetrahedra of its range of slots by their block,
// then places them; the order is (block, slot) whatever the thread count. A block's tetrahedra
// (about 200 at 30 points a cell) are each other's neighbours and the next blocks' ones, so the
// scan finds most neighbours' records and points in cache. Vertex ids say little of position
// in DAG mode (they are the input's order; the walk mode stores the points in BRIO and Hilbert
// order, whose rounds interleave), and slot order scatters the reads where later insertions
// reused slots. Cells of several points keep each thread's counts in cache
// (128 KB at 1M points). docs/experiments.md has the orders measured.
// The first pass also lowers each vertex's lowest live tetrahedron, the threads together with
// relaxed compare-and-swaps (a thread's own ids only grow, so one rarely retries).
// `ordered` false: the first pass's lowest tetrahedra alone (no cells, no list), where no scan
// is to run.
LiveTetrahedra live_tetrahedra(const SharedMesh& mesh, int parts, bool ordered) {
  const std::size_t slots = mesh.tets.size();
  LiveTetrahedra live;
  live.lowest_tetrahedron.assign(mesh.points.size(), kNoTet);
  auto lower_lowest = [&live](const Tet& tet, TetId t) {
    for (const VertexId v : tet.vertex) {
      if (v == kInfiniteVertex) continue;
      std::atomic_ref<TetId> lowest(live.lowest_tetrahedron[v]);
      TetId seen = lowest.load(std::memory_order_relaxed);
      while (t < seen && !lowest.compare_exchange_weak(seen, t, std::memory_order_relaxed)) {
      }
    }
  };
  if (!ordered) {
    in_parallel_ranges(slots, parts, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t i = begin; i < end; ++i) {
        const auto t = static_cast<TetId>(i);
        if (mesh.tets.is_alive(t, std::memory_order_acquire)) lower_lowest(mesh.tets[t], t);
      }
    });
    return live;
  }
  const ScanCells cells = scan_cells(mesh.points, parts);
  const std::size_t blocks = cells.count;
  auto block_of = [&cells](const Tet& t) {
    VertexId low = kInfiniteVertex;  // the largest id: some vertex is finite
    for (const VertexId v : t.vertex) low = std::min(low, v);
    return cells.of_point[low];
  };
  // Each slot's block, from the first pass, so that the second reads 4 bytes a slot instead of
  // the store's 32 and the cells (the listing went from 0.17-0.18 s to 0.14-0.15 s at 1M points,
  // 2 threads; 28 MB more while it runs). Left uninitialized: the first pass writes every entry.
  constexpr std::uint32_t kDeadSlot = ~std::uint32_t{0};
  const std::unique_ptr<std::uint32_t[]> block_at(new std::uint32_t[slots]);
  std::vector<std::vector<std::uint32_t>> place(static_cast<std::size_t>(std::max(parts, 1)));
  in_parallel_ranges(slots, parts, [&](std::size_t begin, std::size_t end, std::size_t part) {
    std::vector<std::uint32_t>& count = place[part];
    count.assign(blocks, 0);
    for (std::size_t i = begin; i < end; ++i) {
      const auto t = static_cast<TetId>(i);
      if (!mesh.tets.is_alive(t, std::memory_order_acquire)) {
        block_at[i] = kDeadSlot;
        continue;
      }
      const Tet& tet = mesh.tets[t];
      const std::uint32_t block = block_of(tet);
      block_at[i] = block;
      ++count[block];
      lower_lowest(tet, t);
    }
  });
  // Each part's count becomes where its first tetrahedron of the block goes.
  std::uint32_t next = 0;
  for (std::size_t b = 0; b < blocks; ++b) {
    for (auto& count : place) {
      if (count.empty()) continue;  // a part that had no range (a short store runs as one)
      const std::uint32_t here = count[b];
      count[b] = next;
      next += here;
    }
  }
  live.ordered.resize(next);
  in_parallel_ranges(slots, parts, [&](std::size_t begin, std::size_t end, std::size_t part) {
    std::vector<std::uint32_t>& at = place[part];
    for (std::size_t i = begin; i < end; ++i) {
      if (block_at[i] != kDeadSlot) live.ordered[at[block_at[i]]++] = static_cast<TetId>(i);
    }
  });
  return live;
}

// What the exact scan of one range of live tetrahedra found: the vertices to splay from.
struct ScanFindings {
  std::vector<VertexId> to_seed;
  std::uint64_t bad_tetrahedra = 0;
  std::uint64_t non_delaunay_faces = 0;
};

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

}  // namespace

ValidatedFindings validated_findings(const ValidationReport& report, std::size_t input_count,
                                     const std::vector<std::pair<VertexId, VertexId>>& duplicates) {
  std::vector<VertexId> mesh_vertex(input_count);
  std::iota(mesh_vertex.begin(), mesh_vertex.end(), VertexId{0});
  std::vector<VertexId> output_name = mesh_vertex;
  for (const auto& [duplicate, vertex] : duplicates) {
    output_name[vertex] = std::min(output_name[vertex], duplicate);
  }
  for (const auto& [duplicate, vertex] : duplicates) mesh_vertex[output_name[vertex]] = vertex;
  ValidatedFindings found;
  found.rejected_faces = report.perturbed_violations;
  found.vertices.reserve(report.perturbed_violation_vertices.size());
  for (const std::uint32_t v : report.perturbed_violation_vertices) {
    found.vertices.push_back(mesh_vertex.at(v));
  }
  return found;
}

void splay_shared_mesh(SharedMesh& mesh, const std::vector<TetId>& marks, bool exact_mesh,
                       int threads, SplayStats& stats, const ValidatedFindings* validated,
                       const FlipPass* flips_first) {
  const auto t0 = Clock::now();
  if (validated != nullptr && !exact_mesh) {
    throw std::logic_error("star splaying: validated findings on a mesh not built exactly");
  }
  stats.done = true;
  const int parts = std::max(threads, 1);
  stats.scan_threads = static_cast<std::uint64_t>(parts);
  const std::vector<Point3>& points = mesh.points;
  // The live tetrahedra in the scan's order (they also serve the incidence lists and the
  // write-back below, in that order); with validated findings, no scan: the lowest tetrahedron
  // at each vertex alone, the list made below only where a broken mesh needs it.
  const std::size_t slots = mesh.tets.size();
  LiveTetrahedra listed = live_tetrahedra(mesh, parts, validated == nullptr);
  stats.seconds_listing = std::chrono::duration<double>(Clock::now() - t0).count();
  const std::vector<TetId>& live = listed.ordered;
  const std::vector<TetId>& lowest_tetrahedron = listed.lowest_tetrahedron;
  auto is_vertex = [&](VertexId v) { return lowest_tetrahedron[v] != kNoTet; };
  std::vector<char> seed(points.size(), 0);
  auto seed_quad = [&](const Quad& q) {
    for (const VertexId v : q) {
      if (v != kInfiniteVertex) seed[v] = 1;
    }
  };
  // The exact scan, over the run's threads: every non-Delaunay face (infinite tetrahedra included:
  // a reflex hull edge) and every flat or inverted finite tetrahedron seeds its vertices. One side
  // of a face decides on an exactly built mesh, and on any mesh where the lower tetrahedron is
  // finite and positively oriented, the apex across is none of its points and the two see one
  // triangle oppositely (seen_oppositely); elsewhere an inexact kernel's mesh has its face tested
  // from both sides, since its two tetrahedra need not agree.
  std::vector<ScanFindings> findings(static_cast<std::size_t>(parts));
  if (validated != nullptr) {
    stats.found_by_post_check = true;
    stats.non_delaunay_faces = validated->rejected_faces;
    for (const VertexId v : validated->vertices) {
      if (v >= points.size()) throw std::logic_error("star splaying: a found vertex out of range");
      seed[v] = 1;
    }
  } else {
    in_parallel_ranges(
        live.size(), parts, [&](std::size_t begin, std::size_t end, std::size_t part) {
          ScanFindings& found = findings[part];
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
                const VertexId apex =
                    mesh.tets[ref_tet(n)].vertex[static_cast<std::size_t>(ref_face(n))];
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
                  (!one_side && mine != kInfiniteVertex &&
                   in_conflict<Exact>(points, u.vertex, mine));
              if (bad) {
                ++found.non_delaunay_faces;
                note_quad(t.vertex);
                note_quad(u.vertex);
              }
            }
          }
        });
  }
  for (const ScanFindings& found : findings) {
    stats.bad_tetrahedra += found.bad_tetrahedra;
    stats.non_delaunay_faces += found.non_delaunay_faces;
    for (const VertexId v : found.to_seed) seed[v] = 1;
  }
  findings = {};
  stats.seconds_scan = std::chrono::duration<double>(Clock::now() - t0).count();
  // Burglary's marks that are still live tetrahedra. (A dead mark stands for the live tetrahedra
  // below it in the DAG, which for a mark made early is much of the mesh; the exact scan above
  // finds every non-Delaunay face among them anyway.) They are seeds unless the scan proved the
  // mesh Delaunay: on a consistent mesh (an exactly built one is, burglary's included:
  // docs/design.md), every face locally Delaunay under the perturbed test and every tetrahedron
  // positively oriented make it the Delaunay tetrahedralization, so a star at a mark would be
  // splayed into itself, for nothing.
  // `consistent`: built exactly and no flat or inverted tetrahedron found (the walks around a
  // vertex and the skipped grouping of equal points below rely on it too).
  const bool consistent = exact_mesh && stats.bad_tetrahedra == 0;
  const bool proven = consistent && stats.non_delaunay_faces == 0;
  for (const TetId t : marks) {
    if (t < slots && mesh.tets.is_alive(t, std::memory_order_acquire)) {
      ++stats.live_marks;
      if (!proven) seed_quad(mesh.tets[t].vertex);
    }
  }
  stats.marks_seeded = !proven && stats.live_marks > 0;
  // Each set of equal points has one vertex in the result (`canonical`: the vertex the engine
  // kept, else the lowest index): one that is no vertex yet (an abandoned insertion) is seeded; a
  // second vertex of the same point (an inexact kernel can insert a duplicate) seeds the vertices
  // around it, whose new stars leave it out. (The engine's skipped duplicates are the other
  // points of each set: nothing to do.) Where every point is a vertex of an exactly built mesh
  // with no flat or inverted tetrahedron, no two points are equal (two vertices at one point would
  // make the tetrahedra around them flat, or the mesh cover that point twice), and the grouping,
  // 0.07 s at 1M points, is skipped.
  const bool all_distinct_vertices =
      consistent && std::all_of(lowest_tetrahedron.begin(), lowest_tetrahedron.end(),
                                [](TetId t) { return t != kNoTet; });
  std::vector<VertexId> canonical;
  if (all_distinct_vertices) {
    canonical.resize(points.size());
    std::iota(canonical.begin(), canonical.end(), VertexId{0});
  } else {
    canonical = canonical_points(points, is_vertex);
  }
  std::vector<VertexId> vertices;
  std::vector<VertexId> second_copies;
  bool any_seed = false;
  for (VertexId v = 0; v < points.size(); ++v) {
    if (canonical[v] == v) {
      vertices.push_back(v);
      if (!is_vertex(v)) {
        seed[v] = 1;
        ++stats.missing_vertices;
      }
      any_seed |= seed[v] != 0;
    } else if (is_vertex(v)) {
      second_copies.push_back(v);
    }
  }
  // Nothing to splay (the usual end of a clean run): no star is read.
  if (!any_seed && second_copies.empty()) {
    stats.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    return;
  }
  // Where the mesh is consistent (built exactly, every tetrahedron positive, no point twice), the
  // tetrahedra at a vertex are found by a walk around it; elsewhere from incidence lists of the
  // whole mesh (a broken mesh's star need not be connected through its faces), which at 1M points
  // take about 0.25 s and 110 MB.
  std::unique_ptr<MeshStars> stars_of_mesh_owned;
  const WalkedMeshStars* walked = nullptr;
  stats.stars_walked = consistent && second_copies.empty();
  if (stats.stars_walked) {
    auto walker = std::make_unique<WalkedMeshStars>(mesh, lowest_tetrahedron);
    walked = walker.get();
    stars_of_mesh_owned = std::move(walker);
  } else {
    // The list the listing above skipped (validated findings) is needed here and in the
    // write-back.
    if (validated != nullptr) listed.ordered = live_tetrahedra(mesh, parts, true).ordered;
    stars_of_mesh_owned = std::make_unique<SharedMeshStars>(mesh, live, parts);
  }
  const MeshStars& stars_of_mesh = *stars_of_mesh_owned;
  std::vector<Quad> around;
  for (const VertexId v : second_copies) {
    stars_of_mesh.tetrahedra_of(v, around);
    for (const Quad& q : around) seed_quad(q);
  }
  auto seeded_vertices = [&] {
    std::vector<VertexId> out;
    for (VertexId v = 0; v < points.size(); ++v) {
      if (seed[v] != 0 && canonical[v] == v) out.push_back(v);
    }
    return out;
  };
  std::vector<VertexId> seeds = seeded_vertices();
  // Flips first (--repair=flips-splay), on a consistent mesh where every distinct point is a
  // vertex: the tetrahedra at the seeds hold every non-Delaunay face, and what the flips leave of
  // those is what the stars must repair. The flips keep the mesh consistent, so the walks still
  // serve, from a live tetrahedron at each vertex: where a vertex's died, one of the flips' new
  // ones at it is alive (a flip keeps its vertices). So `lowest_tetrahedron` is from here on a
  // walk's start, not always the lowest.
  if (flips_first != nullptr && walked != nullptr && stats.missing_vertices == 0 &&
      !seeds.empty()) {
    const auto flipping = Clock::now();
    std::vector<TetId> at_seeds;
    std::vector<TetId> around_seed;
    for (const VertexId v : seeds) {
      walked->tetrahedron_ids_of(v, around_seed);
      at_seeds.insert(at_seeds.end(), around_seed.begin(), around_seed.end());
    }
    std::sort(at_seeds.begin(), at_seeds.end());
    at_seeds.erase(std::unique(at_seeds.begin(), at_seeds.end()), at_seeds.end());
    std::vector<TetId> made;
    std::vector<Quad> left;
    stats.flipped = true;
    stats.flips = (*flips_first)(at_seeds, made, left);
    for (const TetId t : made) {
      if (!mesh.tets.is_alive(t, std::memory_order_relaxed)) continue;
      for (const VertexId v : mesh.tets[t].vertex) {
        if (v == kInfiniteVertex) continue;
        const TetId start = listed.lowest_tetrahedron[v];
        if (!mesh.tets.is_alive(start, std::memory_order_relaxed) ||
            mesh.tets[start].index_of(v) < 0) {
          listed.lowest_tetrahedron[v] = t;
          ++stats.walk_starts_moved;
        }
      }
    }
    stats.faces_left = left.size() / 2;
    std::fill(seed.begin(), seed.end(), 0);
    for (const Quad& q : left) seed_quad(q);
    seeds = seeded_vertices();
    stats.seconds_flipping = std::chrono::duration<double>(Clock::now() - flipping).count();
  }
  stats.seeds = seeds.size();
  if (seeds.empty()) {
    stats.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    return;
  }

  const NearGrid grid(points, [&] {  // the vertices of the mesh
    std::vector<VertexId> present;
    for (const VertexId v : vertices) {
      if (is_vertex(v)) present.push_back(v);
    }
    return present;
  });
  StarSplayer splayer(points, stars_of_mesh, canonical, pool_of(points, vertices),
                      [&](VertexId x, std::vector<VertexId>& out) {
                        grid.near(x, out);
                        std::vector<Quad> around;
                        const std::size_t found = out.size();
                        for (std::size_t i = 0; i < found; ++i) {  // and their neighbours
                          stars_of_mesh.tetrahedra_of(out[i], around);
                          for (const Quad& q : around) {
                            for (const VertexId y : q) {
                              if (y != kInfiniteVertex) out.push_back(y);
                            }
                          }
                        }
                      });
  const auto building = Clock::now();
  splayer.activate_all(seeds, parts);
  const auto enforcing = Clock::now();
  stats.seconds_building = std::chrono::duration<double>(enforcing - building).count();
  splayer.run();
  stats.seconds_enforcing = std::chrono::duration<double>(Clock::now() - enforcing).count();

  // Write back. New: every tetrahedron of an active star, once. Old: every live tetrahedron at an
  // active vertex, replaced. The enforcement made the two agree wherever an inactive vertex is
  // involved, so the new ones fit the kept ones face to face. A broken mesh can defeat that at an
  // inactive vertex (the fast kernel's mesh may hold a face in two pairs of tetrahedra, all locally
  // Delaunay): the vertices of every face that does not fit are splayed too, and the plan is made
  // again.
  std::vector<TetId> dying;
  std::vector<Quad> created;
  std::vector<FaceEntry> faces;
  for (;;) {
    std::vector<Quad> fresh;
    for (const VertexId v : splayer.active_vertices()) {
      for (const Quad& q : splayer.star(v).tetrahedra()) {
        VertexId owner = v;
        for (const VertexId y : q) {
          if (y != kInfiniteVertex && splayer.active(y)) owner = std::min(owner, y);
        }
        if (owner == v) fresh.push_back(q);
      }
    }
    dying.clear();
    if (walked != nullptr) {
      // The walks around the active vertices find the same tetrahedra as the pass below, without
      // reading the whole mesh (sorted here; the order does not change the result).
      std::vector<TetId> around_active;
      for (const VertexId v : splayer.active_vertices()) {
        walked->tetrahedron_ids_of(v, around_active);
        dying.insert(dying.end(), around_active.begin(), around_active.end());
      }
      std::sort(dying.begin(), dying.end());
      dying.erase(std::unique(dying.begin(), dying.end()), dying.end());
    } else {
      for (const TetId i : live) {
        bool touched = false;
        for (const VertexId v : mesh.tets[i].vertex) {
          touched |= v != kInfiniteVertex && splayer.active(v);
        }
        if (touched) dying.push_back(i);
      }
    }
    std::vector<char> is_dying(mesh.tets.size(), 0);  // the flips may have added slots
    for (const TetId t : dying) is_dying[t] = 1;
    faces.clear();
    for (const TetId t : dying) {
      const Tet& tet = mesh.tets[t];
      for (std::size_t f = 0; f < 4; ++f) {
        const FaceRef outside = tet.neighbor[f];
        if (is_dying[ref_tet(outside)] == 0) {
          faces.push_back({face_key(tet.vertex, f), outside, false});
        }
      }
    }
    created = std::move(fresh);
    for (std::size_t j = 0; j < created.size(); ++j) {
      for (std::size_t f = 0; f < 4; ++f) {
        faces.push_back(
            {face_key(created[j], f), face_ref(static_cast<TetId>(j), static_cast<int>(f)), true});
      }
    }
    std::sort(faces.begin(), faces.end(),
              [](const FaceEntry& a, const FaceEntry& b) { return a.key < b.key; });
    // A face fits when exactly two entries have its key, at least one of them new.
    std::vector<VertexId> grow;
    for (std::size_t i = 0; i < faces.size();) {
      std::size_t j = i;
      bool any_new = false;
      while (j < faces.size() && faces[j].key == faces[i].key) any_new |= faces[j++].is_new;
      if (j - i != 2 || !any_new) {
        auto add = [&](VertexId v) {
          if (v != kInfiniteVertex && canonical[v] == v && !splayer.active(v)) grow.push_back(v);
        };
        for (const VertexId v : faces[i].key) add(v);
        // The tetrahedra on the kept side: their other vertices too.
        for (std::size_t k = i; k < j; ++k) {
          if (faces[k].is_new) continue;
          for (const VertexId v : mesh.tets[ref_tet(faces[k].ref)].vertex) add(v);
        }
        if (grow.empty()) {
          throw std::logic_error(
              "star splaying: the repaired region does not fit the mesh around it");
        }
      }
      i = j;
    }
    if (grow.empty()) break;
    ++stats.regrown;
    for (const VertexId v : grow) splayer.activate(v);
    splayer.run();
  }
  stats.stars = splayer.counts().stars;
  stats.offers = splayer.counts().offers;
  stats.changes = splayer.counts().changes;
  std::vector<TetId> ids(created.size());
  for (std::size_t j = 0; j < created.size(); ++j) {
    ids[j] = mesh.tets.allocate();
    Tet& tet = mesh.tets[ids[j]];
    tet.vertex = created[j];
    if (mesh.tets.has_children()) {
      for (auto& c : mesh.tets.children(ids[j])) c.store(kNoTet, std::memory_order_relaxed);
    }
    if (mesh.tets.has_lock_words()) mesh.tets.lock_word(ids[j]).store(0, std::memory_order_relaxed);
  }
  auto resolve = [&](const FaceEntry& e) {
    return e.is_new ? face_ref(ids[ref_tet(e.ref)], ref_face(e.ref)) : e.ref;
  };
  for (std::size_t i = 0; i < faces.size(); i += 2) {
    const FaceRef a = resolve(faces[i]);
    const FaceRef b = resolve(faces[i + 1]);
    mesh.tets[ref_tet(a)].neighbor[static_cast<std::size_t>(ref_face(a))] = b;
    mesh.tets[ref_tet(b)].neighbor[static_cast<std::size_t>(ref_face(b))] = a;
  }
  for (const TetId t : dying) mesh.tets.set_alive(t, false);
  for (const TetId t : ids) mesh.tets.set_alive(t, true);
  stats.tetrahedra_removed = dying.size();
  stats.tetrahedra_created = created.size();
  stats.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace dtlab::engine
