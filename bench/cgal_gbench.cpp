// dtlab (walk and DAG modes, optimistic-detect at 2 threads) and CGAL's Delaunay_triangulation_3
// (sequential, parallel at 2 threads) as Google Benchmark cases on the same generated points:
// wall time per triangulation, medians of 3 repetitions, points per second. Every engine runs in
// this one process, so peak memory is not measured here: `dtlab experiment compare` (each run in
// its own process) and bench/cgal_compare give bytes per point.
//   cgal_gbench [--benchmark_filter=uniform:1000000] [google benchmark flags]
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
               dtlab::engine::Location location, dtlab::engine::Method method, int threads) {
  const auto& points = points_of(family, n);
  dtlab::engine::TriangulateOptions options;
  options.location = location;
  options.method = method;
  options.threads = threads;
  if (threads > 1) options.distribution = dtlab::engine::Distribution::Blocks;
  std::size_t tetrahedra = 0;
  for (auto _ : state) {
    const auto result = dtlab::engine::triangulate(points, options);
    tetrahedra = result.tetrahedra.size();
    benchmark::DoNotOptimize(result.tetrahedra.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(points.size()));
  state.counters["tetrahedra"] = static_cast<double>(tetrahedra);
}

void run_cgal(benchmark::State& state, const std::string& family, std::int64_t n, int threads) {
  const auto& points = points_of(family, n);
  std::uint64_t cells = 0;
  for (auto _ : state) cells = dtlab::experiments::run_cgal(points, threads).finite_cells;
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(points.size()));
  state.counters["tetrahedra"] = static_cast<double>(cells);
}

void register_all() {
  using dtlab::engine::Location;
  using dtlab::engine::Method;
  const std::vector<std::pair<std::string, std::int64_t>> inputs = {
      {"uniform", 1000000}, {"uniform", 100000}, {"grid", 1000000}, {"sphere", 100000}};
  for (const auto& [family, n] : inputs) {
    const std::string input = family + ":" + std::to_string(n);
    const auto add = [&](const std::string& engine, auto fn) {
      benchmark::RegisterBenchmark((input + "/" + engine).c_str(), fn)
          ->Unit(benchmark::kSecond)
          ->UseRealTime()
          ->Iterations(1)
          ->Repetitions(3)
          ->ReportAggregatesOnly(true);
    };
    const std::string f = family;
    const std::int64_t size = n;
    add("dtlab_walk", [f, size](benchmark::State& s) {
      run_dtlab(s, f, size, Location::Walk, Method::Sequential, 1);
    });
    if (size <= 100000) {  // the DAG mode takes about 44 s at 1M points
      add("dtlab_dag", [f, size](benchmark::State& s) {
        run_dtlab(s, f, size, Location::Dag, Method::Sequential, 1);
      });
    }
    add("cgal", [f, size](benchmark::State& s) { run_cgal(s, f, size, 1); });
    add("dtlab_walk_optimistic_detect_2t", [f, size](benchmark::State& s) {
      run_dtlab(s, f, size, Location::Walk, Method::OptimisticDetect, 2);
    });
    if (dtlab::experiments::cgal_parallel_available()) {
      add("cgal_parallel_2t", [f, size](benchmark::State& s) { run_cgal(s, f, size, 2); });
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
