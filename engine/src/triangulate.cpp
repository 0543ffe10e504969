// Driver of the sequential engine: input scaling, insertion order, bounding, kernel dispatch,
// stats.
#include "dtlab/engine/triangulate.hpp"

#include <sys/resource.h>

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "dtlab/engine/point_set_info.hpp"
#include "dtlab/predicates/audit.hpp"
#include "dtlab/predicates/kernels.hpp"
#include "incremental_delaunay.hpp"
#include "insertion_order.hpp"
#include "parallel_methods.hpp"
#include "parallel_ranges.hpp"
#include "splay_repair.hpp"

namespace dtlab::engine {
namespace {

using Clock = std::chrono::steady_clock;

std::uint64_t peak_rss_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024;  // Linux reports KiB
}

class Progress {
 public:
  Progress(bool enabled, std::size_t total)
      : enabled_(enabled), total_(total), start_(Clock::now()) {}
  void update(std::size_t done) {
    if (!enabled_ || (done & 0x3FFF) != 0) return;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    if (elapsed < 2.0) return;
    std::fprintf(stderr, "\r[dtlab] inserted %zu / %zu points (%.0f%%), %.1f s", done, total_,
                 100.0 * static_cast<double>(done) / static_cast<double>(total_), elapsed);
    shown_ = true;
  }
  ~Progress() {
    if (shown_) std::fprintf(stderr, "\n");
  }

 private:
  bool enabled_;
  std::size_t total_;
  Clock::time_point start_;
  bool shown_ = false;
};

}  // namespace

template <class K>
std::vector<Tetrahedron> run_sequential(const std::vector<Point3>& points, std::size_t input_count,
                                        const std::vector<std::uint32_t>& order,
                                        const std::array<std::uint32_t, 4>& first, bool skip_first,
                                        const TriangulateOptions& options,
                                        TriangulationStats& stats) {
  IncrementalDelaunay<K> dt(points, options, stats);
  dt.start(first[0], first[1], first[2], first[3]);
  if (skip_first) stats.inserted += 4;
  // An empty order is the identity (the walk mode stores the points in insertion order).
  const std::size_t count = order.empty() ? input_count : order.size();
  Progress progress(options.progress, count);
  for (std::size_t i = 0; i < count; ++i) {
    const auto v = order.empty() ? static_cast<std::uint32_t>(i) : order[i];
    progress.update(i + 1);
    if (skip_first && (v == first[0] || v == first[1] || v == first[2] || v == first[3])) continue;
    switch (dt.insert(v)) {
      case IncrementalDelaunay<K>::Outcome::Inserted:
        ++stats.inserted;
        break;
      case IncrementalDelaunay<K>::Outcome::Duplicate:
        ++stats.duplicates;
        break;
      case IncrementalDelaunay<K>::Outcome::GaveUp:  // no policy gives up in the sequential engine
      case IncrementalDelaunay<K>::Outcome::Unlocated:
      case IncrementalDelaunay<K>::Outcome::Abandoned:
        ++stats.abandoned_insertions;
        break;
    }
  }
  stats.store_slots = dt.store_slots();
  stats.dag_nodes = options.location == Location::Walk ? 0 : dt.store_slots();
  stats.predicate_calls = dt.predicate_calls();
  stats.location_steps = dt.location_steps();
  stats.walk_fallbacks = dt.walk_fallbacks();
  if (splays(options.repair))
    splay_shared_mesh(dt.mesh(), {}, options.kernel != KernelKind::Fast, 1, stats.splay);
  const auto output_start = Clock::now();
  std::vector<Tetrahedron> result = dt.take_finite_tetrahedra(static_cast<VertexId>(input_count));
  stats.seconds.output += std::chrono::duration<double>(Clock::now() - output_start).count();
  return result;
}

#define DTLAB_INSTANTIATE(K)                                                      \
  template std::vector<Tetrahedron> run_sequential<K>(                            \
      const std::vector<Point3>&, std::size_t, const std::vector<std::uint32_t>&, \
      const std::array<std::uint32_t, 4>&, bool, const TriangulateOptions&, TriangulationStats&);
DTLAB_FOR_EACH_KERNEL(DTLAB_INSTANTIATE)
#undef DTLAB_INSTANTIATE

namespace {

template <class K>
std::vector<Tetrahedron> run_method(const std::vector<Point3>& points, std::size_t input_count,
                                    const std::vector<std::uint32_t>& order,
                                    const std::array<std::uint32_t, 4>& first, bool skip_first,
                                    const TriangulateOptions& options, TriangulationStats& stats) {
  if (options.method == Method::Sequential) {
    return run_sequential<K>(points, input_count, order, first, skip_first, options, stats);
  }
  return run_parallel<K>(points, input_count, order, first, skip_first, options, stats);
}

template <class K>
std::vector<Tetrahedron> run_kernel(const std::vector<Point3>& points, std::size_t input_count,
                                    const std::vector<std::uint32_t>& order,
                                    const std::array<std::uint32_t, 4>& first, bool skip_first,
                                    const TriangulateOptions& options, TriangulationStats& stats) {
  if (options.audit) {
    return run_method<predicates::Audited<K>>(points, input_count, order, first, skip_first,
                                              options, stats);
  }
  return run_method<K>(points, input_count, order, first, skip_first, options, stats);
}

std::vector<Tetrahedron> dispatch(const std::vector<Point3>& points, std::size_t input_count,
                                  const std::vector<std::uint32_t>& order,
                                  const std::array<std::uint32_t, 4>& first, bool skip_first,
                                  const TriangulateOptions& options, TriangulationStats& stats) {
  switch (options.kernel) {
    case KernelKind::Fast:
      return run_kernel<predicates::FastKernel>(points, input_count, order, first, skip_first,
                                                options, stats);
    case KernelKind::Filtered:
      return run_kernel<predicates::FilteredKernel>(points, input_count, order, first, skip_first,
                                                    options, stats);
    case KernelKind::Exact:
      return run_kernel<predicates::ExactKernel>(points, input_count, order, first, skip_first,
                                                 options, stats);
    case KernelKind::Adaptive:
      break;
  }
  return run_kernel<predicates::AdaptiveKernel>(points, input_count, order, first, skip_first,
                                                options, stats);
}

// Each set of equal input points is named by its lowest index (as SharedMesh::finite_tetrahedra
// does in the engine's own numbering, which the walk mode's renumbering changes).
void name_duplicates_by_lowest_index(const std::vector<Point3>& input,
                                     std::vector<Tetrahedron>& tets) {
  std::vector<std::uint32_t> by_point(input.size());
  for (std::size_t i = 0; i < by_point.size(); ++i) by_point[i] = static_cast<std::uint32_t>(i);
  auto less = [&](std::uint32_t a, std::uint32_t b) {
    const Point3& p = input[a];
    const Point3& q = input[b];
    if (p.x != q.x) return p.x < q.x;
    if (p.y != q.y) return p.y < q.y;
    if (p.z != q.z) return p.z < q.z;
    return a < b;
  };
  std::sort(by_point.begin(), by_point.end(), less);
  std::vector<std::uint32_t> lowest(input.size());
  for (std::size_t i = 0; i < by_point.size(); ++i) {
    const bool same = i > 0 && input[by_point[i]] == input[by_point[i - 1]];
    lowest[by_point[i]] = same ? lowest[by_point[i - 1]] : by_point[i];
  }
  for (auto& t : tets) {
    for (auto& v : t) {
      if (v < lowest.size()) v = lowest[v];
    }
  }
}

// Every coordinate times 2^exponent, for a lossless scaling (RangeScaling::lossless: every result
// a normal double) and its inverse: two multiplications by powers of two that are normal doubles
// (|exponent| <= 1200, so each half is), and exact, since every value between c and c 2^exponent
// keeps c's significand and lies in the range of doubles. The same numbers as std::ldexp, which
// as a library call per coordinate took 0.6 % of a sequential walk's run at a million points.
void scale_points(std::vector<Point3>& points, int exponent, int threads) {
  const double first = std::ldexp(1.0, exponent / 2);
  const double second = std::ldexp(1.0, exponent - exponent / 2);
  in_parallel_ranges(points.size(), threads, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i) {
      Point3& p = points[i];
      p = {(p.x * first) * second, (p.y * first) * second, (p.z * first) * second};
    }
  });
}

// points[i] = old points[from[i]] for a permutation `from`. Through a second array: this runs
// before the store grows or after it is released, below the run's peak either way, and a gather
// is faster than following the permutation's cycles in place (and splits over threads).
void permute(std::vector<Point3>& points, const std::vector<std::uint32_t>& from, int threads) {
  std::vector<Point3> gathered(points.size());
  in_parallel_ranges(points.size(), threads, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i) gathered[i] = points[from[i]];
  });
  points.swap(gathered);
}

// The inverse: points[from[i]] = old points[i] (each thread writes distinct entries).
void unpermute(std::vector<Point3>& points, const std::vector<std::uint32_t>& from, int threads) {
  std::vector<Point3> scattered(points.size());
  in_parallel_ranges(points.size(), threads, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i) scattered[from[i]] = points[i];
  });
  points.swap(scattered);
}

}  // namespace

const char* to_string(KernelKind k) {
  switch (k) {
    case KernelKind::Fast:
      return "fast";
    case KernelKind::Adaptive:
      return "adaptive";
    case KernelKind::Filtered:
      return "filtered";
    case KernelKind::Exact:
      return "exact";
  }
  return "?";
}
const char* to_string(Bounding b) {
  return b == Bounding::Infinite ? "infinite" : "aux-tet";
}
const char* to_string(Location l) {
  return l == Location::Walk ? "walk" : "dag";
}
std::vector<Tetrahedron> canonical_tetrahedra(std::vector<Tetrahedron> tets) {
  for (auto& t : tets) std::sort(t.begin(), t.end());
  std::sort(tets.begin(), tets.end());
  return tets;
}

const char* to_string(Insertion i) {
  return i == Insertion::Cavity ? "cavity" : "flips";
}
const char* to_string(Method m) {
  switch (m) {
    case Method::Sequential:
      return "sequential";
    case Method::Pessimistic:
      return "pessimistic";
    case Method::OptimisticDetect:
      return "optimistic-detect";
    case Method::OptimisticPrevent:
      return "optimistic-prevent";
    case Method::Burglary:
      return "burglary";
    case Method::Batch:
      return "batch";
  }
  return "?";
}
const char* to_string(Distribution d) {
  switch (d) {
    case Distribution::Static:
      return "static";
    case Distribution::Dynamic:
      return "dynamic";
    case Distribution::Strips:
      return "strips";
    case Distribution::Blocks:
      return "blocks";
    case Distribution::Auto:
      return "auto";
  }
  return "?";
}

Distribution effective_distribution(const TriangulateOptions& options) {
  if (options.distribution != Distribution::Auto) return options.distribution;
  return options.location == Location::Walk ? Distribution::Blocks : Distribution::Static;
}

const char* to_string(Repair r) {
  switch (r) {
    case Repair::None:
      return "none";
    case Repair::Flips:
      return "flips";
    case Repair::Rebuild:
      return "rebuild";
    case Repair::Splay:
      return "splay";
    case Repair::FlipsThenSplay:
      return "flips-splay";
  }
  return "?";
}

namespace {

// The run on the caller's points, which it scales and reorders in place (no second copy at the
// run's peak) and puts back as they were, on every path out. When `as_given` (the same points,
// untouched) is there, `points` is a scratch copy: it is not put back after a finished run, and
// the duplicates' names and the auxiliary run's reference come from `as_given`.
Triangulation triangulate_in_place(std::vector<Point3>& points, const TriangulateOptions& options,
                                   const std::vector<Point3>* as_given) {
  const auto start = Clock::now();
  if (options.insertion == Insertion::Cavity && options.location != Location::Walk) {
    // A cavity's tetrahedra have more successors than the history DAG's four children.
    throw std::invalid_argument(
        "--insertion cavity needs --location walk (the DAG mode's history "
        "keeps at most four children a tetrahedron)");
  }
  Triangulation result;
  TriangulationStats& stats = result.stats;
  const std::size_t input_count = points.size();
  // The steps over whole arrays before the first insertion and after the last run on the
  // method's threads (one for the sequential engine, so that its time stays one thread's).
  const int threads = options.method == Method::Sequential ? 1 : std::max(1, options.threads);
  stats.points = input_count;
  if (input_count >= static_cast<std::size_t>(kInfiniteVertex) - 8) {
    throw TriangulationError("too many points for 32-bit vertex ids");
  }

  const CoordinateMagnitudes magnitudes = coordinate_magnitudes(points);
  if (!magnitudes.finite) throw TriangulationError("input has a NaN or infinite coordinate");
  // The first tetrahedron and the walk mode's order come from the input as given.
  std::vector<std::uint32_t> order = random_order(input_count, options.seed);
  const SimplexSearch search = find_simplex(points, order);
  if (!search.simplex) {
    throw TriangulationError("no tetrahedralization exists: the affine dimension of the " +
                             std::to_string(input_count) + " input points is " +
                             dimension_name(search.dimension) +
                             "; at least 4 points not in one plane are needed");
  }
  std::array<std::uint32_t, 4> simplex = *search.simplex;
  // The walk mode inserts in BRIO and Hilbert order (each parallel thread its share of it, in
  // that order: parallel_methods.cpp) and renumbers the vertices in that order: the points are
  // stored in the order they are inserted, so that the points of neighbouring tetrahedra lie
  // close in memory.
  std::vector<std::uint32_t> input_index;  // engine vertex id -> input index (walk mode)
  if (options.location == Location::Walk) {
    brio_hilbert_order(points, order, threads);
    input_index = std::move(order);
    // The first tetrahedron's engine ids, by one pass over the map rather than through its
    // inverse: a 4-byte-a-point inverse came from the heap (glibc raises its mmap threshold once
    // a large block is freed) and, freed, stayed resident at the run's peak (3.9 MB at 1M points).
    const std::array<std::uint32_t, 4> simplex_input = simplex;
    for (std::size_t i = 0; i < input_count; ++i) {
      for (std::size_t k = 0; k < 4; ++k) {
        if (input_index[i] == simplex_input[k]) simplex[k] = static_cast<std::uint32_t>(i);
      }
    }
    permute(points, input_index, threads);
    order.clear();  // the identity: insertion order is storage order now (4 bytes a point less)
    order.shrink_to_fit();
  }

  // Exact power-of-two scaling of the largest magnitude into [2^99, 2^100) (signs are unchanged),
  // for every kernel when it is lossless, so that all kernels see the same numbers; undone before
  // the points are handed back. Every input is taken: when some coordinates still lie outside the
  // range where expansion arithmetic is exact (valid_range.hpp), the adaptive and filtered kernels
  // hand the calls their float stage cannot decide to GMP.
  const RangeScaling scaling =
      adaptive_range_scaling(magnitudes.max_abs, magnitudes.min_abs_nonzero);
  if (scaling.lossless) {
    stats.scale_exponent = scaling.exponent;
    scale_points(points, scaling.exponent, threads);
  }
  // The caller's points again: unscaled (exact, the scaling is lossless), auxiliary points
  // dropped, in input order.
  auto restore_points = [&] {
    points.resize(input_count);
    if (scaling.lossless) scale_points(points, -scaling.exponent, threads);
    if (!input_index.empty()) unpermute(points, input_index, threads);
  };

  // The store's limit ends the run with the input's size in the message (tet_mesh.hpp).
  auto run = [&](const std::array<std::uint32_t, 4>& first, bool skip_first) {
    stats.seconds.ordering = std::chrono::duration<double>(Clock::now() - start).count();
    try {
      return dispatch(points, input_count, order, first, skip_first, options, stats);
    } catch (const StoreFull& e) {
      restore_points();
      throw TriangulationError(std::string(e.what()) + "; " + std::to_string(input_count) +
                               " points need more in this run");
    } catch (...) {
      restore_points();
      throw;
    }
  };
  if (options.bounding == Bounding::Infinite) {
    result.tetrahedra = run(simplex, true);
  } else {
    // The paper's auxiliary tetrahedron: (m,0,0), (0,m,0), (0,0,m), (-m,-m,-m) around the box
    // centre, m = 200 x the box size; removed with every tetrahedron touching it at the end.
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
      if (!std::isfinite(points[i].x) || !std::isfinite(points[i].y) ||
          !std::isfinite(points[i].z)) {
        restore_points();
        throw TriangulationError(
            "the auxiliary tetrahedron (200 x the bounding box) overflows double; use "
            "--bounding infinite");
      }
    }
    result.tetrahedra = run({n, n + 1, n + 2, n + 3}, false);
  }
  const auto finish_start = Clock::now();
  if (as_given == nullptr) restore_points();
  const std::vector<Point3>& input = as_given != nullptr ? *as_given : points;
  if (!input_index.empty()) {
    std::vector<Tetrahedron>& tets = result.tetrahedra;
    in_parallel_ranges(tets.size(), threads, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t i = begin; i < end; ++i) {
        for (auto& v : tets[i]) v = input_index[v];
      }
    });
    if (stats.duplicates > 0) name_duplicates_by_lowest_index(input, result.tetrahedra);
  }
  stats.seconds.output += std::chrono::duration<double>(Clock::now() - finish_start).count();
  stats.tetrahedra = result.tetrahedra.size();
  // The post-check's validation is a measurement, not part of the method.
  stats.seconds.total =
      std::chrono::duration<double>(Clock::now() - start).count() - stats.post_check.seconds_check;
  stats.seconds.other = std::max(0.0, stats.seconds.total - stats.seconds.location -
                                          stats.seconds.subdivision - stats.seconds.legalization);

  if (options.bounding == Bounding::AuxTet) {
    // Measured outside seconds.total: the exact hull's tetrahedra that the auxiliary run lost.
    TriangulateOptions reference = options;
    reference.bounding = Bounding::Infinite;
    reference.audit = false;
    reference.progress = false;
    const auto exact = canonical_tetrahedra(triangulate(input, reference).tetrahedra);
    const auto aux = canonical_tetrahedra(result.tetrahedra);
    std::vector<Tetrahedron> lost;
    std::set_difference(exact.begin(), exact.end(), aux.begin(), aux.end(),
                        std::back_inserter(lost));
    stats.hull_tetrahedra_lost = static_cast<std::int64_t>(lost.size());
  }
  stats.peak_rss_bytes = peak_rss_bytes();
  return result;
}

}  // namespace

Triangulation triangulate(const std::vector<Point3>& input, const TriangulateOptions& options) {
  std::vector<Point3> points = input;
  return triangulate_in_place(points, options, &input);
}

Triangulation triangulate(std::vector<Point3>&& input, const TriangulateOptions& options) {
  Triangulation result = triangulate_in_place(input, options, nullptr);
  result.points = std::move(input);
  return result;
}

std::string stats_json(const TriangulationStats& s, const TriangulateOptions& options,
                       const std::string& method, int threads) {
  nlohmann::ordered_json j;
  j["points"] = s.points;
  j["inserted"] = s.inserted;
  j["duplicates"] = s.duplicates;
  j["tetrahedra"] = s.tetrahedra;
  j["seconds"] = {{"total", s.seconds.total},
                  {"location", s.seconds.location},
                  {"subdivision", s.seconds.subdivision},
                  {"legalization", s.seconds.legalization},
                  {"other", s.seconds.other},
                  {"ordering", s.seconds.ordering},
                  {"output", s.seconds.output}};
  j["flips"] = {
      {"S23", s.flips.s23}, {"S32", s.flips.s32}, {"S22", s.flips.s22}, {"S44", s.flips.s44}};
  j["cavity"] = {{"insertions", s.cavity.insertions},
                 {"tetrahedra_removed", s.cavity.tetrahedra_removed},
                 {"fallbacks", s.cavity.fallbacks}};
  j["dag_nodes"] = s.dag_nodes;
  j["predicate_calls"] = s.predicate_calls;
  j["location_steps"] = s.location_steps;
  j["walk_fallbacks"] = s.walk_fallbacks;
  j["store_slots"] = s.store_slots;
  j["abandoned_insertions"] = s.abandoned_insertions;
  if (s.hull_tetrahedra_lost >= 0) {
    j["hull_tetrahedra_lost"] = s.hull_tetrahedra_lost;
  } else {
    j["hull_tetrahedra_lost"] = nullptr;
  }
  j["peak_rss_bytes"] = s.peak_rss_bytes;
  // The whole process's peak (input, output and the run) per input point.
  j["bytes_per_point"] = s.points > 0 ? s.peak_rss_bytes / s.points : 0;
  j["scale_exponent"] = s.scale_exponent;
  if (!s.threads.empty()) {
    std::uint64_t waits = 0, deadlocks = 0, stale = 0, give_ups = 0, raises = 0, burglaries = 0,
                  burgled = 0, problems = 0, suspicious = 0;
    nlohmann::ordered_json per_thread = nlohmann::ordered_json::array();
    for (const ThreadStats& t : s.threads) {
      waits += t.waits;
      deadlocks += t.deadlocks;
      stale += t.stale_cycles;
      give_ups += t.give_ups;
      raises += t.priority_raises;
      burglaries += t.burglaries;
      burgled += t.burgled;
      problems += t.potential_problems;
      suspicious += t.suspicious_tetrahedra;
      per_thread.push_back({{"inserted", t.inserted},
                            {"duplicates", t.duplicates},
                            {"abandoned", t.abandoned},
                            {"waits", t.waits},
                            {"deadlocks", t.deadlocks},
                            {"stale_cycles", t.stale_cycles},
                            {"give_ups", t.give_ups},
                            {"priority_raises", t.priority_raises},
                            {"burglaries", t.burglaries},
                            {"burgled", t.burgled},
                            {"potential_problems", t.potential_problems},
                            {"suspicious_tetrahedra", t.suspicious_tetrahedra}});
    }
    j["waits"] = waits;
    j["deadlocks"] = deadlocks;
    j["stale_cycles"] = stale;
    j["give_ups"] = give_ups;
    j["priority_raises"] = raises;
    j["burglaries"] = burglaries;
    j["burgled"] = burgled;
    j["potential_problems"] = problems;
    j["suspicious_tetrahedra"] = suspicious;
    if (options.method == Method::Batch) {
      j["queue_full_waits"] = s.queue_full_waits;
      j["queue_empty_waits"] = s.queue_empty_waits;
    }
    j["per_thread"] = per_thread;
  }
  if (s.post_check.done) {
    const PostCheck& c = s.post_check;
    nlohmann::ordered_json pc;
    pc["non_delaunay_faces"] = c.non_delaunay_faces;
    pc["reflex_boundary_edges"] = c.reflex_boundary_edges;
    pc["mesh_consistent"] = c.mesh_consistent;
    pc["repaired"] = c.repaired;
    pc["repair"] = to_string(options.repair);
    if (c.repaired) {
      pc["repair_flips"] = c.repair_flips;
      pc["non_delaunay_after_marked"] = c.non_delaunay_after_marked;
      pc["sweep_flips"] = c.sweep_flips;
      pc["non_delaunay_after_flips"] = c.non_delaunay_after_flips;
      pc["mesh_consistent_after_flips"] = c.mesh_consistent_after_flips;
      pc["rebuilt"] = c.rebuilt;
      pc["seconds_repair"] = c.seconds_repair;
    }
    pc["non_delaunay_faces_after"] = c.non_delaunay_faces_after;
    pc["reflex_boundary_edges_after"] = c.reflex_boundary_edges_after;
    pc["mesh_consistent_after"] = c.mesh_consistent_after;
    pc["non_delaunay_after"] = c.non_delaunay_after;
    pc["seconds_check"] = c.seconds_check;
    j["post_check"] = pc;
  }
  if (s.splay.done) {
    const SplayStats& r = s.splay;
    j["splay"] = {{"non_delaunay_faces", r.non_delaunay_faces},
                  {"bad_tetrahedra", r.bad_tetrahedra},
                  {"missing_vertices", r.missing_vertices},
                  {"seeds", r.seeds},
                  {"live_marks", r.live_marks},
                  {"marks_seeded", r.marks_seeded},
                  {"proven_by_post_check", r.proven_by_post_check},
                  {"found_by_post_check", r.found_by_post_check},
                  {"stars_walked", r.stars_walked},
                  {"stars", r.stars},
                  {"offers", r.offers},
                  {"changes", r.changes},
                  {"regrown", r.regrown},
                  {"bridges", r.bridges},
                  {"tetrahedra_removed", r.tetrahedra_removed},
                  {"tetrahedra_created", r.tetrahedra_created},
                  {"seconds", r.seconds},
                  {"seconds_scan", r.seconds_scan},
                  {"seconds_listing", r.seconds_listing},
                  {"seconds_building", r.seconds_building},
                  {"seconds_enforcing", r.seconds_enforcing},
                  {"flipped", r.flipped},
                  {"flips", r.flips},
                  {"faces_left", r.faces_left},
                  {"walk_starts_moved", r.walk_starts_moved},
                  {"seconds_flipping", r.seconds_flipping},
                  {"scan_threads", r.scan_threads}};
  }
  j["repair"] = to_string(options.repair);
  j["method"] = method;
  j["threads"] = threads;
  j["distribution"] = to_string(effective_distribution(options));
  j["predicates"] = to_string(options.kernel);
  j["location"] = to_string(options.location);
  j["insertion"] = to_string(options.insertion);
  j["bounding"] = to_string(options.bounding);
  j["seed"] = options.seed;
  return j.dump(2);
}

}  // namespace dtlab::engine
