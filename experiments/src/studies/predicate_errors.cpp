// predicate-errors: the four kernels on every generator family: invalid results by kind, abandoned
// insertions, wrong signs (the audit compares each fast call with the exact kernel), time, and
// "fast, then star splaying" beside "adaptive throughout".
#include <algorithm>

#include "studies.hpp"

namespace dtlab::experiments {
namespace {

using engine::KernelKind;

struct Config {
  const char* variant;
  KernelKind kernel;
  bool repair;
  bool audit;
};

// Timed runs are validated; the audit runs (which evaluate every fast call twice) are not timed.
constexpr Config kConfigs[] = {
    {"fast", KernelKind::Fast, false, false},
    {"adaptive", KernelKind::Adaptive, false, false},
    {"filtered", KernelKind::Filtered, false, false},
    {"exact", KernelKind::Exact, false, false},
    {"fast+repair", KernelKind::Fast, true, false},
    {"audit:fast", KernelKind::Fast, false, true},
    {"audit:adaptive", KernelKind::Adaptive, false, true},
    {"audit:filtered", KernelKind::Filtered, false, true},
};

std::vector<RunSpec> plan(const StudyParams& p) {
  std::vector<RunSpec> runs;
  for_each_base_run(p, [&](RunSpec base) {
    for (const Config& c : kConfigs) {
      RunSpec spec = base;
      spec.variant = c.variant;
      spec.options.kernel = c.kernel;
      if (c.repair) spec.options.repair = engine::Repair::Splay;
      spec.audit = c.audit;
      spec.validate = !c.audit;
      runs.push_back(spec);
    }
  });
  return runs;
}

std::string count_runs(const CsvTable& t, const std::vector<const Row*>& rows, const char* column,
                       const char* bad) {
  std::size_t n = 0;
  for (const Row* r : rows) n += t.get(*r, column) == bad ? 1 : 0;
  return std::to_string(n);
}

std::string summarize(const CsvTable& t) {
  const std::vector<std::string> keys = {"input", "size_asked", "location"};
  // Every row, failed ones too: they are counted, not hidden.
  const auto sources = group_rows(t, keys, [](const Row&) { return true; });
  const auto rows_of = [&](const RowGroup& source, const std::string& variant, bool ok) {
    std::vector<const Row*> out;
    for (const Row* r : source.rows) {
      if (t.get(*r, "variant") == variant && is_ok(t, *r) == ok) out.push_back(r);
    }
    return out;
  };
  // The validator's other kinds: bad vertex ids, open boundary, volume or probe mismatches,
  // duplicate sets used twice.
  const auto other_violations = [&](const std::vector<const Row*>& rows) {
    double worst = 0.0;
    for (const Row* r : rows) {
      double sum = 0.0;
      for (const char* column :
           {"validation.invalid_tetrahedra", "validation.open_boundary_edges",
            "validation.volume_mismatch", "validation.volume_excess",
            "validation.probes_covered_twice", "validation.repeated_duplicates"}) {
        sum += t.number(*r, column);
      }
      worst = std::max(worst, sum);
    }
    return fixed(worst, 0);
  };
  MarkdownTable kernels({"input", "points", "kernel", "runs", "failed runs", "invalid runs",
                         "non-Delaunay faces", "flat or inverted", "overlapping faces",
                         "missing points", "reflex boundary", "other violations", "abandoned",
                         "wrong signs (audit)", "stage A %", "seconds (median)", "x adaptive"});
  MarkdownTable repair({"input", "points", "adaptive s", "fast s", "fast+repair s",
                        "of which splaying s", "fast+repair / adaptive", "valid after splaying",
                        "non-Delaunay faces splayed (max)"});
  for (const RowGroup& s : sources) {
    const std::string points = thousands(aggregate_of(t, s.rows, "points").median);
    const double adaptive = aggregate_of(t, rows_of(s, "adaptive", true), "seconds.total").median;
    for (const char* variant : {"fast", "adaptive", "filtered", "exact", "fast+repair"}) {
      const auto rows = rows_of(s, variant, true);
      const auto failed = rows_of(s, variant, false);
      if (rows.empty() && failed.empty()) continue;
      const std::string kernel = variant;
      const auto audit_rows = rows_of(s, "audit:" + kernel.substr(0, kernel.find('+')), true);
      const double seconds = aggregate_of(t, rows, "seconds.total").median;
      kernels.add({s.key[0], points, variant, std::to_string(rows.size() + failed.size()),
                   std::to_string(failed.size()), count_runs(t, rows, "validation.valid", "false"),
                   fixed(aggregate_of(t, rows, "validation.non_delaunay_faces").max, 0),
                   fixed(aggregate_of(t, rows, "validation.non_positive_orientation").max, 0),
                   fixed(aggregate_of(t, rows, "validation.non_manifold_faces").max +
                             aggregate_of(t, rows, "validation.inconsistent_faces").max,
                         0),
                   fixed(aggregate_of(t, rows, "validation.missing_points").max, 0),
                   fixed(aggregate_of(t, rows, "validation.reflex_boundary_edges").max +
                             aggregate_of(t, rows, "validation.reflex_boundary_vertices").max,
                         0),
                   other_violations(rows),
                   fixed(aggregate_of(t, rows, "abandoned_insertions").max, 0),
                   kernel == "fast" && !audit_rows.empty()
                       ? fixed(aggregate_of(t, audit_rows, "audit.wrong_sign").max, 0)
                       : "-",
                   (kernel == "adaptive" || kernel == "filtered") && !audit_rows.empty()
                       ? fixed(100.0 * aggregate_of(t, audit_rows, "audit.stage.A").mean /
                                   aggregate_of(t, audit_rows, "audit.calls").mean,
                               2)
                       : "-",
                   fixed(seconds, 3), fixed(seconds / adaptive, 2)});
    }
    const auto fast = rows_of(s, "fast", true);
    const auto fixed_up = rows_of(s, "fast+repair", true);
    if (fixed_up.empty()) continue;
    const double total = aggregate_of(t, fixed_up, "seconds.total").median;
    std::size_t valid = 0;
    for (const Row* r : fixed_up) valid += t.get(*r, "validation.valid") == "true" ? 1 : 0;
    repair.add({s.key[0], points, fixed(adaptive, 3),
                fixed(aggregate_of(t, fast, "seconds.total").median, 3), fixed(total, 3),
                fixed(aggregate_of(t, fixed_up, "splay.seconds").median, 3),
                fixed(total / adaptive, 2),
                std::to_string(valid) + " / " + std::to_string(fixed_up.size()),
                fixed(aggregate_of(t, fixed_up, "splay.non_delaunay_faces").max, 0)});
  }
  return "### Kernels per family\n\n" + kernels.str() +
         "\n\"invalid runs\" counts the runs whose mesh the exact validator rejects; the next "
         "columns are the largest count of each kind of violation over the seeds: faces whose "
         "opposite vertex lies inside the circumsphere, flat or inverted tetrahedra, faces shared "
         "by more than two tetrahedra or by two on the same side, distinct points that are no "
         "vertex, reflex boundary edges and vertices (a hull that is not convex), and the rest "
         "(vertex ids out of range, open boundary, volume or probe mismatches, duplicates used "
         "twice). \"failed runs\" ended without a mesh (an error); they are listed below the "
         "tables. The coplanar and collinear families are not in the default inputs: they have no "
         "tetrahedralization, and every kernel refuses them with an error. Wrong signs "
         "come from a separate audit run that evaluates every fast predicate call with the exact "
         "kernel too; the timed runs do not pay for it. \"stage A %\" is the share of the adaptive "
         "(or filtered) kernel's calls that its floating-point filter decided, from the same "
         "kind of audit run. The adaptive, filtered and exact kernels "
         "must have 0 in every error column.\n\n### Fast, then star splaying, against adaptive "
         "throughout\n\n" +
         repair.str() +
         "\n\"fast+repair\" triangulates with plain doubles, then repairs with star splaying and "
         "exact predicates (gDel3D's recipe on the CPU).\n";
}

}  // namespace

Study predicate_errors_study() {
  return {"predicate-errors",
          "fast, adaptive, filtered and exact predicates per generator family: invalid results, "
          "abandoned insertions, wrong signs, time, and fast-then-repair against adaptive",
          {3,
           1,
           {},
           {},
           {10000},
           {500},
           {"uniform", "normal", "cluster", "grid", "sphere", "planes", "cospherical", "duplicates",
            "near-duplicates", "lattice", "tiny", "huge"},
           {"uniform", "grid", "sphere", "near-duplicates"},
           {engine::Location::Dag}},
          plan,
          summarize};
}

}  // namespace dtlab::experiments
