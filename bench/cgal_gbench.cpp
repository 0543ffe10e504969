// dtlab (walk and DAG modes, flips and cavity insertion, optimistic-detect at 2 threads) and
// CGAL's Delaunay_triangulation_3
// (sequential, parallel at 2 threads) as Google Benchmark cases on the same generated points:
// wall time per triangulation, medians of 3 repetitions, points per second. Every engine runs in
// this one process, so peak memory is not measured here: `dtlab experiment compare` (each run in
// its own process) and bench/cgal_compare give bytes per point.
//   cgal_gbench [--benchmark_filter=uniform_1000000] [google benchmark flags]
#include <benchmark/benchmark.h>

#include <map>
#include <string>
#include <vector>

#include "dtlab/engine/triangulate.hpp"
#include "dtlab/experiments/cgal_engine.hpp"
#include "dtlab/generators/generators.hpp"

namespace {

using dtlab::predicates::Point3;

const std::vector<Point3>& points_of(const std::string& family, std::int64_t n) {
  static std::map<std::string, std::vector<Point3>> cache;
  const std::string key = family + ":" + std::to_string(n);
  auto it = cache.find(key);
  if (it == cache.end()) {
    it = cache.emplace(key, dtlab::generators::generate(family, n, 1).points).first;
  }
  return it->second;
}

void run_dtlab(benchmark::State& state, const std::string& family, std::int64_t n,
               dtlab::engine::Location location, dtlab::engine::Method method, int threads,
               dtlab::engine::Insertion insertion = dtlab::engine::Insertion::Flips) {
  const auto& points = points_of(family, n);
  dtlab::engine::TriangulateOptions options;
  options.location = location;
  options.insertion = insertion;
  options.method = method;
  options.threads = threads;
  if (threads > 1) options.distribution = dtlab::engine::Distribution::Blocks;
  std::size_t tetrahedra = 0;
  for (auto iteration : state) {
    (void)iteration;
    const auto result = dtlab::engine::triangulate(points, options);
    tetrahedra = result.tetrahedra.size();
    benchmark::DoNotOptimize(result.tetrahedra.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(points.size()));
  state.counters["tetrahedra"] = static_cast<double>(tetrahedra);
}

void dtlab_walk(benchmark::State& state, const char* family, std::int64_t n) {
  run_dtlab(state, family, n, dtlab::engine::Location::Walk, dtlab::engine::Method::Sequential, 1);
}
void dtlab_dag(benchmark::State& state, const char* family, std::int64_t n) {
  run_dtlab(state, family, n, dtlab::engine::Location::Dag, dtlab::engine::Method::Sequential, 1);
}
void dtlab_walk_optimistic_detect_2t(benchmark::State& state, const char* family, std::int64_t n) {
  run_dtlab(state, family, n, dtlab::engine::Location::Walk,
            dtlab::engine::Method::OptimisticDetect, 2);
}

void dtlab_walk_cavity(benchmark::State& state, const char* family, std::int64_t n) {
  run_dtlab(state, family, n, dtlab::engine::Location::Walk, dtlab::engine::Method::Sequential, 1,
            dtlab::engine::Insertion::Cavity);
}
void dtlab_walk_cavity_optimistic_detect_2t(benchmark::State& state, const char* family,
                                            std::int64_t n) {
  run_dtlab(state, family, n, dtlab::engine::Location::Walk,
            dtlab::engine::Method::OptimisticDetect, 2, dtlab::engine::Insertion::Cavity);
}

void run_cgal(benchmark::State& state, const char* family, std::int64_t n, int threads) {
  if (threads > 1 && !dtlab::experiments::cgal_parallel_available()) {
    state.SkipWithError("this build has no TBB: CGAL's parallel mode is not available");
    return;
  }
  const auto& points = points_of(family, n);
  std::uint64_t cells = 0;
  for (auto iteration : state) {
    (void)iteration;
    cells = dtlab::experiments::run_cgal(points, threads).finite_cells;
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(points.size()));
  state.counters["tetrahedra"] = static_cast<double>(cells);
}
void cgal(benchmark::State& state, const char* family, std::int64_t n) {
  run_cgal(state, family, n, 1);
}
void cgal_parallel_2t(benchmark::State& state, const char* family, std::int64_t n) {
  run_cgal(state, family, n, 2);
}

}  // namespace

// One iteration per repetition, 3 repetitions: the aggregates (mean, median, stddev) are over
// whole triangulations.
#define DTLAB_CASE(engine, name, family, n)  \
  BENCHMARK_CAPTURE(engine, name, family, n) \
      ->Unit(benchmark::kSecond)             \
      ->UseRealTime()                        \
      ->Iterations(1)                        \
      ->Repetitions(3)                       \
      ->ReportAggregatesOnly(true)
#define DTLAB_INPUT(name, family, n)                                   \
  DTLAB_CASE(dtlab_walk, name, family, n);                             \
  DTLAB_CASE(dtlab_walk_cavity, name, family, n);                      \
  DTLAB_CASE(cgal, name, family, n);                                   \
  DTLAB_CASE(dtlab_walk_optimistic_detect_2t, name, family, n);        \
  DTLAB_CASE(dtlab_walk_cavity_optimistic_detect_2t, name, family, n); \
  DTLAB_CASE(cgal_parallel_2t, name, family, n)

DTLAB_INPUT(uniform_1000000, "uniform", 1000000);
DTLAB_INPUT(uniform_100000, "uniform", 100000);
DTLAB_CASE(dtlab_dag, uniform_100000, "uniform", 100000);  // the DAG mode: about 44 s at 1M
DTLAB_INPUT(grid_1000000, "grid", 1000000);
DTLAB_INPUT(sphere_100000, "sphere", 100000);

BENCHMARK_MAIN();
