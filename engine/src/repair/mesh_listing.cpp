// The shared mesh read for star splaying (mesh_listing.hpp).
#include "repair/mesh_listing.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <memory>

#include "location/insertion_order.hpp"
#include "support/parallel_ranges.hpp"

namespace dtlab::engine {

SharedMeshStars::SharedMeshStars(const SharedMesh& mesh, const std::vector<TetId>& live,
                                 int threads)
    : mesh_(mesh), first_(mesh.points.size() + 1, 0) {
  const std::size_t n = mesh.points.size();
  const int parts = std::clamp(threads, 1, 4);
  std::vector<std::vector<std::uint32_t>> at(static_cast<std::size_t>(parts));
  in_parallel_ranges(live.size(), parts, [&](std::size_t begin, std::size_t end, std::size_t part) {
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
  in_parallel_ranges(live.size(), parts, [&](std::size_t begin, std::size_t end, std::size_t part) {
    std::vector<std::uint32_t>& place = at[part];
    for (std::size_t i = begin; i < end; ++i) {
      for (const VertexId v : mesh.tets[live[i]].vertex) {
        if (v != kInfiniteVertex) of_[place[v]++] = live[i];
      }
    }
  });
}

void SharedMeshStars::tetrahedra_of(VertexId x, std::vector<Quad>& out) const {
  out.clear();
  for (std::uint32_t i = first_[x]; i < first_[x + 1]; ++i)
    out.push_back(mesh_.tets[of_[i]].vertex);
}

namespace {

// The scan's blocks: the cells of a 2^k x 2^k x 2^k grid over the points' bounding box, numbered
// along the Hilbert curve (consecutive blocks are face-adjacent cells): k is the largest (at most
// 7) with 8^k cells for at least 4 points each, so a cell holds 4 to 32 points on uniform data
// (docs/performance.md, "Measured choices"). A tetrahedron belongs to the cell of its lowest
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
// reused slots. Cells of several points keep each thread's counts in cache. docs/experiments.md
// has the orders measured.
// The first pass also lowers each vertex's lowest live tetrahedron, the threads together with
// relaxed compare-and-swaps (a thread's own ids only grow, so one rarely retries).
// `ordered` false: the first pass's lowest tetrahedra alone (no cells, no list), where no scan
// is to run.
}  // namespace

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
  // the store's 32 and the cells (docs/performance.md, "Measured choices"). Left uninitialized:
  // the first pass writes every entry.
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

}  // namespace dtlab::engine
