// The engine's entry point (dtlab/engine/triangulate.hpp): checks the input, orders and scales the
// points in place, bounds them (the vertex at infinity or the paper's auxiliary tetrahedron), runs
// the method from the registry on them, and puts the points and the output back in the input's
// numbering.
#include "dtlab/engine/triangulate.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <utility>

#include "driver/point_transforms.hpp"
#include "dtlab/engine/methods.hpp"
#include "dtlab/engine/point_set_info.hpp"
#include "dtlab/engine/run_monitor.hpp"
#include "location/insertion_order.hpp"
#include "location/location_policy.hpp"
#include "mesh/tet_store.hpp"
#include "methods/registry.hpp"
#include "support/parallel_ranges.hpp"
#include "support/worker_pool.hpp"

namespace dtlab::engine {
namespace {

using Clock = std::chrono::steady_clock;

std::uint64_t peak_rss_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024;  // Linux reports KiB
}

// The caller's points as the methods take them, changed in place (no second copy at the run's
// peak): in insertion order where the location mode stores them so, and scaled by a power of two.
// restore() puts them back as given.
class PreparedPoints {
 public:
  PreparedPoints(std::vector<Point3>& points, const TriangulateOptions& options, int threads,
                 TriangulationStats& stats)
      : points_(points), input_count_(points.size()), threads_(threads) {
    stats.points = input_count_;
    if (input_count_ >= static_cast<std::size_t>(kInfiniteVertex) - 8) {
      throw TriangulationError("too many points for 32-bit vertex ids");
    }
    const bool walk_order = resolve_location(options.location).order == InsertionOrder::BrioHilbert;
    // The first tetrahedron and the walk mode's order come from the input as given. The random
    // order is drawn beside the scans of the coordinates (magnitudes, and the walk mode's curve
    // frame, the points' box read in their own order): the shuffle is one thread's sequence, and
    // the scans need nothing from it.
    CoordinateMagnitudes magnitudes;
    auto draw_order = [&] { order_ = random_order(input_count_, options.seed); };
    auto scan = [&] {
      magnitudes = coordinate_magnitudes(points);
      if (walk_order && magnitudes.finite) frame_ = hilbert_frame(points, input_count_);
    };
    if (threads_ > 1) {
      in_parallel_ranges(
          2, 2,
          [&](std::size_t, std::size_t, std::size_t part) { part == 0 ? scan() : draw_order(); },
          /*minimum=*/0);
    } else {
      scan();
      draw_order();
    }
    if (!magnitudes.finite) throw TriangulationError("input has a NaN or infinite coordinate");
    const SimplexSearch search = find_simplex(points, order_);
    if (!search.simplex) {
      throw TriangulationError("no tetrahedralization exists: the affine dimension of the " +
                               std::to_string(input_count_) + " input points is " +
                               dimension_name(search.dimension) +
                               "; at least 4 points not in one plane are needed");
    }
    simplex_ = *search.simplex;
    if (walk_order) store_in_order();
    // Exact power-of-two scaling of the largest magnitude into [2^99, 2^100) (signs are
    // unchanged), for every kernel when it is lossless, so that all kernels see the same numbers;
    // undone before the points are handed back. Every input is taken: when some coordinates still
    // lie outside the range where expansion arithmetic is exact (valid_range.hpp), the adaptive
    // and filtered kernels hand the calls their float stage cannot decide to GMP.
    scaling_ = adaptive_range_scaling(magnitudes.max_abs, magnitudes.min_abs_nonzero);
    if (scaling_.lossless) {
      stats.scale_exponent = scaling_.exponent;
      scale_points(points, scaling_.exponent, threads_);
    }
  }

  // The caller's points again: unscaled (exact, the scaling is lossless), auxiliary points
  // dropped, in input order.
  void restore() {
    points_.resize(input_count_);
    if (scaling_.lossless) scale_points(points_, -scaling_.exponent, threads_);
    if (!input_index_.empty()) unpermute(points_, input_index_, threads_);
  }

  // The output's ids from the engine's numbering to the input's, equal points named by their
  // lowest index: after a walk-mode run with duplicates (its BRIO order renumbered them), and
  // after star splaying repaired an inexact kernel's mesh, which keeps whichever copy the mesh had
  // (the DAG mode's input order names an exact kernel's duplicates right already).
  void to_input_ids(std::vector<Tetrahedron>& tets, const std::vector<Point3>& input,
                    bool duplicates, bool inexact_repaired) const {
    if (input_index_.empty()) {  // the DAG mode keeps the input's order
      if (inexact_repaired) name_duplicates_by_lowest_index(input, tets);
      return;
    }
    in_parallel_ranges(tets.size(), threads_, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t i = begin; i < end; ++i) {
        for (auto& v : tets[i]) v = input_index_[v];
      }
    });
    if (duplicates || inexact_repaired) name_duplicates_by_lowest_index(input, tets);
  }

  [[nodiscard]] std::vector<Point3>& points() { return points_; }
  [[nodiscard]] std::size_t input_count() const { return input_count_; }
  [[nodiscard]] const std::vector<std::uint32_t>& order() const { return order_; }
  [[nodiscard]] const std::array<std::uint32_t, 4>& simplex() const { return simplex_; }

 private:
  // The BRIO and Hilbert order (each parallel thread inserts its share of it, in that order),
  // with the vertices renumbered in it: the points are stored in the order they are inserted, so
  // that the points of neighbouring tetrahedra lie close in memory.
  void store_in_order() {
    brio_hilbert_order(points_, order_, threads_, &frame_);
    input_index_ = std::move(order_);
    // The first tetrahedron's engine ids, by one pass over the map rather than through its
    // inverse: a 4-byte-a-point inverse came from the heap (glibc raises its mmap threshold once
    // a large block is freed) and, freed, stayed resident at the run's peak. Each id is found in
    // one thread's range only, so the threads write different entries.
    const std::array<std::uint32_t, 4> simplex_input = simplex_;
    in_parallel_ranges(input_count_, threads_,
                       [&](std::size_t begin, std::size_t end, std::size_t) {
                         for (std::size_t i = begin; i < end; ++i) {
                           for (std::size_t k = 0; k < 4; ++k) {
                             if (input_index_[i] == simplex_input[k])
                               simplex_[k] = static_cast<std::uint32_t>(i);
                           }
                         }
                       });
    permute(points_, input_index_, threads_);
    order_.clear();  // the identity: insertion order is storage order now (4 bytes a point less)
    order_.shrink_to_fit();
  }

  std::vector<Point3>& points_;
  std::size_t input_count_;
  int threads_;
  std::vector<std::uint32_t> order_;        // insertion order (empty: the identity)
  std::vector<std::uint32_t> input_index_;  // engine vertex id -> input index, or empty
  std::array<std::uint32_t, 4> simplex_{};  // the first tetrahedron, in the engine's ids
  HilbertFrame frame_{};                    // the walk mode's curve's cube
  RangeScaling scaling_;
};

// The paper's auxiliary tetrahedron around the points, appended to them: (m,0,0), (0,m,0),
// (0,0,m), (-m,-m,-m) around the box centre, m = 200 x the box size; removed with every
// tetrahedron touching it at the end. Returns its four ids.
std::array<std::uint32_t, 4> add_auxiliary_tetrahedron(std::vector<Point3>& points) {
  Point3 lo = points[0];
  Point3 hi = points[0];
  for (const Point3& p : points) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  const double size = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  const double m = 200.0 * size;
  const Point3 c{(lo.x + hi.x) / 2, (lo.y + hi.y) / 2, (lo.z + hi.z) / 2};
  const auto n = static_cast<std::uint32_t>(points.size());
  points.push_back({c.x + m, c.y, c.z});
  points.push_back({c.x, c.y + m, c.z});
  points.push_back({c.x, c.y, c.z + m});
  points.push_back({c.x - m, c.y - m, c.z - m});
  // Only reachable when the scaling was not lossless and the magnitudes are near DBL_MAX.
  for (std::size_t i = n; i < points.size(); ++i) {
    if (!std::isfinite(points[i].x) || !std::isfinite(points[i].y) || !std::isfinite(points[i].z)) {
      throw TriangulationError(
          "the auxiliary tetrahedron (200 x the bounding box) overflows double; use "
          "--bounding infinite");
    }
  }
  return {n, n + 1, n + 2, n + 3};
}

// The method's run on the prepared points, bounded as options.bounding asks. On any exception
// the points are restored first; the store's limit becomes an error with the input's size.
std::vector<Tetrahedron> run_method(PreparedPoints& prepared, const TriangulateOptions& options,
                                    TriangulationStats& stats, Clock::time_point start) {
  try {
    const bool infinite = options.bounding == Bounding::Infinite;
    const std::array<std::uint32_t, 4> first =
        infinite ? prepared.simplex() : add_auxiliary_tetrahedron(prepared.points());
    stats.seconds.ordering = std::chrono::duration<double>(Clock::now() - start).count();
    return method_run(options.method)(MethodInput{prepared.points(), prepared.input_count(),
                                                  prepared.order(), first, infinite, options},
                                      stats);
  } catch (const StoreFull& e) {
    prepared.restore();
    throw RunFailed(std::string(e.what()) + "; " + std::to_string(prepared.input_count()) +
                    " points need more in this run");
  } catch (...) {
    prepared.restore();
    throw;
  }
}

// Measured outside seconds.total: the exact hull's tetrahedra that the auxiliary run lost.
std::int64_t hull_tetrahedra_lost(const std::vector<Point3>& input,
                                  const TriangulateOptions& options,
                                  const std::vector<Tetrahedron>& tets) {
  TriangulateOptions reference = options;
  reference.bounding = Bounding::Infinite;
  reference.audit = false;
  reference.progress = false;
  reference.monitor = nullptr;
  const auto exact = canonical_tetrahedra(triangulate(input, reference).tetrahedra);
  const auto aux = canonical_tetrahedra(tets);
  std::vector<Tetrahedron> lost;
  std::set_difference(exact.begin(), exact.end(), aux.begin(), aux.end(), std::back_inserter(lost));
  return static_cast<std::int64_t>(lost.size());
}

// The run on the caller's points, which it scales and reorders in place and puts back as they
// were, on every path out. When `as_given` (the same points, untouched) is there, `points` is a
// scratch copy: it is not put back after a finished run, and the duplicates' names and the
// auxiliary run's reference come from `as_given`.
Triangulation triangulate_in_place(std::vector<Point3>& points, const TriangulateOptions& options,
                                   const std::vector<Point3>* as_given) {
  const auto start = Clock::now();
  if (const auto why = unsupported(options)) throw std::invalid_argument(*why);
  if (options.monitor != nullptr) {
    options.monitor->done.store(0, std::memory_order_relaxed);
    options.monitor->total.store(points.size(), std::memory_order_relaxed);
  }
  Triangulation result;
  TriangulationStats& stats = result.stats;
  // The steps over whole arrays before the first insertion and after the last run on the
  // method's threads (one for the sequential engine, so that its time stays one thread's).
  const int threads = method_info(options.method).parallel ? std::max(1, options.threads) : 1;
  // Those threads are started once for the run (support/worker_pool.hpp): this one and
  // threads - 1 workers, which every step's parallel helpers take.
  std::optional<WorkerPool> workers;
  if (threads > 1) workers.emplace(threads - 1);
  std::optional<PoolScope> run_threads(std::in_place, workers ? &*workers : nullptr);
  PreparedPoints prepared(points, options, threads, stats);
  result.tetrahedra = run_method(prepared, options, stats, start);

  const auto finish_start = Clock::now();
  if (as_given == nullptr) prepared.restore();
  const std::vector<Point3>& input = as_given != nullptr ? *as_given : points;
  // The engine's duplicate count finds equal points under an exact kernel; the fast kernel can
  // miss one (abandon it, or insert it as a second vertex), and star splaying then keeps whichever
  // copy the mesh had.
  const bool inexact_repaired = options.kernel == KernelKind::Fast && stats.splay.done;
  prepared.to_input_ids(result.tetrahedra, input, stats.duplicates > 0, inexact_repaired);
  stats.seconds.output += std::chrono::duration<double>(Clock::now() - finish_start).count();
  stats.tetrahedra = result.tetrahedra.size();
  run_threads.reset();  // the workers joined within the run's time, as its threads were before
  workers.reset();
  // The post-check's validation is a measurement, not part of the method.
  stats.seconds.total =
      std::chrono::duration<double>(Clock::now() - start).count() - stats.post_check.seconds_check;
  stats.seconds.other = std::max(0.0, stats.seconds.total - stats.seconds.location -
                                          stats.seconds.subdivision - stats.seconds.legalization);
  if (options.bounding == Bounding::AuxTet) {
    stats.hull_tetrahedra_lost = hull_tetrahedra_lost(input, options, result.tetrahedra);
  }
  stats.peak_rss_bytes = peak_rss_bytes();
  if (options.monitor != nullptr) options.monitor->done.store(options.monitor->total.load());
  return result;
}

}  // namespace

std::vector<Tetrahedron> canonical_tetrahedra(std::vector<Tetrahedron> tets) {
  for (auto& t : tets) {
    // A sorting network for four: each exchange is one transposition, so the count of exchanges
    // made gives the parity of the permutation that sorted the ids.
    bool odd = false;
    const auto order = [&t, &odd](std::size_t i, std::size_t j) {
      if (t[j] < t[i]) {
        std::swap(t[i], t[j]);
        odd = !odd;
      }
    };
    order(0, 1);
    order(2, 3);
    order(0, 2);
    order(1, 3);
    order(1, 2);
    if (odd) std::swap(t[2], t[3]);  // back to an even permutation of the ids as given
  }
  std::sort(tets.begin(), tets.end());
  return tets;
}

Triangulation triangulate(const std::vector<Point3>& input, const TriangulateOptions& options) {
  std::vector<Point3> points = input;
  return triangulate_in_place(points, options, &input);
}

Triangulation triangulate(std::vector<Point3>&& input, const TriangulateOptions& options) {
  Triangulation result = triangulate_in_place(input, options, nullptr);
  result.points = std::move(input);
  return result;
}

}  // namespace dtlab::engine
