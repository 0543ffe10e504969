#pragma once
// What a study's rows become, for a run and for a merge of shards alike: DIR/NAME.md (the summary,
// also printed on stdout) and DIR/NAME.png (tools/plot_study.py); and the small things both need.
#include <filesystem>
#include <string>

#include "dtlab/experiments/experiment.hpp"
#include "study.hpp"

namespace dtlab::experiments {

// $VARIABLE when set and not empty, else `fallback`.
std::string from_env_or(const char* variable, const std::string& fallback);
// The source tree (for the commit and tools/): $DTLAB_SOURCE_DIR or the one this was built from.
std::string source_tree();

// Writes `text` to `path`; throws std::runtime_error when it cannot.
void write_text(const std::filesystem::path& path, const std::string& text);

struct SummaryHeader {
  std::string command;   // the Markdown line naming the command(s) that ran the study
  std::string machines;  // "Machine: ..." (or one line per shard's machine)
  int seeds = 1;
};

// Reads DIR/NAME.csv, writes DIR/NAME.md (and prints it), then the plot unless options.plot is
// false. Returns false, with a message on stderr, when the plot fails.
bool write_summary(const Study& study, const std::filesystem::path& dir,
                   const SummaryHeader& header, const ExperimentOptions& options);

}  // namespace dtlab::experiments
