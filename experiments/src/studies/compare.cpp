// compare: dtlab (walk and DAG, sequential; the lock methods in walk mode; the walk mode with
// flips and with cavity insertion) against CGAL's
// Delaunay_triangulation_3 (sequential; parallel with TBB at the same thread count) on the same
// points, in interleaved rounds, each run in its own process: time, throughput, peak memory.
#include <algorithm>

#include "dtlab/engine/methods.hpp"
#include "dtlab/experiments/cgal_engine.hpp"
#include "studies.hpp"

namespace dtlab::experiments {
namespace {

using engine::Method;

std::vector<RunSpec> plan(const StudyParams& p) {
  std::vector<RunSpec> runs;
  const bool walk = std::find(p.locations.begin(), p.locations.end(), engine::Location::Walk) !=
                    p.locations.end();
  for (const std::string& input : p.inputs) {
    for_each_source(
        p, input, [&](const std::string& label, const std::string& source, std::int64_t n) {
          // The same points (seed 1) in every round; rounds interleave the engines.
          for (int round = 1; round <= p.seeds; ++round) {
            const RunSpec base = [&] {
              RunSpec spec = dtlab_run(label, source, n, 1);
              spec.round = round;
              return spec;
            }();
            for (const engine::Location location : p.locations) {
              RunSpec spec = base;
              spec.options.location = location;
              spec.variant = std::string("dtlab ") + engine::to_string(location);
              runs.push_back(spec);
              if (location == engine::Location::Walk) {
                spec.options.insertion = engine::Insertion::Cavity;
                spec.variant = "dtlab walk cavity";
                runs.push_back(spec);
              }
            }
            RunSpec cgal = base;
            cgal.engine = Engine::CgalSequential;
            cgal.variant = "CGAL";
            runs.push_back(cgal);
            for (const int threads : p.threads) {
              if (threads < 2) continue;
              // The lock methods run in walk mode only (the DAG mode is the paper's baseline).
              std::vector<Method> methods;
              if (walk) {
                // --quick: one of them; else every parallel method of the registry.
                for (const engine::MethodInfo& info : engine::methods()) {
                  if (info.parallel && (!p.quick || info.method == Method::OptimisticDetect)) {
                    methods.push_back(info.method);
                  }
                }
              }
              for (const Method method : methods) {
                RunSpec spec = base;
                spec.options.location = engine::Location::Walk;
                spec.options.method = method;
                spec.options.threads = threads;
                spec.options.distribution = p.distribution;  // auto: blocks in walk mode
                for (const engine::Insertion insertion :
                     {engine::Insertion::Flips, engine::Insertion::Cavity}) {
                  spec.options.insertion = insertion;
                  if (engine::unsupported(spec.options)) continue;
                  spec.variant =
                      std::string(insertion == engine::Insertion::Cavity ? "dtlab walk cavity "
                                                                         : "dtlab walk ") +
                      engine::to_string(method);
                  runs.push_back(spec);
                }
              }
              if (cgal_parallel_available()) {
                RunSpec parallel = base;
                parallel.engine = Engine::CgalParallel;
                parallel.options.threads = threads;
                parallel.variant = "CGAL parallel";
                runs.push_back(parallel);
              }
            }
          }
        });
  }
  return runs;
}

std::string summarize(const CsvTable& t) {
  MarkdownTable table({"input", "points", "engine", "threads", "rounds", "median s", "min s",
                       "Mpoints/s", "x CGAL", "peak MiB", "bytes/point", "tetrahedra"});
  for (const RowGroup& input :
       group_rows(t, {"input", "size_asked"}, [&](const Row& r) { return is_ok(t, r); })) {
    std::vector<const Row*> cgal_rows;
    for (const Row* r : input.rows) {
      if (t.get(*r, "variant") == "CGAL") cgal_rows.push_back(r);
    }
    const double cgal = aggregate_of(t, cgal_rows, "seconds.total").median;
    CsvTable sub{t.header, {}};
    for (const Row* r : input.rows) sub.rows.push_back(*r);
    for (const RowGroup& g :
         group_rows(sub, {"variant", "threads"}, [](const Row&) { return true; })) {
      const double points = aggregate_of(sub, g.rows, "points").median;
      const Aggregate seconds = aggregate_of(sub, g.rows, "seconds.total");
      const double peak = aggregate_of(sub, g.rows, "peak_rss_bytes").median;
      table.add({input.key[0], thousands(points), g.key[0], threads_cell(sub, *g.rows.front()),
                 std::to_string(seconds.count), fixed(seconds.median, 3), fixed(seconds.min, 3),
                 fixed(points / seconds.median / 1e6, 3), fixed(seconds.median / cgal, 2),
                 fixed(peak / 1048576.0, 0), fixed(peak / points, 0),
                 thousands(aggregate_of(sub, g.rows, "tetrahedra").median)});
    }
  }
  return table.str() +
         "\nEvery run in its own process; peak memory is that process's peak RSS, which includes "
         "the input points and the parent's pages at the fork. dtlab's seconds are the engine's "
         "(`seconds.total`), CGAL's include converting the points. The parallel methods run in "
         "walk mode with the blocks distribution; CGAL's parallel mode uses a 50^3 lock grid. "
         "Both are compiled with the same flags (machine.json).\n";
}

}  // namespace

Study compare_study() {
  return {"compare",
          "dtlab (walk with flips or cavities, DAG, the lock methods) against CGAL (sequential "
          "and parallel) on the same points: time, throughput, peak memory",
          {3,
           2,
           {2},
           {2},
           {1000000},
           {20000},
           {"uniform"},
           {"uniform"},
           {engine::Location::Walk, engine::Location::Dag}},
          plan,
          summarize};
}

}  // namespace dtlab::experiments
