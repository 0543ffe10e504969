#include "run_columns.hpp"

#include <algorithm>
#include <stdexcept>

#include "dtlab/engine/validator.hpp"
#include "dtlab/predicates/audit.hpp"
#include "flat_json.hpp"

namespace dtlab::experiments {
namespace {

const std::vector<std::string> kRunColumns = {
    "run_key",        "study",        "input",  "source",      "size_asked", "variant",
    "engine",         "round",        "status", "outcome",     "error",      "hardware_threads",
    "oversubscribed", "seconds_wall", "commit", "finished_utc"};

// The options that stats_json does not write, and the peers study's own count (it writes method,
// threads, distribution, predicates, location, insertion, bounding, repair and seed).
const std::vector<std::string> kOptionColumns = {"options.max_flips_per_insertion",
                                                 "options.max_location_steps",
                                                 "options.watchdog_seconds",
                                                 "options.max_tetrahedra",
                                                 "options.stress",
                                                 "options.validate",
                                                 "options.audit",
                                                 "options.timeout_seconds",
                                                 "peer.turned_tetrahedra",
                                                 "peer.version"};

std::vector<std::string> audit_columns() {
  std::vector<std::string> columns = {"audit.calls", "audit.wrong_sign"};
  for (int p = 0; p < predicates::kPredicateCount; ++p) {
    columns.push_back(std::string("audit.wrong_sign.") +
                      predicates::predicate_name(static_cast<predicates::Predicate>(p)));
  }
  for (int s = 0; s < predicates::kStageCount; ++s) {
    columns.push_back(std::string("audit.stage.") +
                      predicates::stage_name(static_cast<predicates::Stage>(s)));
  }
  return columns;
}

// The stats JSON with every optional part present, so that its keys are every stat's column.
nlohmann::ordered_json full_stats_template() {
  engine::TriangulationStats stats;
  stats.threads.resize(1);
  stats.post_check.done = true;
  stats.post_check.repaired = true;
  stats.splay.done = true;
  stats.hull_tetrahedra_lost = 0;
  stats.partition_passes.resize(1);
  stats.lock_grid_cells = 1;
  engine::TriangulateOptions options;
  options.method = engine::Method::Batch;
  return nlohmann::ordered_json::parse(engine::stats_json(stats, options, "batch", 2));
}

std::vector<std::string> build_columns() {
  std::vector<std::string> columns = kRunColumns;
  for (const std::string& c : kOptionColumns) columns.push_back(c);
  for (const auto& [key, value] : flatten(full_stats_template())) columns.push_back(key);
  const auto validation = nlohmann::ordered_json::parse(engine::ValidationReport{}.json());
  for (const auto& [key, value] : flatten(validation)) columns.push_back("validation." + key);
  for (const std::string& c : audit_columns()) columns.push_back(c);
  return columns;
}

}  // namespace

const std::vector<std::string>& run_columns() {
  static const std::vector<std::string> columns = build_columns();
  return columns;
}

std::size_t run_column(const std::string& column) {
  const auto& columns = run_columns();
  const auto it = std::find(columns.begin(), columns.end(), column);
  if (it == columns.end()) throw std::out_of_range("no run column " + column);
  return static_cast<std::size_t>(it - columns.begin());
}

std::string run_key(const RunSpec& spec) {
  const engine::TriangulateOptions& o = spec.options;
  // A peer takes none of the engine's options: its tool (the variant) and seed name it.
  if (spec.engine == Engine::Peer) {
    return spec.input + ":" + std::to_string(spec.size) + "/" + spec.variant + "/peer/seed" +
           std::to_string(o.seed) + "/round" + std::to_string(spec.round);
  }
  // Parallel dtlab runs only (the key of every other run is as before): --resume must not take a
  // row of one distribution for another.
  const bool split = spec.engine == Engine::Dtlab && o.method != engine::Method::Sequential;
  const std::string distribution =
      split ? std::string("/") + engine::to_string(engine::effective_distribution(o)) : "";
  // Cavity insertion only (flips keys stay as they were).
  const std::string cavity = o.insertion == engine::Insertion::Cavity ? "/cavity" : "";
  return spec.input + ":" + std::to_string(spec.size) + "/" + spec.variant + "/" +
         to_string(spec.engine) + "/" + engine::to_string(o.method) + "/" +
         std::to_string(o.threads) + "t/" + engine::to_string(o.kernel) + "/" +
         engine::to_string(o.location) + "/" + engine::to_string(o.bounding) + "/" +
         engine::to_string(o.repair) + "/seed" + std::to_string(o.seed) + "/round" +
         std::to_string(spec.round) + distribution + cavity;
}

}  // namespace dtlab::experiments
