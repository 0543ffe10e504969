#include "splay_repair.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <thread>

#include "dtlab/engine/point_set_info.hpp"
#include "dtlab/engine/repair.hpp"
#include "dtlab/engine/validator.hpp"
#include "dtlab/predicates/kernels.hpp"
#include "insertion_order.hpp"
#include "parallel_ranges.hpp"
#include "radix_sort.hpp"
#include "star_pieces.hpp"
#include "star_splaying.hpp"
#include "vertex_grid.hpp"
#include "walked_mesh_stars.hpp"

namespace dtlab::engine {
namespace {

using Clock = std::chrono::steady_clock;
using Exact = predicates::AdaptiveKernel;

// Vertices near a point, for the star of a point that no tetrahedron uses: a uniform grid over
// the vertices; the shells around the point's cell are scanned until at least 8 vertices were
// seen, then one shell more. (Nearness only helps the first star; correctness comes from the
// consistency enforcement.) Built at the first question, by whichever thread asks first (a
// consistent mesh, every point a vertex, never asks: the grid of 1M uniform points took
// 20-24 ms, timed alone on the development VM).
class NearGrid {
 public:
  NearGrid(const std::vector<Point3>& points, std::function<std::vector<VertexId>()> vertices)
      : points_(points), vertices_(std::move(vertices)) {}

  void near(VertexId x, std::vector<VertexId>& out) const {
    std::call_once(built_, [this] {
      const std::vector<VertexId> vertices = vertices_();
      if (!vertices.empty()) grid_.emplace(points_, vertices);
    });
    if (!grid_) return;
    const std::array<int, 3> c = grid_->cell(points_[x]);
    for (int r = 0; r < grid_->cells(); ++r) {
      const std::size_t before = out.size();
      grid_->for_shell(c, r, [&out](VertexId v) { out.push_back(v); });
      if (before >= 8) return;  // this shell was the one more after reaching 8
    }
  }

 private:
  const std::vector<Point3>& points_;
  std::function<std::vector<VertexId>()> vertices_;
  mutable std::once_flag built_;
  mutable std::optional<VertexGrid> grid_;
};

// 32 bits of a hash of a point's coordinates (-0.0 read as +0.0, since the two are equal): equal
// points hash alike. Knuth's multiplicative hashing (TAOCP vol. 3, 6.4) with the golden ratio,
// 2^64 / phi, folded over the three bit patterns; the high half of the last product is the key.
std::uint64_t coordinate_hash(const Point3& p) {
  constexpr std::uint64_t kGoldenRatio = 0x9E3779B97F4A7C15ULL;  // floor(2^64 / phi), odd
  auto bits = [](double c) { return std::bit_cast<std::uint64_t>(c == 0.0 ? 0.0 : c); };
  std::uint64_t h = 0;
  for (const double c : {p.x, p.y, p.z}) {
    h = (h ^ bits(c)) * kGoldenRatio;
    h ^= h >> 29;  // the high bits back into the low ones, for the next product
  }
  return h >> 32;  // a 32-bit key: the radix sort skips the four zero digits
}

// canonical[x]: the one index that stands for all the points equal to point x in the result:
// the lowest index among those that `is_vertex` (the engine keeps whichever duplicate it met
// first), else the lowest index. Equal points are found by sorting the indices by a hash of the
// coordinates (linear time, stable: each run of equal hashes keeps its indices increasing), then
// comparing exactly inside each run (two different points with one hash only make a run longer).
template <class IsVertex>
std::vector<VertexId> canonical_points(const std::vector<Point3>& points, IsVertex is_vertex) {
  const std::size_t n = points.size();
  std::vector<KeyedId> keyed(n);
  for (std::size_t i = 0; i < n; ++i)
    keyed[i] = {coordinate_hash(points[i]), static_cast<VertexId>(i)};
  {
    std::vector<KeyedId> scratch(n);
    stable_sort_by_key(keyed.data(), scratch.data(), n);
  }
  std::vector<VertexId> canonical(n);
  std::vector<VertexId> run;
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i + 1;
    while (j < n && keyed[j].first == keyed[i].first) ++j;
    run.clear();
    for (std::size_t k = i; k < j; ++k) run.push_back(keyed[k].second);
    i = j;
    if (run.size() > 1) {
      std::stable_sort(run.begin(), run.end(), [&](VertexId a, VertexId b) {
        return predicates::lexicographically_less(points[a], points[b]);
      });
    }
    for (std::size_t a = 0; a < run.size();) {
      std::size_t b = a;
      VertexId chosen = run[a];
      bool found = false;
      for (; b < run.size() && points[run[b]] == points[run[a]]; ++b) {
        if (!found && is_vertex(run[b])) {
          chosen = run[b];
          found = true;
        }
      }
      for (std::size_t k = a; k < b; ++k) canonical[run[k]] = chosen;
      a = b;
    }
  }
  return canonical;
}

// Four affinely independent vertices of `vertices`.
std::array<VertexId, 4> pool_of(const std::vector<Point3>& points,
                                const std::vector<VertexId>& vertices) {
  const SimplexSearch s = find_simplex(points, vertices);
  if (!s.simplex) throw std::invalid_argument("star splaying: the points do not span 3D");
  return *s.simplex;
}

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

// A tetrahedron list as MeshStars (ids already checked and mapped to representatives).
class ListMeshStars : public MeshStars {
 public:
  ListMeshStars(std::size_t n, const std::vector<Tetrahedron>& tets) : first_(n + 1, 0) {
    for (const Tetrahedron& t : tets) {
      for (const VertexId v : t) ++first_[v + 1];
    }
    std::partial_sum(first_.begin(), first_.end(), first_.begin());
    of_.resize(first_.back());
    std::vector<std::uint32_t> fill(first_.begin(), first_.end() - 1);
    for (std::size_t i = 0; i < tets.size(); ++i) {
      for (const VertexId v : tets[i]) of_[fill[v]++] = static_cast<std::uint32_t>(i);
    }
    tets_ = &tets;
  }
  void tetrahedra_of(VertexId x, std::vector<Quad>& out) const override {
    out.clear();
    for (std::uint32_t i = first_[x]; i < first_[x + 1]; ++i) out.push_back((*tets_)[of_[i]]);
  }

 private:
  std::vector<std::uint32_t> first_;
  std::vector<std::uint32_t> of_;
  const std::vector<Tetrahedron>* tets_ = nullptr;
};

struct FaceEntry {
  std::array<VertexId, 3> key;
  FaceRef ref;
  bool is_new;
};

std::array<VertexId, 3> face_key(const Quad& q, std::size_t f) {
  const auto& fv = kFaceVertex[f];
  std::array<VertexId, 3> k{q[static_cast<std::size_t>(fv[0])], q[static_cast<std::size_t>(fv[1])],
                            q[static_cast<std::size_t>(fv[2])]};
  std::sort(k.begin(), k.end());
  return k;
}

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

std::vector<Tetrahedron> splay_tetrahedra(const std::vector<Point3>& points,
                                          const std::vector<Tetrahedron>& tets, SplayStats& stats,
                                          int threads) {
  const auto t0 = Clock::now();
  stats.done = true;
  // Duplicates: each set is named by its lowest index.
  const std::vector<VertexId> representative =
      canonical_points(points, [](VertexId /*v*/) { return false; });
  std::vector<VertexId> vertices;
  for (VertexId v = 0; v < points.size(); ++v) {
    if (representative[v] == v) vertices.push_back(v);
  }
  std::vector<Tetrahedron> mapped;
  mapped.reserve(tets.size());
  for (Tetrahedron t : tets) {
    for (auto& v : t) v = representative[v];
    mapped.push_back(t);
  }
  const ListMeshStars stars_of_mesh(points.size(), mapped);
  const NearGrid grid(points, [&] { return vertices; });
  StarSplayer splayer(points, stars_of_mesh, representative, pool_of(points, vertices),
                      [&](VertexId x, std::vector<VertexId>& out) { grid.near(x, out); });
  std::vector<Quad> around;
  for (const VertexId v : vertices) {
    stars_of_mesh.tetrahedra_of(v, around);
    if (around.empty()) ++stats.missing_vertices;
  }
  splayer.activate_all(vertices, threads);
  stats.seeds = vertices.size();
  splayer.run();
  // Stars that agree but fall apart into pieces (a lone input tetrahedron keeps its four to
  // itself): each piece is bridged to another by its closest pair across, an edge every star
  // keeps, until one piece holds every vertex (star_pieces.hpp). Each round must leave fewer
  // pieces; one that does not is an error, not a loop without end.
  std::size_t bridged_before = vertices.size();
  for (;;) {
    const auto bridges =
        closest_pairs_across(points, vertices, pieces_of_stars(points.size(), vertices, splayer));
    if (bridges.empty()) break;
    if (bridges.size() >= bridged_before) {
      throw std::logic_error("star splaying: bridging did not join the pieces of agreeing stars");
    }
    bridged_before = bridges.size();
    stats.bridges += bridges.size();
    for (const auto& [x, y] : bridges) splayer.introduce(x, y);
    splayer.run();
  }
  stats.stars = splayer.counts().stars;
  stats.offers = splayer.counts().offers;
  stats.changes = splayer.counts().changes;
  std::vector<Tetrahedron> out;
  for (const VertexId v : vertices) {
    for (const Quad& q : splayer.star(v).tetrahedra()) {
      if (std::find(q.begin(), q.end(), kInfiniteVertex) != q.end()) continue;
      if (*std::min_element(q.begin(), q.end()) == v) out.push_back(q);
    }
  }
  stats.tetrahedra_created = out.size();
  stats.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return out;
}

namespace {

// A tetrahedron list as a SharedMesh closed by the vertex at infinity, as the engine builds one:
// a slot per tetrahedron, neighbours matched by face keys, and an infinite tetrahedron on every
// boundary face (its face listed with the finite tetrahedron's vertex on the negative side, then
// the vertex at infinity), those matched with each other across the boundary edges. False where
// a face or a boundary edge is not on exactly two, or where the boundary is not one sphere (one
// component, V - E + F = 2: a ball beside a solid torus passes the validator's Euler
// characteristic, 1 + 0, but no walk or star would ever join the two); the store is then unusable.
bool close_into_mesh(const std::vector<Tetrahedron>& tets, SharedMesh& mesh) {
  mesh.tets.keep_children(false);
  mesh.tets.keep_lock_words(false);
  std::vector<FaceEntry> faces;
  faces.reserve(4 * tets.size());
  for (const Tetrahedron& q : tets) {
    const TetId t = mesh.tets.allocate();
    mesh.tets[t].vertex = q;
    mesh.tets.set_alive(t, true);
    for (std::size_t f = 0; f < 4; ++f) {
      faces.push_back({face_key(q, f), face_ref(t, static_cast<int>(f)), false});
    }
  }
  auto by_key = [](const FaceEntry& a, const FaceEntry& b) { return a.key < b.key; };
  std::sort(faces.begin(), faces.end(), by_key);
  // Pairs are linked; a face met once is on the boundary and gets its infinite tetrahedron.
  std::vector<FaceEntry> hull_edges;
  auto link = [&](FaceRef a, FaceRef b) {
    mesh.tets[ref_tet(a)].neighbor[static_cast<std::size_t>(ref_face(a))] = b;
    mesh.tets[ref_tet(b)].neighbor[static_cast<std::size_t>(ref_face(b))] = a;
  };
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j - i > 2) return false;
    if (j - i == 2) {
      link(faces[i].ref, faces[i + 1].ref);
    } else {
      const Tet& finite = mesh.tets[ref_tet(faces[i].ref)];
      const auto& fv = kFaceVertex[static_cast<std::size_t>(ref_face(faces[i].ref))];
      const Quad q{finite.vertex[static_cast<std::size_t>(fv[0])],
                   finite.vertex[static_cast<std::size_t>(fv[1])],
                   finite.vertex[static_cast<std::size_t>(fv[2])], kInfiniteVertex};
      const TetId u = mesh.tets.allocate();
      mesh.tets[u].vertex = q;
      mesh.tets.set_alive(u, true);
      link(faces[i].ref, face_ref(u, 3));
      for (std::size_t f = 0; f < 3; ++f) {
        hull_edges.push_back({face_key(q, f), face_ref(u, static_cast<int>(f)), false});
      }
    }
    i = j;
  }
  std::sort(hull_edges.begin(), hull_edges.end(), by_key);
  const std::size_t boundary_faces = hull_edges.size() / 3;
  if (boundary_faces == 0) return false;
  // The boundary's pieces: its faces (the infinite tetrahedra, slots after the finite ones) joined
  // across the edges they share.
  const auto first_infinite = static_cast<TetId>(tets.size());
  std::vector<TetId> piece(boundary_faces);
  std::iota(piece.begin(), piece.end(), TetId{0});
  auto find = [&](TetId x) {
    while (piece[x] != x) x = piece[x] = piece[piece[x]];
    return x;
  };
  for (std::size_t i = 0; i < hull_edges.size(); i += 2) {
    if (i + 1 >= hull_edges.size() || hull_edges[i].key != hull_edges[i + 1].key ||
        (i + 2 < hull_edges.size() && hull_edges[i + 2].key == hull_edges[i].key)) {
      return false;
    }
    link(hull_edges[i].ref, hull_edges[i + 1].ref);
    const TetId a = find(ref_tet(hull_edges[i].ref) - first_infinite);
    const TetId b = find(ref_tet(hull_edges[i + 1].ref) - first_infinite);
    piece[std::max(a, b)] = std::min(a, b);
  }
  for (TetId f = 0; f < boundary_faces; ++f) {
    if (find(f) != 0) return false;
  }
  std::vector<VertexId> on_boundary;
  for (TetId f = 0; f < boundary_faces; ++f) {
    const Tet& u = mesh.tets[first_infinite + f];
    on_boundary.insert(on_boundary.end(), u.vertex.begin(), u.vertex.begin() + 3);
  }
  std::sort(on_boundary.begin(), on_boundary.end());
  const auto boundary_vertices = static_cast<std::size_t>(
      std::unique(on_boundary.begin(), on_boundary.end()) - on_boundary.begin());
  const std::size_t boundary_edges = hull_edges.size() / 2;
  return boundary_vertices + boundary_faces == boundary_edges + 2;
}

// Whether the tetrahedra at every vertex are connected through the faces that contain it: the
// walks of WalkedMeshStars then find them all. The validator's mesh_consistent() does not say so
// for any list: two fans that meet at one vertex only, their boundaries closed, pass it.
bool every_star_connected(const SharedMesh& mesh, std::size_t point_count,
                          std::vector<TetId>& some_tetrahedron, int threads) {
  std::vector<std::uint32_t> incident(point_count, 0);
  some_tetrahedron.assign(point_count, kNoTet);
  for (TetId t = 0; t < mesh.tets.size(); ++t) {
    for (const VertexId v : mesh.tets[t].vertex) {
      if (v == kInfiniteVertex) continue;
      ++incident[v];
      if (some_tetrahedron[v] == kNoTet) some_tetrahedron[v] = t;
    }
  }
  const WalkedMeshStars walks(mesh, some_tetrahedron);
  std::atomic<bool> connected{true};
  in_parallel_ranges(point_count, std::max(threads, 1),
                     [&](std::size_t begin, std::size_t end, std::size_t /*part*/) {
                       std::vector<TetId> around;
                       for (std::size_t v = begin; v < end && connected.load(); ++v) {
                         if (incident[v] == 0) continue;
                         walks.tetrahedron_ids_of(static_cast<VertexId>(v), around);
                         if (around.size() != incident[v]) connected.store(false);
                       }
                     });
  return connected.load();
}

// dtlab repair of a list that is already a tetrahedralization of the hull of distinct points,
// Delaunay or not: closed by the vertex at infinity into a mesh whose boundary is one sphere and
// whose vertex stars are connected (the cheap checks first), then judged consistent() by the
// exact validator (oriented, manifold, every point a vertex, Euler characteristic 1, a convex
// boundary and the hull's exact volume: one cover of the hull, proven, not sampled). Such a list
// is the mesh burglary's post-check hands over, and is splayed the same way, from the faces the
// validation rejected only (docs/design.md, "dtlab repair, locally"). Empty for any other list
// (the caller splays every vertex); `seconds_checking` is then what the checks took.
std::optional<std::vector<Tetrahedron>> repair_locally(const std::vector<Point3>& points,
                                                       const std::vector<Tetrahedron>& tets,
                                                       SplayStats& stats, int threads) {
  const auto t0 = Clock::now();
  auto give_up = [&]() -> std::optional<std::vector<Tetrahedron>> {
    stats.seconds_checking = std::chrono::duration<double>(Clock::now() - t0).count();
    return std::nullopt;
  };
  const std::vector<VertexId> canonical =
      canonical_points(points, [](VertexId /*v*/) { return false; });
  for (VertexId v = 0; v < points.size(); ++v) {
    if (canonical[v] != v) return give_up();  // equal points: named as the global path names
  }
  SharedMesh mesh(points);
  std::vector<TetId> some_tetrahedron;
  if (!close_into_mesh(tets, mesh) ||
      !every_star_connected(mesh, points.size(), some_tetrahedron, threads)) {
    return give_up();
  }
  const ValidationReport report = validate(points, tets, ValidateWith::Adaptive, threads, true);
  if (!report.consistent()) return give_up();
  stats.seconds_checking = std::chrono::duration<double>(Clock::now() - t0).count();
  const ValidatedFindings found = validated_findings(report, points.size(), {});
  splay_shared_mesh(mesh, {}, true, threads, stats, &found);
  stats.local = true;
  std::vector<Tetrahedron> out =
      mesh.finite_tetrahedra(static_cast<VertexId>(points.size()), {}, threads);
  stats.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return out;
}

// The local repair where the list allows it, else every vertex splayed (`seconds` then includes
// the checks that sent it there).
std::vector<Tetrahedron> repair_list(const std::vector<Point3>& points,
                                     const std::vector<Tetrahedron>& tets, SplayStats& stats,
                                     int threads) {
  if (auto local = repair_locally(points, tets, stats, threads)) return *std::move(local);
  const double checking = stats.seconds_checking;
  std::vector<Tetrahedron> out = splay_tetrahedra(points, tets, stats, threads);
  stats.seconds += checking;
  return out;
}

}  // namespace

std::vector<Tetrahedron> repair(const std::vector<Point3>& points,
                                const std::vector<Tetrahedron>& tets, SplayStats& stats,
                                int threads) {
  if (threads == kAllThreads) {
    threads = static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
  }
  double max_abs = 0.0;
  double min_abs = 0.0;
  for (const Point3& p : points) {
    for (const double c : {p.x, p.y, p.z}) {
      if (!std::isfinite(c)) throw TriangulationError("input has a NaN or infinite coordinate");
      const double m = std::fabs(c);
      max_abs = std::max(max_abs, m);
      if (m > 0.0 && (min_abs == 0.0 || m < min_abs)) min_abs = m;
    }
  }
  for (const Tetrahedron& t : tets) {
    for (const VertexId v : t) {
      if (v >= points.size()) throw TriangulationError("a tetrahedron names a missing vertex");
    }
  }
  if (analyze(points).dimension < 3) {
    throw TriangulationError("no tetrahedralization exists: the points span less than 3D");
  }
  // The engine's lossless power-of-two scaling keeps the exact stages off their GMP fallback.
  const RangeScaling scaling = adaptive_range_scaling(max_abs, min_abs);
  if (!scaling.lossless) return repair_list(points, tets, stats, threads);
  std::vector<Point3> scaled = points;
  for (Point3& p : scaled) {
    p = {std::ldexp(p.x, scaling.exponent), std::ldexp(p.y, scaling.exponent),
         std::ldexp(p.z, scaling.exponent)};
  }
  return repair_list(scaled, tets, stats, threads);
}

}  // namespace dtlab::engine
