#include "run_executor.hpp"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <exception>
#include <map>

#include "dtlab/engine/validator.hpp"
#include "dtlab/experiments/cgal_engine.hpp"
#include "dtlab/predicates/audit.hpp"
#include "flat_json.hpp"

namespace dtlab::experiments {
namespace {

constexpr char kSeparator = '\x1f';  // between the values the child sends back

const std::vector<std::string> kRunColumns = {
    "run_key",          "study",          "input",        "source", "size_asked",
    "variant",          "engine",         "round",        "status", "error",
    "hardware_threads", "oversubscribed", "seconds_wall", "commit", "finished_utc"};

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
  engine::TriangulateOptions options;
  options.method = engine::Method::Batch;
  return nlohmann::ordered_json::parse(engine::stats_json(stats, options, "batch", 2));
}

std::vector<std::string> build_columns() {
  std::vector<std::string> columns = kRunColumns;
  for (const auto& [key, value] : flatten(full_stats_template())) columns.push_back(key);
  const auto validation = nlohmann::ordered_json::parse(engine::ValidationReport{}.json());
  for (const auto& [key, value] : flatten(validation)) columns.push_back("validation." + key);
  for (const std::string& c : audit_columns()) columns.push_back(c);
  return columns;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::uint64_t peak_rss_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024;  // Linux reports KiB
}

void put_audit(std::map<std::string, std::string>& cells) {
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

// The run itself, in the child: the cells it measured (the driver adds the rest).
void run_in_child(const RunSpec& spec, const std::vector<predicates::Point3>& points,
                  std::map<std::string, std::string>& cells) {
  if (spec.engine != Engine::Dtlab) {
    const int threads = spec.engine == Engine::CgalParallel ? spec.options.threads : 1;
    const CgalRun run = run_cgal(points, threads);
    cells["points"] = std::to_string(points.size());
    cells["tetrahedra"] = std::to_string(run.finite_cells);
    cells["seconds.total"] = nlohmann::json(run.seconds).dump();
    cells["threads"] = std::to_string(threads);
    cells["method"] = threads > 1 ? "cgal-parallel" : "cgal";
    cells["seed"] = std::to_string(spec.options.seed);
    const std::uint64_t peak = peak_rss_bytes();
    cells["peak_rss_bytes"] = std::to_string(peak);
    cells["bytes_per_point"] = std::to_string(points.empty() ? 0 : peak / points.size());
    return;
  }
  engine::TriangulateOptions options = spec.options;
  options.progress = false;
  options.audit = spec.audit;
  if (spec.audit) predicates::audit_counters().reset();
  const engine::Triangulation result = engine::triangulate(points, options);
  for (auto& [key, value] : flatten(nlohmann::ordered_json::parse(engine::stats_json(
           result.stats, options, engine::to_string(options.method), options.threads)))) {
    cells[key] = value;
  }
  if (spec.audit) put_audit(cells);
  if (spec.validate) {
    const engine::ValidationReport report =
        engine::validate(points, result.tetrahedra, engine::ValidateWith::Adaptive);
    for (auto& [key, value] : flatten(nlohmann::ordered_json::parse(report.json()))) {
      cells["validation." + key] = value;
    }
  }
}

std::string join_cells(const std::map<std::string, std::string>& cells) {
  std::string out;
  for (const auto& [key, value] : cells) {
    out += key;
    out += kSeparator;
    out += value;
    out += kSeparator;
  }
  return out;
}

std::map<std::string, std::string> split_cells(const std::string& text) {
  std::map<std::string, std::string> cells;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t key_end = text.find(kSeparator, pos);
    if (key_end == std::string::npos) break;
    const std::size_t value_end = text.find(kSeparator, key_end + 1);
    if (value_end == std::string::npos) break;
    cells[text.substr(pos, key_end - pos)] = text.substr(key_end + 1, value_end - key_end - 1);
    pos = value_end + 1;
  }
  return cells;
}

bool write_all(int fd, const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

const char* to_string(Engine e) {
  switch (e) {
    case Engine::Dtlab:
      return "dtlab";
    case Engine::CgalSequential:
      return "cgal";
    case Engine::CgalParallel:
      return "cgal-parallel";
  }
  return "?";
}

const std::vector<std::string>& run_columns() {
  static const std::vector<std::string> columns = build_columns();
  return columns;
}

std::string run_key(const RunSpec& spec) {
  const engine::TriangulateOptions& o = spec.options;
  return spec.input + ":" + std::to_string(spec.size) + "/" + spec.variant + "/" +
         to_string(spec.engine) + "/" + engine::to_string(o.method) + "/" +
         std::to_string(o.threads) + "t/" + engine::to_string(o.kernel) + "/" +
         engine::to_string(o.location) + "/" + engine::to_string(o.bounding) + "/" +
         engine::to_string(o.repair) + "/seed" + std::to_string(o.seed) + "/round" +
         std::to_string(spec.round);
}

std::vector<std::string> execute_isolated(const std::string& study, const RunSpec& spec,
                                          const std::vector<predicates::Point3>& points,
                                          unsigned hardware_threads) {
  std::map<std::string, std::string> cells;
  const auto start = std::chrono::steady_clock::now();
  std::fflush(nullptr);  // nothing buffered is written twice
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("pipe failed");
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    close(fds[0]);
    std::map<std::string, std::string> measured;
    try {
      run_in_child(spec, points, measured);
      measured["status"] = "ok";
    } catch (const std::exception& e) {
      measured["status"] = "error";
      measured["error"] = e.what();
    }
    _exit(write_all(fds[1], join_cells(measured)) ? 0 : 1);
  }
  close(fds[1]);
  std::string text;
  char buffer[4096];
  for (;;) {
    const ssize_t n = read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
  }
  close(fds[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  cells = split_cells(text);
  if (WIFSIGNALED(status)) {
    cells["status"] = "crashed";
    cells["error"] = "the run ended by signal " + std::to_string(WTERMSIG(status));
  } else if (cells.find("status") == cells.end()) {
    cells["status"] = "crashed";
    cells["error"] = "the run sent no result";
  }
  cells["seconds_wall"] = nlohmann::json(seconds_since(start)).dump();
  cells["run_key"] = run_key(spec);
  cells["study"] = study;
  cells["input"] = spec.input;
  cells["source"] = spec.source;
  cells["size_asked"] = std::to_string(spec.size);
  cells["variant"] = spec.variant;
  cells["engine"] = to_string(spec.engine);
  cells["round"] = std::to_string(spec.round);
  cells["hardware_threads"] = std::to_string(hardware_threads);
  cells["oversubscribed"] =
      spec.options.threads > static_cast<int>(hardware_threads) ? "true" : "false";
  // Options the engine's JSON did not give (a failed run, CGAL): from the spec.
  const auto fill = [&](const char* key, const std::string& value) {
    if (cells[key].empty()) cells[key] = value;
  };
  fill("threads", std::to_string(spec.options.threads));
  fill("seed", std::to_string(spec.options.seed));
  if (spec.engine == Engine::Dtlab) {
    fill("method", engine::to_string(spec.options.method));
    fill("predicates", engine::to_string(spec.options.kernel));
    fill("location", engine::to_string(spec.options.location));
    fill("bounding", engine::to_string(spec.options.bounding));
    fill("repair", engine::to_string(spec.options.repair));
    fill("distribution", engine::to_string(spec.options.distribution));
  } else {
    fill("method", to_string(spec.engine));
  }
  std::vector<std::string> row;
  for (const std::string& column : run_columns()) {
    const auto it = cells.find(column);
    row.push_back(it == cells.end() ? std::string() : it->second);
  }
  return row;
}

}  // namespace dtlab::experiments
