#pragma once
// `dtlab experiment NAME`: one study of the paper's questions, run in-process (each run in a forked
// child, so that its audit counters and peak memory are its own and a failed run cannot end the
// study), written as
// DIR/NAME.csv (a row per run, appended as it finishes), DIR/NAME.md (the summary table),
// DIR/NAME.png (the plot, by tools/plot_study.py), DIR/machine.json and DIR/plan.json.
#include <cstdint>
#include <string>
#include <vector>

namespace dtlab::experiments {

struct ExperimentOptions {
  std::string out_dir;
  bool quick = false;   // a reduced run (at most two minutes) that checks the files, not numbers
  bool resume = false;  // keep DIR/NAME.csv's finished rows and run only the others
  bool plot = true;     // write DIR/NAME.png (needs python3 and matplotlib)
  int seeds = 0;        // 0: the study's default (rounds, for the timing studies)
  std::vector<int> threads;            // empty: the study's default
  std::vector<std::int64_t> sizes;     // empty: the study's default
  std::vector<std::string> inputs;     // generator families or model names; empty: default
  std::vector<std::string> locations;  // "dag", "walk"; empty: the study's default
  std::string distribution;            // the parallel runs' split (static, ..., auto); empty: auto
  std::string data_dir;                // the real models; empty: $DTLAB_DATA_DIR or ../shared/data
  double timeout_seconds = 0;  // each run killed after this long (status timeout); 0: the study's
  std::vector<std::string> tools;  // the peers study's tools; empty: all
  std::string tetgen;              // the peers study's TetGen program; empty: $DTLAB_TETGEN, tetgen
  std::string tools_dir;     // plot_study.py; empty: $DTLAB_TOOLS_DIR or the source tree's tools/
  std::string command_line;  // written above the summary table
  // "K/N": run only the K-th of N slices of the plan (every N-th run from the K-th), and write no
  // summary or plot; `merge` joins the slices. Empty: the whole plan.
  std::string shard;
};

struct StudyListing {
  std::string name;
  std::string summary;
};

std::vector<StudyListing> list_studies();

// Runs study `name`; returns 0, or 2 with a message on stderr for an unknown study, a missing
// --out or a failed plot. Bad parameters (an unknown input or location, --threads for a study
// that takes none), an unwritable directory or a CSV that cannot be resumed throw
// (std::invalid_argument, std::runtime_error, std::filesystem::filesystem_error); the CLI
// reports them and exits 2. A run that fails is a row with status "error" or "crashed".
int run_experiment(const std::string& name, const ExperimentOptions& options);

// `dtlab experiment merge OUT DIR...`: checks that the shards' folders hold one study's plan
// exactly once (one study, commit and set of parameters; every shard 1..N once; every run once)
// and writes OUT/NAME.csv, NAME.md, NAME.png, machines.json (every shard's machine), machine.json
// and plan.json. options.out_dir is OUT. A missing, doubled or foreign shard or run throws
// std::invalid_argument naming it (the CLI exits 2); a failed plot returns 2.
int merge_experiment(const std::vector<std::string>& dirs, const ExperimentOptions& options);

}  // namespace dtlab::experiments
