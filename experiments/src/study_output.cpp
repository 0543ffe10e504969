#include "study_output.hpp"

#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>
#include <stdexcept>
#include <vector>

#include "machine_record.hpp"
#include "process_status.hpp"
#include "summary.hpp"

extern char** environ;

namespace dtlab::experiments {
namespace {

namespace fs = std::filesystem;

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
  const int status = wait_for(pid);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
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

std::string from_env_or(const char* variable, const std::string& fallback) {
  const char* value = std::getenv(variable);
  return value != nullptr && *value != '\0' ? value : fallback;
}

std::string source_tree() {
  return from_env_or("DTLAB_SOURCE_DIR", DTLAB_SOURCE_DIR);
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

bool write_summary(const Study& study, const fs::path& dir, const SummaryHeader& header,
                   const ExperimentOptions& options) {
  const std::string name = study.name;
  const CsvTable table = read_csv((dir / (name + ".csv")).string());
  std::string md = "## " + name + ": " + study.summary + "\n\n";
  md += header.command + "  \n";
  md += header.machines + " Runs measured at " + row_commits(table) +
        ". Seeds (rounds): " + std::to_string(header.seeds) + ". " +
        std::to_string(table.rows.size()) + " runs.\n\n";
  md += study.summarize(table);
  md += failed_runs(table);
  write_text(dir / (name + ".md"), md);
  std::printf("%s", md.c_str());
  std::fflush(stdout);
  if (!options.plot) return true;
  const std::string tools =
      !options.tools_dir.empty()
          ? options.tools_dir
          : from_env_or("DTLAB_TOOLS_DIR", std::string(DTLAB_SOURCE_DIR) + "/tools");
  if (!plot(tools, name, dir)) {
    std::fprintf(stderr,
                 "dtlab: error: the plot failed (python3 with matplotlib: scripts/setup.sh); "
                 "the CSV and the table are written\n");
    return false;
  }
  return true;
}

}  // namespace dtlab::experiments
