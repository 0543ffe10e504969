#include "dtlab/experiments/experiment.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>
#include <thread>

#include "dtlab/generators/generators.hpp"
#include "dtlab/io/point_readers.hpp"
#include "machine_record.hpp"
#include "run_executor.hpp"
#include "study.hpp"
#include "summary.hpp"

namespace dtlab::experiments {
namespace {

namespace fs = std::filesystem;

std::string from_env_or(const char* variable, const std::string& fallback) {
  const char* value = std::getenv(variable);
  return value != nullptr && *value != '\0' ? value : fallback;
}

engine::Location parse_location(const std::string& name) {
  if (name == "dag") return engine::Location::Dag;
  if (name == "walk") return engine::Location::Walk;
  throw std::invalid_argument("unknown location " + name + " (dag | walk)");
}

StudyParams resolve(const Study& study, const ExperimentOptions& options) {
  const StudyDefaults& d = study.defaults;
  StudyParams p;
  p.quick = options.quick;
  p.seeds = options.seeds > 0 ? options.seeds : (options.quick ? d.quick_seeds : d.seeds);
  p.threads =
      !options.threads.empty() ? options.threads : (options.quick ? d.quick_threads : d.threads);
  p.sizes = !options.sizes.empty() ? options.sizes : (options.quick ? d.quick_sizes : d.sizes);
  p.inputs = !options.inputs.empty() ? options.inputs : (options.quick ? d.quick_inputs : d.inputs);
  for (const std::string& l : options.locations) p.locations.push_back(parse_location(l));
  if (p.locations.empty()) p.locations = d.locations;
  p.data_dir =
      !options.data_dir.empty()
          ? options.data_dir
          : from_env_or("DTLAB_DATA_DIR", std::string(DTLAB_SOURCE_DIR) + "/../shared/data");
  p.hardware_threads = std::max(1U, std::thread::hardware_concurrency());
  for (const int t : p.threads) {
    if (t < 1 || t > 1024) throw std::invalid_argument("--threads: each count in [1, 1024]");
  }
  for (const std::int64_t n : p.sizes) {
    if (n < 1 || n > generators::kMaxPoints) throw std::invalid_argument("--sizes: out of range");
  }
  for (const std::string& input : p.inputs) {
    if (!is_generator_family(input) && model_path(p.data_dir, input).empty()) {
      throw std::invalid_argument("input " + input +
                                  ": neither a generator family (dtlab generate --help) nor a "
                                  "point file in " +
                                  p.data_dir + " (--data DIR)");
    }
  }
  return p;
}

// The points of a run; a generator's points depend on the seed, a model's do not.
class PointCache {
 public:
  const std::vector<predicates::Point3>& get(const RunSpec& spec) {
    std::string family;
    std::int64_t n = 0;
    const bool generated = generators::parse_spec(spec.source, family, n);
    const std::string key =
        generated ? spec.source + "#" + std::to_string(spec.options.seed) : spec.source;
    if (key != key_) {
      points_ = generated ? generators::generate(family, n, spec.options.seed).points
                          : io::read_points(spec.source);
      key_ = key;
    }
    return points_;
  }

 private:
  std::string key_;
  std::vector<predicates::Point3> points_;
};

bool plot(const std::string& tools_dir, const std::string& name, const fs::path& dir) {
  const std::string script = tools_dir + "/plot_study.py";
  if (!fs::is_regular_file(script)) {
    std::fprintf(stderr, "dtlab: error: %s not found (--tools DIR)\n", script.c_str());
    return false;
  }
  // Through its #! line (Debian's python3, where python3-matplotlib lives), not a python3 that
  // PATH may name first.
  const std::string command = "'" + script + "' " + name + " '" + (dir / (name + ".csv")).string() +
                              "' '" + (dir / (name + ".png")).string() + "'";
  std::fflush(nullptr);
  return std::system(command.c_str()) == 0;
}

}  // namespace

std::vector<StudyListing> list_studies() {
  std::vector<StudyListing> out;
  for (const Study& s : all_studies()) out.push_back({s.name, s.summary});
  return out;
}

int run_experiment(const std::string& name, const ExperimentOptions& options) {
  const Study* study = nullptr;
  for (const Study& s : all_studies()) {
    if (name == s.name) study = &s;
  }
  if (study == nullptr) {
    std::fprintf(stderr, "dtlab: error: unknown study %s (dtlab experiment --list)\n",
                 name.c_str());
    return 2;
  }
  if (options.out_dir.empty()) {
    std::fprintf(stderr, "dtlab: error: --out DIR is required\n");
    return 2;
  }
  const StudyParams params = resolve(*study, options);
  const std::vector<RunSpec> plan = study->plan(params);
  std::set<std::string> planned;
  for (const RunSpec& spec : plan) {
    if (!planned.insert(run_key(spec)).second) {
      throw std::logic_error("study " + name + " plans run " + run_key(spec) + " twice");
    }
  }

  const fs::path dir(options.out_dir);
  fs::create_directories(dir);
  const std::string source_dir = from_env_or("DTLAB_SOURCE_DIR", DTLAB_SOURCE_DIR);
  {
    std::ofstream machine(dir / "machine.json");
    if (!machine) throw std::runtime_error((dir / "machine.json").string() + ": cannot write");
    machine << machine_json(source_dir, options.command_line) << "\n";
  }

  const fs::path csv_path = dir / (name + ".csv");
  std::vector<std::vector<std::string>> kept;
  std::set<std::string> finished;
  if (options.resume && fs::exists(csv_path)) {
    std::size_t dropped = 0;
    CsvTable old = read_csv(csv_path.string(), &dropped);
    if (old.header != run_columns()) {
      throw std::runtime_error(csv_path.string() +
                               " has other columns (another dtlab version): run without --resume");
    }
    for (auto& row : old.rows) {
      finished.insert(row[old.column("run_key")]);
      kept.push_back(std::move(row));
    }
    std::fprintf(stderr, "dtlab: resuming %s: %zu finished rows kept%s\n", csv_path.c_str(),
                 kept.size(), dropped > 0 ? ", a cut last line dropped" : "");
  }
  CsvAppender csv(csv_path.string(), run_columns(), kept);

  const auto column_of = [](const char* column) {
    const auto& columns = run_columns();
    return static_cast<std::size_t>(std::find(columns.begin(), columns.end(), column) -
                                    columns.begin());
  };
  const std::size_t status_column = column_of("status");
  const std::size_t wall_column = column_of("seconds_wall");
  const std::size_t commit_column = column_of("commit");
  const std::size_t finished_column = column_of("finished_utc");
  const std::string commit = git_commit(source_dir);
  const auto start = std::chrono::steady_clock::now();
  PointCache cache;
  std::size_t done = 0;
  std::size_t failed = 0;
  for (const RunSpec& spec : plan) {
    ++done;
    const std::string key = run_key(spec);
    if (finished.count(key) != 0) continue;
    const auto& points = cache.get(spec);
    std::vector<std::string> row = execute_isolated(name, spec, points, params.hardware_threads);
    row[commit_column] = commit;
    row[finished_column] = utc_now();
    csv.append(row);
    const std::string& status = row[status_column];
    if (status != "ok") ++failed;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "[%zu/%zu %.0f s] %s: %s %s s\n", done, plan.size(), elapsed, key.c_str(),
                 status.c_str(), row[wall_column].c_str());
  }

  const CsvTable table = read_csv(csv_path.string());
  std::string md = "## " + name + ": " + study->summary + "\n\n";
  md += "`" + options.command_line + "`  \n";
  md += "Machine: " + machine_line(source_dir) +
        ". Seeds (rounds): " + std::to_string(params.seeds) + ". " +
        std::to_string(table.rows.size()) + " runs.\n\n";
  md += study->summarize(table, params);
  md += failed_runs(table);
  {
    std::ofstream out(dir / (name + ".md"));
    if (!out) throw std::runtime_error((dir / (name + ".md")).string() + ": cannot write");
    out << md;
  }
  std::printf("%s", md.c_str());
  std::fflush(stdout);
  std::fprintf(stderr, "dtlab: wrote %s, %s.md and machine.json in %s\n", csv_path.c_str(),
               name.c_str(), dir.c_str());
  if (failed > 0) std::fprintf(stderr, "dtlab: %zu runs ended without a result\n", failed);
  if (options.plot) {
    const std::string tools =
        !options.tools_dir.empty()
            ? options.tools_dir
            : from_env_or("DTLAB_TOOLS_DIR", std::string(DTLAB_SOURCE_DIR) + "/tools");
    if (!plot(tools, name, dir)) {
      std::fprintf(stderr,
                   "dtlab: error: the plot failed (python3 with matplotlib: "
                   "scripts/setup.sh); the CSV and the table are written\n");
      return 2;
    }
  }
  return 0;
}

}  // namespace dtlab::experiments
