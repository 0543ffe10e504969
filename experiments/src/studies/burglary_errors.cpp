// burglary-errors: what the burglary method leaves (non-Delaunay faces, reflex boundary edges,
// potential problems, suspicious tetrahedra) before and after star splaying, beside the deadlocks
// and give-ups of the optimistic methods on the same points, seeds and thread counts.
#include "studies.hpp"

namespace dtlab::experiments {
namespace {

using engine::Method;

std::vector<RunSpec> plan(const StudyParams& p) {
  std::vector<RunSpec> runs;
  for_each_base_run(p, [&](RunSpec base) {
    for (const int threads : p.threads) {
      for (const Method method :
           {Method::Burglary, Method::OptimisticDetect, Method::OptimisticPrevent}) {
        RunSpec spec = base;
        spec.options.method = method;
        spec.options.threads = threads;
        spec.variant = engine::to_string(method);
        if (method == Method::Burglary) {
          spec.options.repair = engine::Repair::Splay;
          spec.variant = "burglary+splay";
        }
        runs.push_back(spec);
      }
    }
  });
  return runs;
}

// "median / max" of a column over rows; "-" when there are none.
std::string median_max(const CsvTable& t, const std::vector<const Row*>& rows, const char* column) {
  if (rows.empty()) return "-";
  const Aggregate a = aggregate_of(t, rows, column);
  return fixed(a.median, 0) + " / " + fixed(a.max, 0);
}

std::string summarize(const CsvTable& t) {
  MarkdownTable table({"input", "points", "location", "threads", "runs", "burglaries per 1k points",
                       "potential problems", "suspicious tetrahedra",
                       "non-Delaunay faces (mean / median / max)",
                       "reflex boundary edges (mean / median / max)", "left after splaying (max)",
                       "stars splayed (median)", "repair s (median)", "repair / run",
                       "detect: deadlocks (median / max)", "prevent: give-ups (median / max)"});
  const std::vector<std::string> keys = {"input", "size_asked", "location", "threads"};
  const auto burglary = group_rows(
      t, keys, [&](const Row& r) { return is_ok(t, r) && t.get(r, "method") == "burglary"; });
  const auto others = [&](const std::vector<std::string>& key, const char* method) {
    for (const RowGroup& g : group_rows(
             t, keys, [&](const Row& r) { return is_ok(t, r) && t.get(r, "method") == method; })) {
      if (g.key == key) return g.rows;
    }
    return std::vector<const Row*>{};
  };
  for (const RowGroup& g : burglary) {
    const double points = aggregate_of(t, g.rows, "points").median;
    const double repair = aggregate_of(t, g.rows, "post_check.seconds_repair").median;
    const double run = aggregate_of(t, g.rows, "seconds.total").median;
    const auto detect = others(g.key, "optimistic-detect");
    const auto prevent = others(g.key, "optimistic-prevent");
    table.add({g.key[0], thousands(points), g.key[2], threads_cell(t, *g.rows.front()),
               std::to_string(g.rows.size()),
               fixed(aggregate_of(t, g.rows, "burglaries").mean * 1000.0 / points, 2),
               fixed(aggregate_of(t, g.rows, "potential_problems").mean, 1),
               fixed(aggregate_of(t, g.rows, "suspicious_tetrahedra").mean, 1),
               mean_median_max(aggregate_of(t, g.rows, "post_check.non_delaunay_faces")),
               mean_median_max(aggregate_of(t, g.rows, "post_check.reflex_boundary_edges")),
               fixed(aggregate_of(t, g.rows, "post_check.non_delaunay_after").max, 0),
               fixed(aggregate_of(t, g.rows, "splay.stars").median, 0), fixed(repair, 3),
               fixed(repair / (run - repair), 3), median_max(t, detect, "deadlocks"),
               median_max(t, prevent, "give_ups")});
  }
  return table.str() +
         "\nNon-Delaunay faces and reflex boundary edges are the exact validator's counts right "
         "after the parallel run (`post_check.*` in the CSV); \"left after splaying\" is the same "
         "count (faces + reflex edges) on the mesh star splaying returned, which must be 0. "
         "\"repair / run\" is the repair's seconds over the run's seconds without it. The "
         "optimistic methods ran on the same points, seeds and thread counts (detection gives up "
         "once per deadlock; prevention gives up instead of waiting for a thread of higher "
         "priority). Thread counts above the CPUs available are marked oversubscribed.\n";
}

}  // namespace

Study burglary_errors_study() {
  return {"burglary-errors",
          "non-Delaunay faces, reflex boundary edges, potential problems and suspicious "
          "tetrahedra left by burglary, before and after star splaying, beside the optimistic "
          "methods' deadlocks and give-ups",
          {10,
           2,
           {2, 4, 8},
           {2, 4},
           {10000, 100000},
           {2000},
           {"uniform", "normal", "cluster", "grid", "sphere", "dragon_vrip_res3", "bunny_zipper"},
           {"uniform", "grid", "sphere", "dragon_vrip_res4"},
           {engine::Location::Dag}},
          plan,
          summarize};
}

}  // namespace dtlab::experiments
