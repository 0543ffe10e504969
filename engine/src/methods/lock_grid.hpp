#pragma once
// The lock-grid method's locks (lock_grid.cpp; after the idea of CGAL's Spatial_lock_grid_3, from
// its documentation): a grid of cells over the input's bounding box, one lock word a cell. A
// thread holds a tetrahedron when it holds the cells of its finite vertices; it takes them before
// reading the tetrahedron for change or writing it (the Sync contract, insertion/sync.hpp) and
// lets them all go when the insertion commits or rolls back. A tetrahedron's vertices do not
// change while it lives (nor while a reader's epoch holds its slot), so two threads that hold the
// same tetrahedron would hold the same cells: never at once. A tetrahedron this insertion created
// may be written again without the new point's cell: its other finite vertices (two or three)
// come from acquired tetrahedra, whose cells this thread holds until it commits or rolls back. The
// locks are coarse and few: most insertions touch one to a few cells, taken once each, against some
// 45 compare-and-swaps a point with a word per tetrahedron.
//
// Waiting without cycles ("wait-die" with fixed priorities): the lower thread id has priority. A
// thread that finds a cell held by a thread of lower priority waits for it; one that finds it held
// by a thread of higher priority gives its insertion up (undo log) and retries the point later.
// Every wait goes from a thread to one of higher id, so no chain of waits closes a cycle, and the
// thread of lowest id among the waiting ones always runs.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <thread>
#include <vector>

#include "dtlab/engine/stats.hpp"
#include "dtlab/predicates/point.hpp"
#include "methods/local_undo_log.hpp"

namespace dtlab::engine {

class LockGrid {
 public:
  // `per_axis` cells on each axis over the bounding box of points[0, count); every point gets its
  // cell (the vertices of the mesh are these points).
  LockGrid(const std::vector<predicates::Point3>& points, std::size_t count, int per_axis)
      : per_axis_(per_axis),
        words_(new std::atomic<std::uint32_t>[static_cast<std::size_t>(per_axis) * per_axis *
                                              per_axis]),
        cell_of_(points.size(), 0) {
    const std::size_t cells = static_cast<std::size_t>(per_axis) * per_axis * per_axis;
    for (std::size_t c = 0; c < cells; ++c) words_[c].store(0, std::memory_order_relaxed);
    predicates::Point3 lo = points[0];
    predicates::Point3 hi = points[0];
    for (std::size_t i = 0; i < count; ++i) {
      lo = {std::min(lo.x, points[i].x), std::min(lo.y, points[i].y), std::min(lo.z, points[i].z)};
      hi = {std::max(hi.x, points[i].x), std::max(hi.y, points[i].y), std::max(hi.z, points[i].z)};
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
      const int x = index_on_axis(points[i].x, lo.x, hi.x);
      const int y = index_on_axis(points[i].y, lo.y, hi.y);
      const int z = index_on_axis(points[i].z, lo.z, hi.z);
      cell_of_[i] = static_cast<std::uint32_t>((z * per_axis + y) * per_axis + x);
    }
  }

  // Cells per axis for n points on `threads` threads: about 256 points a cell, so that an
  // insertion's tetrahedra mostly lie in one or two cells; with several threads at least
  // 2 cbrt(threads) per axis (rounded up), some 8 cells a thread, so that each thread's block of
  // the points has cells inside it that no other thread touches.
  static int cells_per_axis(std::size_t n, int threads) {
    const auto per_axis = static_cast<int>(std::lround(std::cbrt(static_cast<double>(n) / 256.0)));
    const int least =
        threads > 1 ? static_cast<int>(std::ceil(2 * std::cbrt(static_cast<double>(threads)))) : 1;
    return std::clamp(per_axis, least, 256);
  }

  [[nodiscard]] int per_axis() const { return per_axis_; }
  [[nodiscard]] std::uint32_t cell_of(VertexId v) const { return cell_of_[v]; }
  std::atomic<std::uint32_t>& word(std::uint32_t cell) const { return words_[cell]; }

 private:
  // The cell of coordinate c on an axis spanning [lo, hi]; halved first, so that a span beyond
  // the largest double does not overflow.
  [[nodiscard]] int index_on_axis(double c, double lo, double hi) const {
    const double span = 0.5 * hi - 0.5 * lo;
    if (!(span > 0)) return 0;
    const double t = (0.5 * c - 0.5 * lo) / span * per_axis_;
    if (!(t >= 0)) return 0;
    return std::min(static_cast<int>(t), per_axis_ - 1);
  }

  int per_axis_;
  std::unique_ptr<std::atomic<std::uint32_t>[]> words_;  // owner's id (thread + 1), 0: free
  std::vector<std::uint32_t> cell_of_;                   // each point's cell
};

class LockGridSync : public LocalUndoLog {
 public:
  static constexpr bool kLocks = true;

  // `self`: this thread's id + 1 (0 is a free cell); `stop`: the watchdog's; `stress`: a short
  // random delay after one cell in 16, while it is held, to shake out races (--stress).
  LockGridSync(SharedMesh& mesh, const LockGrid& grid, std::uint32_t self, ThreadStats& stats,
               const std::atomic<bool>& stop, bool stress = false)
      : LocalUndoLog(mesh),
        grid_(grid),
        self_(self),
        stats_(stats),
        stop_(stop),
        stress_(stress),
        rng_(self) {}

  // Takes the cells of t's finite vertices; false: the insertion must be given up (a cell held by
  // a thread of higher priority, or the watchdog's stop).
  // (A 16-entry cache of the vertices whose cells were taken, skipping their look-ups, ran 2 %
  // fewer instructions and 11 % longer: medians of 5, 1M uniform by flips on one thread.)
  bool acquire(TetId t) {
    for (const VertexId v : mesh_.tets[t].vertex) {
      if (v != kInfiniteVertex && !take(grid_.cell_of(v))) return false;
    }
    return true;
  }

  void commit() {
    forget();
    release_held();
  }
  void rollback() {
    undo();
    release_held();
  }

 private:
  bool take(std::uint32_t cell) {
    std::atomic<std::uint32_t>& word = grid_.word(cell);
    // Only this thread stores self_ in a word, so a relaxed load that sees it is exact.
    if (word.load(std::memory_order_relaxed) == self_) return true;
    bool waited = false;
    for (int spin = 0;; ++spin) {
      std::uint32_t owner = 0;
      // acquire: what the cell's previous holder wrote under it is visible from here on.
      if (word.compare_exchange_strong(owner, self_, std::memory_order_acquire,
                                       std::memory_order_relaxed)) [[likely]] {
        held_.push_back(cell);
        if (stress_) maybe_delay();
        return true;
      }
      if (owner == 0) continue;         // freed between the load and the compare-and-swap
      if (owner < self_) return false;  // the holder has priority: give up
      if (!waited) {
        waited = true;
        ++stats_.waits;
      }
      if (stop_.load(std::memory_order_relaxed)) return false;
      if (spin > 64) std::this_thread::yield();
    }
  }
  [[gnu::noinline]] void maybe_delay() {
    if (std::uniform_int_distribution<int>(0, 15)(rng_) == 0) {
      std::this_thread::sleep_for(
          std::chrono::microseconds(std::uniform_int_distribution<int>(1, 50)(rng_)));
    }
  }
  // release: this thread's writes under the cells are visible to their next holders.
  void release_held() {
    for (const std::uint32_t cell : held_) grid_.word(cell).store(0, std::memory_order_release);
    held_.clear();
  }

  const LockGrid& grid_;
  std::uint32_t self_;
  ThreadStats& stats_;
  const std::atomic<bool>& stop_;
  bool stress_;
  std::minstd_rand rng_;
  std::vector<std::uint32_t> held_;
};

}  // namespace dtlab::engine
