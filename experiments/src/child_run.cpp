#include "child_run.hpp"

#include <sys/resource.h>

#include <chrono>

#include "dtlab/engine/face_adjacency.hpp"
#include "dtlab/experiments/cgal_engine.hpp"
#include "dtlab/predicates/audit.hpp"
#include "flat_json.hpp"
#include "peers/peer_tools.hpp"

namespace dtlab::experiments {
namespace {

std::uint64_t peak_rss_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024;  // Linux reports KiB
}

void put_audit(Cells& cells) {
  const predicates::AuditCounters& counters = predicates::audit_counters();
  std::uint64_t calls = 0;
  std::uint64_t wrong = 0;
  std::uint64_t by_stage[predicates::kStageCount] = {};
  for (int p = 0; p < predicates::kPredicateCount; ++p) {
    calls += counters.calls[p].load();
    const std::uint64_t w = counters.wrong_sign[p].load();
    wrong += w;
    cells[std::string("audit.wrong_sign.") +
          predicates::predicate_name(static_cast<predicates::Predicate>(p))] = std::to_string(w);
    for (int s = 0; s < predicates::kStageCount; ++s) by_stage[s] += counters.by_stage[p][s].load();
  }
  cells["audit.calls"] = std::to_string(calls);
  cells["audit.wrong_sign"] = std::to_string(wrong);
  for (int s = 0; s < predicates::kStageCount; ++s) {
    cells[std::string("audit.stage.") + predicates::stage_name(static_cast<predicates::Stage>(s))] =
        std::to_string(by_stage[s]);
  }
}

Cells measure_cgal(const RunSpec& spec, const std::vector<predicates::Point3>& points) {
  const int threads = spec.engine == Engine::CgalParallel ? spec.options.threads : 1;
  const CgalRun run = run_cgal(points, threads);
  Cells cells;
  cells["points"] = std::to_string(points.size());
  cells["tetrahedra"] = std::to_string(run.finite_cells);
  cells["seconds.total"] = nlohmann::json(run.seconds).dump();
  cells["threads"] = std::to_string(threads);
  cells["method"] = to_string(spec.engine);
  cells["seed"] = std::to_string(spec.options.seed);
  const std::uint64_t peak = peak_rss_bytes();
  cells["peak_rss_bytes"] = std::to_string(peak);
  cells["bytes_per_point"] = std::to_string(points.empty() ? 0 : peak / points.size());
  return cells;
}

void put_validation(const engine::ValidationReport& report, Cells& cells) {
  for (auto& [key, value] : flatten(nlohmann::ordered_json::parse(report.json()))) {
    cells["validation." + key] = value;
  }
  cells["outcome"] = outcome_of(report);
}

// A peer's mesh, judged by the exact validator; a tool that does not orient its tetrahedra has
// the negative ones turned first (counted), flat ones stay errors.
Cells measure_peer(const RunSpec& spec, const std::vector<predicates::Point3>& points,
                   const std::string& scratch_dir) {
  const auto start = std::chrono::steady_clock::now();
  PeerMesh mesh = run_peer(spec.variant, points, spec.tetgen_program, scratch_dir);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::uint64_t turned =
      mesh.oriented ? 0 : engine::orient_positively(points, mesh.tetrahedra);
  Cells cells;
  cells["points"] = std::to_string(points.size());
  cells["tetrahedra"] = std::to_string(mesh.tetrahedra.size());
  cells["seconds.total"] = nlohmann::json(seconds).dump();
  cells["threads"] = std::to_string(1);  // (not "1": GCC 12's false -Wrestrict, bug 105329)
  cells["method"] = spec.variant;
  cells["seed"] = std::to_string(spec.options.seed);
  cells["peer.turned_tetrahedra"] = std::to_string(turned);
  cells["peer.version"] = spec.tool_version;
  put_validation(engine::validate(points, mesh.tetrahedra, engine::ValidateWith::Adaptive), cells);
  return cells;
}

}  // namespace

std::string outcome_of(const engine::ValidationReport& report) {
  return report.valid() ? "valid" : "invalid";
}

Cells measure_run(const RunSpec& spec, std::vector<predicates::Point3>& points,
                  const std::string& scratch_dir) {
  if (spec.engine == Engine::Peer) return measure_peer(spec, points, scratch_dir);
  if (spec.engine != Engine::Dtlab) return measure_cgal(spec, points);
  engine::TriangulateOptions options = spec.options;
  options.progress = false;
  options.audit = spec.audit;
  if (spec.audit) predicates::audit_counters().reset();
  // Moved in (the engine scales and orders them in place), handed back for the validator.
  engine::Triangulation result = engine::triangulate(std::move(points), options);
  points = std::move(result.points);
  Cells cells;
  for (auto& [key, value] : flatten(nlohmann::ordered_json::parse(engine::stats_json(
           result.stats, options, engine::to_string(options.method), options.threads)))) {
    cells[key] = value;
  }
  if (spec.audit) put_audit(cells);
  if (spec.validate) {
    put_validation(engine::validate(points, result.tetrahedra, engine::ValidateWith::Adaptive),
                   cells);
  }
  return cells;
}

}  // namespace dtlab::experiments
