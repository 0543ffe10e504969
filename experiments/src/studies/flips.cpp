// flips (paper Figs. 8 and 9): flips by type per point, per distribution and size, and the time
// against the size of the DAG.
#include "studies.hpp"

namespace dtlab::experiments {
namespace {

std::vector<RunSpec> plan(const StudyParams& p) {
  std::vector<RunSpec> runs;
  for_each_base_run(p, [&](RunSpec base) {
    base.variant = "sequential";
    runs.push_back(base);
  });
  return runs;
}

std::string summarize(const CsvTable& t) {
  MarkdownTable table({"input", "points", "location", "S23 / point", "S32 / point", "S22 / point",
                       "S44 / point", "flips / point", "DAG nodes / point", "store slots / point",
                       "seconds", "us per point"});
  for (const RowGroup& g : group_rows(t, {"input", "size_asked", "location"},
                                      [&](const Row& r) { return is_ok(t, r); })) {
    const double points = aggregate_of(t, g.rows, "points").median;
    const double inserted = aggregate_of(t, g.rows, "inserted").mean;
    const auto per_point = [&](const char* column) {
      return fixed(aggregate_of(t, g.rows, column).mean / inserted, 2);
    };
    const double flips =
        aggregate_of(t, g.rows, "flips.S23").mean + aggregate_of(t, g.rows, "flips.S32").mean +
        aggregate_of(t, g.rows, "flips.S22").mean + aggregate_of(t, g.rows, "flips.S44").mean;
    const double seconds = aggregate_of(t, g.rows, "seconds.total").median;
    table.add({g.key[0], thousands(points), g.key[2], per_point("flips.S23"),
               per_point("flips.S32"), per_point("flips.S22"), per_point("flips.S44"),
               fixed(flips / inserted, 2), per_point("dag_nodes"), per_point("store_slots"),
               fixed(seconds, 3), fixed(1e6 * seconds / inserted, 2)});
  }
  return table.str() +
         "\nMeans over the seeds per inserted point; seconds are medians. S22 and S44 are the "
         "flips of coplanar configurations (grid and lattice data); the DAG has no nodes in walk "
         "mode, whose store reuses slots.\n";
}

}  // namespace

Study flips_study() {
  return {"flips",
          "flips by type per distribution and size, and the time against the DAG's size "
          "(paper Figs. 8 and 9)",
          {3,
           1,
           {},
           {},
           {10000, 50000, 100000, 200000},
           {1000, 3000},
           {"uniform", "normal", "cluster", "grid", "sphere"},
           {"uniform", "grid"},
           {engine::Location::Dag}},
          plan,
          summarize};
}

}  // namespace dtlab::experiments
