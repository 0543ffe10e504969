// speedup: the paper's Table 1 and Figs. 10, 12, 13, 15: the speedup and efficiency of every lock
// method over the sequential engine of the same location mode, per thread count, per round.
#include <array>
#include <cmath>
#include <map>
#include <string>

#include "dtlab/engine/methods.hpp"
#include "studies.hpp"

namespace dtlab::experiments {
namespace {

using engine::Method;

std::vector<RunSpec> plan(const StudyParams& p) {
  std::vector<RunSpec> runs;
  for_each_base_run(p, [&](RunSpec base) {
    // A round is one seed: its points (for a generator) and its insertion order.
    base.variant = "sequential";
    runs.push_back(base);
    // Every parallel method of the registry that runs this location and insertion.
    for (const engine::MethodInfo& info : engine::methods()) {
      RunSpec spec = base;
      spec.options.method = info.method;
      if (!info.parallel || engine::unsupported(spec.options)) continue;
      spec.variant = info.name;
      for (const int threads : p.threads) {
        // A method that needs more threads than asked (batch: a locating and an inserting
        // thread, so at --threads 1 it still runs two) would not run at this count.
        if (threads < info.min_threads) continue;
        spec.options.threads = threads;
        runs.push_back(spec);
      }
    }
  });
  return runs;
}

// Kohout and Kolingerova 2003, Table 1: speedup ranges on uniform and on real data.
std::string paper_range(const std::string& method, int threads) {
  if (method == "pessimistic" && threads == 2) return "1.25-1.57; 1.31-1.72";
  if (method == "optimistic-detect" && threads == 2) return "1.66-1.89; 1.64-1.92";
  if (method == "optimistic-detect" && threads == 4) return "2.40-3.67; 2.39-3.69";
  if (method == "burglary" && threads == 2) return "1.53-1.77; 1.62-1.82";
  if (method == "burglary" && threads == 4) return "2.66-3.44; 2.55-3.37";
  return "-";
}

std::string summarize(const CsvTable& t) {
  MarkdownTable table({"input", "points", "location", "method", "threads", "sequential s",
                       "method s", "speedup (median)", "efficiency", "speedup per round"});
  const auto groups = group_rows(t, {"input", "size_asked", "location", "method", "threads"},
                                 [&](const Row& r) { return is_ok(t, r); });
  // The sequential time of each round (seed), per input, size and location.
  const auto sequential_seconds = [&](const Row& r) {
    for (const Row& s : t.rows) {
      if (is_ok(t, s) && t.get(s, "method") == "sequential" &&
          t.get(s, "input") == t.get(r, "input") &&
          t.get(s, "size_asked") == t.get(r, "size_asked") &&
          t.get(s, "location") == t.get(r, "location") && t.get(s, "seed") == t.get(r, "seed")) {
        return t.number(s, "seconds.total");
      }
    }
    return std::nan("");
  };
  // Table 1's form: per location, method and thread count, the range of the median speedups
  // over the inputs and sizes.
  std::map<std::array<std::string, 3>, std::vector<double>> ranges;
  for (const RowGroup& g : groups) {
    if (g.key[3] == "sequential") continue;
    std::vector<double> speedups;
    std::vector<double> sequential;
    std::string per_round;
    for (const Row* r : g.rows) {
      const double seq = sequential_seconds(*r);
      sequential.push_back(seq);
      speedups.push_back(seq / t.number(*r, "seconds.total"));
      if (!per_round.empty()) per_round += ' ';
      per_round += fixed(speedups.back(), 2);
    }
    const double speedup = aggregate(speedups).median;
    const double threads = t.number(*g.rows.front(), "threads");
    ranges[{g.key[2], g.key[3], threads_cell(t, *g.rows.front())}].push_back(speedup);
    table.add({g.key[0], thousands(aggregate_of(t, g.rows, "points").median), g.key[2], g.key[3],
               threads_cell(t, *g.rows.front()), fixed(aggregate(sequential).median, 3),
               fixed(aggregate_of(t, g.rows, "seconds.total").median, 3), fixed(speedup, 2),
               fixed(speedup / threads, 2), per_round});
  }
  MarkdownTable table1({"location", "method", "threads", "speedup (min - max)",
                        "efficiency % (min - max)", "paper, Table 1 (uniform; real)"});
  for (const auto& [key, values] : ranges) {
    const Aggregate a = aggregate(values);
    const double threads = std::stod(key[2]);
    table1.add({key[0], key[1], key[2], fixed(a.min, 2) + " - " + fixed(a.max, 2),
                fixed(100.0 * a.min / threads, 0) + " - " + fixed(100.0 * a.max / threads, 0),
                paper_range(key[1], static_cast<int>(threads))});
  }
  return table.str() +
         "\nSpeedup = the sequential engine's seconds (same location mode, same seed) over the "
         "method's, per round; efficiency = speedup / threads. Each round is one seed: its "
         "points and its insertion order, so the spread over rounds mixes the input's variation "
         "with the machine's noise. Burglary's times include no repair. The batch method runs "
         "T - 1 locating threads and one inserting thread, so it has no 1-thread row.\n\n"
         "In the form of the paper's Table 1 (the range over the inputs and sizes above of the "
         "median speedups; the paper's ranges are over its sizes up to 200,000 points):\n\n" +
         table1.str();
}

}  // namespace

Study speedup_study() {
  return {"speedup",
          "speedup and efficiency of every lock method over the sequential engine of the same "
          "location mode, per thread count, per round (paper Table 1, Figs. 10, 12, 13, 15)",
          {5,
           2,
           {1, 2, 4},
           {1, 2},
           {10000, 50000, 100000, 200000},
           {3000},
           {"uniform", "dragon_vrip_res2"},
           {"uniform"},
           {engine::Location::Dag, engine::Location::Walk}},
          plan,
          summarize};
}

}  // namespace dtlab::experiments
