// breakdown (paper Fig. 4): the sequential engine's time per phase (location, subdivision,
// legalization, other) against the number of points, per location mode.
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
  MarkdownTable table({"input", "points", "location", "total s", "location s", "subdivision s",
                       "legalization s", "other s", "location %", "subdivision %", "legalization %",
                       "us per point"});
  for (const RowGroup& g : group_rows(t, {"input", "size_asked", "location"},
                                      [&](const Row& r) { return is_ok(t, r); })) {
    const double points = aggregate_of(t, g.rows, "points").median;
    const double total = aggregate_of(t, g.rows, "seconds.total").median;
    const auto phase = [&](const char* column) { return aggregate_of(t, g.rows, column).median; };
    table.add({g.key[0], thousands(points), g.key[2], fixed(total, 3),
               fixed(phase("seconds.location"), 3), fixed(phase("seconds.subdivision"), 3),
               fixed(phase("seconds.legalization"), 3), fixed(phase("seconds.other"), 3),
               fixed(100.0 * phase("seconds.location") / total, 0),
               fixed(100.0 * phase("seconds.subdivision") / total, 0),
               fixed(100.0 * phase("seconds.legalization") / total, 0),
               fixed(1e6 * total / points, 2)});
  }
  return table.str() +
         "\nMedians over the seeds. \"location\" is the DAG descent or the walk; \"subdivision\" "
         "the 1->4 (or 2->6, k->2k) split; \"legalization\" the flips; \"other\" the setup, the "
         "order and the output.\n";
}

}  // namespace

Study breakdown_study() {
  return {"breakdown",
          "the sequential engine's time per phase against the number of points (paper Fig. 4)",
          {3,
           1,
           {},
           {},
           {10000, 20000, 50000, 100000, 200000},
           {1000, 3000},
           {"uniform"},
           {"uniform"},
           {engine::Location::Dag, engine::Location::Walk}},
          plan,
          summarize};
}

}  // namespace dtlab::experiments
