#include "dtlab/experiments/experiment.hpp"

#include <sched.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <stdexcept>

#include "dtlab/generators/generators.hpp"
#include "dtlab/io/point_readers.hpp"
#include "machine_record.hpp"
#include "run_columns.hpp"
#include "run_executor.hpp"
#include "study.hpp"
#include "summary.hpp"

extern char** environ;

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

engine::Distribution parse_distribution(const std::string& name) {
  for (const engine::Distribution d :
       {engine::Distribution::Static, engine::Distribution::Dynamic, engine::Distribution::Strips,
        engine::Distribution::Blocks, engine::Distribution::Auto}) {
    if (name == engine::to_string(d)) return d;
  }
  throw std::invalid_argument("unknown distribution " + name +
                              " (static | dynamic | strips | blocks | auto)");
}

StudyParams resolve(const Study& study, const ExperimentOptions& options) {
  const StudyDefaults& d = study.defaults;
  StudyParams p;
  p.quick = options.quick;
  p.seeds = options.seeds > 0 ? options.seeds : (options.quick ? d.quick_seeds : d.seeds);
  if (!options.threads.empty() && d.threads.empty()) {
    throw std::invalid_argument(std::string("study ") + study.name +
                                " runs the sequential engine only: it takes no --threads");
  }
  p.threads =
      !options.threads.empty() ? options.threads : (options.quick ? d.quick_threads : d.threads);
  p.sizes = !options.sizes.empty() ? options.sizes : (options.quick ? d.quick_sizes : d.sizes);
  p.inputs = !options.inputs.empty() ? options.inputs : (options.quick ? d.quick_inputs : d.inputs);
  for (const std::string& l : options.locations) p.locations.push_back(parse_location(l));
  if (p.locations.empty()) p.locations = d.locations;
  if (!options.distribution.empty()) p.distribution = parse_distribution(options.distribution);
  p.data_dir =
      !options.data_dir.empty()
          ? options.data_dir
          : from_env_or("DTLAB_DATA_DIR", std::string(DTLAB_SOURCE_DIR) + "/../shared/data");
  p.hardware_threads = available_cpus();
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
  // Mutable for the forked child, which moves its image of them into the engine.
  std::vector<predicates::Point3>& get(const RunSpec& spec) {
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

// Runs tools/plot_study.py through its #! line (Debian's python3, where python3-matplotlib
// lives, not a python3 that PATH may name first), without a shell.
bool plot(const std::string& tools_dir, const std::string& name, const fs::path& dir) {
  const std::string script = tools_dir + "/plot_study.py";
  if (!fs::is_regular_file(script)) {
    std::fprintf(stderr, "dtlab: error: %s not found ($DTLAB_TOOLS_DIR)\n", script.c_str());
    return false;
  }
  const std::string csv = (dir / (name + ".csv")).string();
  const std::string png = (dir / (name + ".png")).string();
  std::vector<char*> argv = {const_cast<char*>(script.c_str()), const_cast<char*>(name.c_str()),
                             const_cast<char*>(csv.c_str()), const_cast<char*>(png.c_str()),
                             nullptr};
  std::fflush(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, script.c_str(), nullptr, nullptr, argv.data(), environ) != 0) {
    return false;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

// The rows a resumed study keeps: finished (status ok) runs of this plan. Rows of an older
// version's CSV are mapped when their columns are a subset of today's (new cells stay empty).
struct Resumed {
  std::vector<std::vector<std::string>> kept;
  std::set<std::string> finished;
};

Resumed resume_rows(const fs::path& csv_path, const std::set<std::string>& planned) {
  Resumed r;
  if (!fs::exists(csv_path) || fs::file_size(csv_path) == 0) return r;
  std::size_t cut = 0;
  const CsvTable old = read_csv(csv_path.string(), &cut);
  std::vector<std::size_t> to_new;
  for (const std::string& column : old.header) {
    try {
      to_new.push_back(run_column(column));
    } catch (const std::out_of_range&) {
      throw std::runtime_error(csv_path.string() + " has a column " + column +
                               " this version does not write: run without --resume");
    }
  }
  std::vector<std::vector<std::string>> other_plan;
  std::size_t failed = 0;
  for (const auto& row : old.rows) {
    std::vector<std::string> mapped(run_columns().size());
    for (std::size_t i = 0; i < row.size(); ++i) mapped[to_new[i]] = row[i];
    std::string& key = mapped[run_column("run_key")];
    // Keys written before the distribution joined them: a parallel row gets the one it ran with.
    const std::string& distribution = mapped[run_column("distribution")];
    const std::string suffix = "/" + distribution;
    if (mapped[run_column("engine")] == "dtlab" && mapped[run_column("method")] != "sequential" &&
        !distribution.empty() && !key.ends_with(suffix)) {
      key += suffix;
    }
    if (mapped[run_column("status")] != "ok") {
      ++failed;
    } else if (planned.count(key) == 0) {
      other_plan.push_back(std::move(mapped));
    } else if (r.finished.insert(key).second) {
      r.kept.push_back(std::move(mapped));
    }
  }
  std::fprintf(stderr, "dtlab: resuming %s: %zu finished rows kept", csv_path.c_str(),
               r.kept.size());
  if (cut > 0) std::fprintf(stderr, ", %zu cut lines dropped", cut);
  if (failed > 0) std::fprintf(stderr, ", %zu failed runs to run again", failed);
  if (old.header.size() != run_columns().size()) {
    std::fprintf(stderr, ", %zu columns new in this version left empty in them",
                 run_columns().size() - old.header.size());
  }
  std::fprintf(stderr, "\n");
  if (!other_plan.empty()) {
    fs::path aside = csv_path;
    aside.replace_extension(".other-runs.csv");
    CsvAppender keep_aside(aside.string(), run_columns(), other_plan);
    std::fprintf(stderr, "dtlab: %zu rows of other parameters moved to %s\n", other_plan.size(),
                 aside.c_str());
  }
  return r;
}

// "Runs measured at commit X" (or "at commits X, Y") from the rows' commit column.
std::string row_commits(const CsvTable& table) {
  std::set<std::string> commits;
  for (const auto& row : table.rows) commits.insert(short_commit(table.get(row, "commit")));
  std::string out;
  for (const std::string& c : commits) out += (out.empty() ? "" : ", ") + c;
  return commits.size() == 1 ? "commit " + out : "commits " + out;
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
    machine << machine_json(source_dir, options.command_line) << "\n";
    if (!machine) throw std::runtime_error((dir / "machine.json").string() + ": cannot write");
  }

  const fs::path csv_path = dir / (name + ".csv");
  std::set<std::string> finished;
  std::unique_ptr<CsvAppender> csv;
  {
    Resumed resumed;
    if (options.resume) resumed = resume_rows(csv_path, planned);
    finished = std::move(resumed.finished);
    csv = std::make_unique<CsvAppender>(csv_path.string(), run_columns(), resumed.kept);
  }  // the kept rows are freed before any run: the children's memory does not hold them

  const std::size_t status_column = run_column("status");
  const std::size_t wall_column = run_column("seconds_wall");
  const std::string commit = git_commit(source_dir);
  const auto start = std::chrono::steady_clock::now();
  PointCache cache;
  std::size_t done = 0;
  std::size_t failed = 0;
  for (const RunSpec& spec : plan) {
    ++done;
    const std::string key = run_key(spec);
    if (finished.count(key) != 0) continue;
    std::vector<std::string> row =
        execute_isolated(name, spec, cache.get(spec), params.hardware_threads);
    row[run_column("commit")] = commit;
    row[run_column("finished_utc")] = utc_now();
    csv->append(row);
    const std::string& status = row[status_column];
    if (status != "ok") ++failed;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "[%zu/%zu %.0f s] %s: %s %s s\n", done, plan.size(), elapsed, key.c_str(),
                 status.c_str(), row[wall_column].c_str());
  }
  csv.reset();

  const CsvTable table = read_csv(csv_path.string());
  std::string md = "## " + name + ": " + study->summary + "\n\n";
  md += "`" + options.command_line + "`  \n";
  md += "Machine: " + machine_line() + ". Runs measured at " + row_commits(table) +
        ". Seeds (rounds): " + std::to_string(params.seeds) + ". " +
        std::to_string(table.rows.size()) + " runs.\n\n";
  md += study->summarize(table);
  md += failed_runs(table);
  {
    std::ofstream out(dir / (name + ".md"));
    out << md;
    if (!out) throw std::runtime_error((dir / (name + ".md")).string() + ": cannot write");
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
                   "dtlab: error: the plot failed (python3 with matplotlib: scripts/setup.sh); "
                   "the CSV and the table are written\n");
      return 2;
    }
  }
  return 0;
}

}  // namespace dtlab::experiments
