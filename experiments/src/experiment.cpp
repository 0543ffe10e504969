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
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "dtlab/engine/methods.hpp"
#include "dtlab/generators/generators.hpp"
#include "dtlab/io/point_readers.hpp"
#include "machine_record.hpp"
#include "peers/peer_tools.hpp"
#include "run_columns.hpp"
#include "run_executor.hpp"
#include "shards.hpp"
#include "studies/studies.hpp"
#include "study.hpp"
#include "study_output.hpp"

extern char** environ;

namespace dtlab::experiments {
namespace {

namespace fs = std::filesystem;

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

// The peers study's tools and TetGen program, checked before any run: an unknown tool, a TetGen
// that is not installed or a build without Qhull is an error here, not a column of failed runs.
void resolve_tools(const Study& study, const ExperimentOptions& options, StudyParams& p) {
  const bool peers = std::string(study.name) == "peers";
  if (!peers && (!options.tools.empty() || !options.tetgen.empty())) {
    throw std::invalid_argument(std::string("--tools and --tetgen are the peers study's; ") +
                                study.name + " takes neither");
  }
  if (!peers) return;
  if (!options.locations.empty() || !options.distribution.empty()) {
    throw std::invalid_argument(
        "peers takes no --location or --distribution: its dtlab runs are sequential, with the "
        "walk and cavities (dtlab triangulate's default)");
  }
  p.tetgen_program =
      !options.tetgen.empty() ? options.tetgen : from_env_or("DTLAB_TETGEN", "tetgen");
  const auto missing = [&](const std::string& tool) -> std::string {
    if (tool.rfind("qhull", 0) == 0 && !qhull_available()) {
      return "this build has no Qhull (libqhull-dev, scripts/setup.sh, then rebuild)";
    }
    if (tool == "tetgen" && !program_found(p.tetgen_program)) {
      return "no program " + p.tetgen_program + " (apt-get install tetgen, or --tetgen PATH)";
    }
    return "";
  };
  const std::vector<std::string> known = peers_study_tools();
  std::string names;
  for (const std::string& k : known) names += (names.empty() ? "" : ", ") + k;
  if (options.tools.empty()) {
    // Every tool this machine has; the others are named, and left out.
    for (const std::string& tool : known) {
      const std::string why = missing(tool);
      if (why.empty()) {
        p.tools.push_back(tool);
      } else {
        std::fprintf(stderr, "dtlab: peers: %s left out: %s\n", tool.c_str(), why.c_str());
      }
    }
    return;
  }
  p.tools = options.tools;
  for (const std::string& tool : p.tools) {
    if (std::find(known.begin(), known.end(), tool) == known.end()) {
      throw std::invalid_argument("--tools: unknown tool " + tool + " (known: " + names + ")");
    }
    const std::string why = missing(tool);
    if (!why.empty())
      throw std::invalid_argument(tool + ": " + why + "; or leave it out of --tools");
  }
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
  if (options.timeout_seconds < 0) throw std::invalid_argument("--timeout: seconds >= 0");
  p.timeout_seconds = options.timeout_seconds > 0
                          ? options.timeout_seconds
                          : (options.quick ? d.quick_timeout_seconds : d.timeout_seconds);
  resolve_tools(study, options, p);
  // The methods whose waits spin refuse more threads than the CPUs serve (docs/design.md, "Threads
  // a CPU"); a study refuses the count rather than plan runs that would differ from machine to
  // machine.
  const int spinning_most = engine::kSpinningThreadsPerCpu * static_cast<int>(p.hardware_threads);
  for (const int t : p.threads) {
    if (t < 1 || t > 1024) throw std::invalid_argument("--threads: each count in [1, 1024]");
    if (t > spinning_most) {
      throw std::invalid_argument(
          "--threads " + std::to_string(t) + ": at most " + std::to_string(spinning_most) +
          " here, the most that optimistic-detect, optimistic-prevent, burglary and lock-grid run "
          "on the " +
          std::to_string(p.hardware_threads) + " CPUs available (" +
          std::to_string(engine::kSpinningThreadsPerCpu) + " a CPU)");
    }
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

// Each run's point set (source and seed), numbered in first-seen order.
std::vector<int> point_set_groups(const std::vector<RunSpec>& plan) {
  std::map<std::string, int> number;
  std::vector<int> groups;
  for (const RunSpec& spec : plan) {
    const std::string key = spec.source + "#" + std::to_string(spec.options.seed);
    groups.push_back(number.emplace(key, static_cast<int>(number.size())).first->second);
  }
  return groups;
}

// The rows a resumed study keeps: finished (status ok) runs of this plan. Rows of an older
// version's CSV are mapped when their columns are a subset of today's (new cells stay empty).
struct Resumed {
  std::vector<std::vector<std::string>> kept;
  std::set<std::string> finished;
};

// `keep_failed`: a run that ended without a result but with an outcome (the peers study's refused,
// crashed and hung tools) is a result too, and is kept like a finished one.
// A row run with another --timeout is of other parameters (a kept "hung" row must have had this
// timeout).
Resumed resume_rows(const fs::path& csv_path, const std::set<std::string>& planned,
                    bool keep_failed, double timeout_seconds) {
  const std::string timeout = nlohmann::json(timeout_seconds).dump();
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
    const bool has_outcome = keep_failed && !mapped[run_column("outcome")].empty();
    if (mapped[run_column("status")] != "ok" && !has_outcome) {
      ++failed;
    } else if (planned.count(key) == 0 ||
               (!mapped[run_column("options.timeout_seconds")].empty() &&
                mapped[run_column("options.timeout_seconds")] != timeout)) {
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

}  // namespace

std::vector<StudyListing> list_studies() {
  std::vector<StudyListing> out;
  for (const Study& s : all_studies()) out.push_back({s.name, s.summary});
  return out;
}

int run_experiment(const std::string& name, const ExperimentOptions& options) {
  const Study* study = find_study(name);
  if (study == nullptr) {
    std::fprintf(stderr, "dtlab: error: unknown study %s (dtlab experiment --list)\n",
                 name.c_str());
    return 2;
  }
  if (options.out_dir.empty()) {
    std::fprintf(stderr, "dtlab: error: --out DIR is required\n");
    return 2;
  }
  const Shard shard = parse_shard(options.shard);
  const StudyParams params = resolve(*study, options);
  const std::vector<RunSpec> plan = study->plan(params);
  std::vector<std::string> plan_keys;
  std::set<std::string> planned;
  for (const RunSpec& spec : plan) {
    plan_keys.push_back(run_key(spec));
    if (!planned.insert(plan_keys.back()).second) {
      throw std::logic_error("study " + name + " plans run " + plan_keys.back() + " twice");
    }
  }
  // This shard's runs: the plan cut into groups of runs on the same points (source and seed, in
  // first-seen order), every count-th group from the shard's index; so the slices of any count
  // cover the same plan exactly once, and a shard generates or reads each point set once.
  const std::vector<int> groups = point_set_groups(plan);
  std::vector<const RunSpec*> mine;
  std::set<std::string> my_keys;
  for (std::size_t i = 0; i < plan.size(); ++i) {
    if (shard.count == 0 || groups[i] % shard.count == shard.index - 1) {
      mine.push_back(&plan[i]);
      my_keys.insert(plan_keys[i]);
    }
  }

  const fs::path dir(options.out_dir);
  fs::create_directories(dir);
  const std::string source_dir = source_tree();
  const std::string commit = git_commit(source_dir);
  write_text(dir / "machine.json", machine_json(source_dir, options.command_line) + "\n");
  write_text(dir / "plan.json", plan_json(name, shard, commit, params, plan_keys, groups) + "\n");

  const fs::path csv_path = dir / (name + ".csv");
  std::set<std::string> finished;
  std::unique_ptr<CsvAppender> csv;
  {
    Resumed resumed;
    if (options.resume)
      resumed = resume_rows(csv_path, my_keys, study->failures_are_results, params.timeout_seconds);
    finished = std::move(resumed.finished);
    csv = std::make_unique<CsvAppender>(csv_path.string(), run_columns(), resumed.kept);
  }  // the kept rows are freed before any run: the children's memory does not hold them

  const std::size_t status_column = run_column("status");
  const std::size_t wall_column = run_column("seconds_wall");
  const auto start = std::chrono::steady_clock::now();
  PointCache cache;
  std::size_t done = 0;
  std::size_t failed = 0;
  for (const RunSpec* spec : mine) {
    ++done;
    const std::string key = run_key(*spec);
    if (finished.count(key) != 0) continue;
    RunSpec run = *spec;
    run.timeout_seconds = params.timeout_seconds;
    std::vector<std::string> row =
        execute_isolated(name, run, cache.get(run), params.hardware_threads);
    row[run_column("commit")] = commit;
    row[run_column("finished_utc")] = utc_now();
    csv->append(row);
    const std::string& status = row[status_column];
    if (status != "ok") ++failed;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "[%zu/%zu %.0f s] %s: %s %s s\n", done, mine.size(), elapsed, key.c_str(),
                 status.c_str(), row[wall_column].c_str());
  }
  csv.reset();
  if (failed > 0) std::fprintf(stderr, "dtlab: %zu runs ended without a result\n", failed);
  if (shard.count != 0) {
    // A shard's rows are a slice: the summary and the plot come from the merge of every shard.
    std::fprintf(stderr,
                 "dtlab: shard %d/%d: wrote %s, plan.json and machine.json in %s; merge the "
                 "shards with dtlab experiment merge OUT DIR...\n",
                 shard.index, shard.count, csv_path.c_str(), dir.c_str());
    return 0;
  }
  SummaryHeader header;
  header.command = "`" + options.command_line + "`";
  header.machines = "Machine: " + machine_line() + ".";
  header.seeds = params.seeds;
  std::fprintf(stderr, "dtlab: wrote %s, %s.md and machine.json in %s\n", csv_path.c_str(),
               name.c_str(), dir.c_str());
  return write_summary(*study, dir, header, options) ? 0 : 2;
}

}  // namespace dtlab::experiments
