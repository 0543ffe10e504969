#pragma once
// What a study is: a plan (the runs, from the parameters) and a summary (Markdown tables from the
// finished rows). The driver (experiment.cpp) runs the plan, appends the rows and writes the files.
#include <cstdint>
#include <string>
#include <vector>

#include "csv_table.hpp"
#include "dtlab/engine/triangulate.hpp"

namespace dtlab::experiments {

// Peer: another mesher of the `peers` study (peers/peer_tools.hpp), named by the run's variant.
enum class Engine { Dtlab, CgalSequential, CgalParallel, Peer };
const char* to_string(Engine e);

// One run: an input, an engine and its options, and what to measure beside the stats.
struct RunSpec {
  std::string input;      // the label: a generator family or a model name
  std::string source;     // a generator spec ("uniform:10000") or a file path
  std::int64_t size = 0;  // points asked for; 0 for a model (taken whole)
  std::string variant;    // the study's name for the configuration ("fast+repair", ...)
  Engine engine = Engine::Dtlab;
  engine::TriangulateOptions options;
  bool validate = false;  // the exact validator (adaptive kernel) on the result
  bool audit = false;     // count predicate calls per stage; fast: signs that differ from exact
  int round = 0;          // repeated runs of the same configuration (timing studies)
  double timeout_seconds = 0;  // the run is killed after this long (status "timeout"); 0: never
  std::string tetgen_program;  // Engine::Peer "tetgen": the program to run
  std::string tool_version;    // Engine::Peer: the tool's version, for its row
};

// The parameters after the study's defaults have filled what the user left out.
struct StudyParams {
  bool quick = false;
  int seeds = 1;
  std::vector<int> threads;
  std::vector<std::int64_t> sizes;
  std::vector<std::string> inputs;
  std::vector<engine::Location> locations;
  engine::Distribution distribution = engine::Distribution::Auto;
  std::string data_dir;
  unsigned hardware_threads = 1;
  double timeout_seconds = 0;      // each run's limit; 0: none
  std::vector<std::string> tools;  // the peers study's tools (peers/peer_tools.hpp, dtlab-*)
  std::string tetgen_program;
};

// The defaults of a study, full and quick. A study with no thread counts takes no --threads.
struct StudyDefaults {
  int seeds;
  int quick_seeds;
  std::vector<int> threads;
  std::vector<int> quick_threads;
  std::vector<std::int64_t> sizes;
  std::vector<std::int64_t> quick_sizes;
  std::vector<std::string> inputs;
  std::vector<std::string> quick_inputs;
  std::vector<engine::Location> locations;
  double timeout_seconds = 0;  // each run's limit unless --timeout; 0: none
  double quick_timeout_seconds = 0;
};

struct Study {
  const char* name;
  const char* summary;
  StudyDefaults defaults;
  std::vector<RunSpec> (*plan)(const StudyParams& params);
  // Markdown (headings, tables, short notes) from every row of the CSV.
  std::string (*summarize)(const CsvTable& rows);
  // A run that ends without a result is a finding (a peer that refuses, crashes or hangs):
  // --resume keeps it rather than running it again.
  bool failures_are_results = false;
};

const std::vector<Study>& all_studies();
// The study named `name`; nullptr when there is none.
const Study* find_study(const std::string& name);

// Resolves a model name (a file in the data directory, with or without its extension) or a path;
// empty when it is neither.
std::string model_path(const std::string& data_dir, const std::string& name);
bool is_generator_family(const std::string& name);

// A run of the dtlab engine on `source` with the given seed; the other options at their defaults.
RunSpec dtlab_run(const std::string& input, const std::string& source, std::int64_t size,
                  std::uint64_t seed);

// The runs of `input` at every size (a model is taken whole, once): calls add(label, source, size).
template <class Add>
void for_each_source(const StudyParams& params, const std::string& input, Add add) {
  if (is_generator_family(input)) {
    for (const std::int64_t n : params.sizes) add(input, input + ":" + std::to_string(n), n);
  } else {
    add(input, model_path(params.data_dir, input), std::int64_t{0});
  }
}

// The plans' common outer loops: every input at every size (a model once), every seed from 1, every
// location, in that order, as a dtlab run with those set; fn(spec) adds the study's runs.
template <class Fn>
void for_each_base_run(const StudyParams& params, Fn fn) {
  for (const std::string& input : params.inputs) {
    for_each_source(
        params, input, [&](const std::string& label, const std::string& source, std::int64_t n) {
          for (int seed = 1; seed <= params.seeds; ++seed) {
            for (const engine::Location location : params.locations) {
              RunSpec spec = dtlab_run(label, source, n, static_cast<std::uint64_t>(seed));
              spec.options.location = location;
              spec.options.distribution = params.distribution;
              fn(spec);
            }
          }
        });
  }
}

}  // namespace dtlab::experiments
