#include "run_executor.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "child_run.hpp"
#include "peers/peer_tools.hpp"
#include "process_status.hpp"
#include "run_columns.hpp"

namespace dtlab::experiments {
namespace {

// The child's message: key, kSeparator, value, kSeparator, ..., then kEnd. A message without kEnd
// was cut (the child died while writing).
constexpr char kSeparator = '\x1f';
constexpr char kEnd = '\x1e';

std::string encode(const Cells& cells) {
  std::string out;
  for (const auto& [key, value] : cells) {
    out += key;
    out += kSeparator;
    out += value;
    out += kSeparator;
  }
  out += kEnd;
  return out;
}

// False when the message is cut.
bool decode(const std::string& text, Cells& cells) {
  if (text.empty() || text.back() != kEnd) return false;
  std::size_t pos = 0;
  const std::size_t end = text.size() - 1;
  while (pos < end) {
    const std::size_t key_end = text.find(kSeparator, pos);
    const std::size_t value_end =
        key_end == std::string::npos ? std::string::npos : text.find(kSeparator, key_end + 1);
    if (value_end == std::string::npos || value_end >= end) return false;
    cells[text.substr(pos, key_end - pos)] = text.substr(key_end + 1, value_end - key_end - 1);
    pos = value_end + 1;
  }
  return true;
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

// A run that ends without a result: its status, outcome (the peers study's classes) and reason.
Cells failure(const char* status, const char* outcome, const std::string& error) {
  return {{"status", status}, {"outcome", outcome}, {"error", error}};
}

[[noreturn]] void child(int fd, const RunSpec& spec, std::vector<predicates::Point3>& points,
                        const std::string& scratch_dir) {
  // A study interrupted by killing the parent alone must not leave its run behind.
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  Cells cells;
  try {
    cells = measure_run(spec, points, scratch_dir);
    cells["status"] = "ok";
  } catch (const PeerCrashed& e) {
    cells = failure("crashed", "crashed", e.what());
  } catch (const std::bad_alloc&) {
    cells = failure("crashed", "crashed", "out of memory (std::bad_alloc)");
  } catch (const PeerInvalidOutput& e) {
    cells = failure("error", "invalid", e.what());
  } catch (const std::exception& e) {  // the engine's or a peer's refusal, with its message
    cells = failure("error", "refused", e.what());
  }
  _exit(write_all(fd, encode(cells)) ? 0 : 1);
}

// Reads the child's message until it closes the pipe or `timeout_seconds` (0: none) pass; false
// on the timeout.
bool read_until(int fd, double timeout_seconds, std::string& text) {
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_seconds);
  char buffer[4096];
  for (;;) {
    int wait_ms = -1;
    if (timeout_seconds > 0) {
      const double left =
          std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
      if (left <= 0) return false;
      wait_ms = static_cast<int>(left * 1000.0) + 1;
    }
    pollfd watched{fd, POLLIN, 0};
    const int ready = poll(&watched, 1, wait_ms);
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) continue;  // the deadline is checked above
    const ssize_t n = read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return true;
    text.append(buffer, static_cast<std::size_t>(n));
  }
}

// The child's verdict: its cells, status "crashed" with the reason, or "timeout".
Cells collect(pid_t pid, int fd, double timeout_seconds) {
  std::string text;
  const bool finished = read_until(fd, timeout_seconds, text);
  close(fd);
  // The child leads its own process group: a tool's processes end with it.
  if (!finished) kill(-pid, SIGKILL);
  const int status = wait_for(pid);
  Cells cells;
  if (!finished) {
    return failure(
        "timeout", "hung",
        "no result within the timeout (" + nlohmann::json(timeout_seconds).dump() + " s): killed");
  }
  if (WIFSIGNALED(status)) {
    return failure("crashed", "crashed",
                   "the run ended by signal " + signal_name(WTERMSIG(status)));
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !decode(text, cells)) {
    return failure("crashed", "crashed", "the run's result did not arrive whole");
  }
  for (const auto& [key, value] : cells) {
    if (key != "status") run_column(key);  // throws for a cell no column holds
  }
  return cells;
}

// A run's folder for a tool's files, removed however the run ended (a killed child cannot).
class ScratchDir {
 public:
  explicit ScratchDir(bool wanted) {
    if (!wanted) return;
    std::string pattern = (std::filesystem::temp_directory_path() / "dtlab-run-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~ScratchDir() {
    std::error_code ignored;
    if (!path_.empty()) std::filesystem::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  std::string path_;
};

void add_run_cells(const std::string& study, const RunSpec& spec, unsigned hardware_threads,
                   Cells& cells) {
  const engine::TriangulateOptions& o = spec.options;
  cells["run_key"] = run_key(spec);
  cells["study"] = study;
  cells["input"] = spec.input;
  cells["source"] = spec.source;
  cells["size_asked"] = std::to_string(spec.size);
  cells["variant"] = spec.variant;
  cells["engine"] = to_string(spec.engine);
  cells["round"] = std::to_string(spec.round);
  cells["hardware_threads"] = std::to_string(hardware_threads);
  cells["oversubscribed"] = o.threads > static_cast<int>(hardware_threads) ? "true" : "false";
  // Options the engine's JSON does not give (a failed run, CGAL): from the spec.
  const auto fill = [&](const char* key, const std::string& value) {
    if (cells[key].empty()) cells[key] = value;
  };
  fill("threads", std::to_string(o.threads));
  fill("seed", std::to_string(o.seed));
  cells["options.timeout_seconds"] = nlohmann::json(spec.timeout_seconds).dump();
  if (spec.engine == Engine::Peer) {
    fill("method", spec.variant);
    return;
  }
  if (spec.engine != Engine::Dtlab) {
    fill("method", to_string(spec.engine));
    return;
  }
  fill("method", engine::to_string(o.method));
  fill("predicates", engine::to_string(o.kernel));
  fill("location", engine::to_string(o.location));
  fill("insertion", engine::to_string(o.insertion));
  fill("bounding", engine::to_string(o.bounding));
  fill("repair", engine::to_string(o.repair));
  fill("distribution", engine::to_string(engine::effective_distribution(o)));
  cells["options.max_flips_per_insertion"] = std::to_string(o.max_flips_per_insertion);
  cells["options.max_location_steps"] = std::to_string(o.max_location_steps);
  cells["options.watchdog_seconds"] = nlohmann::json(o.watchdog_seconds).dump();
  cells["options.max_tetrahedra"] = std::to_string(o.max_tetrahedra);
  cells["options.stress"] = o.stress ? "true" : "false";
  cells["options.validate"] = spec.validate ? "true" : "false";
  cells["options.audit"] = spec.audit ? "true" : "false";
}

}  // namespace

std::vector<std::string> execute_isolated(const std::string& study, const RunSpec& spec,
                                          std::vector<predicates::Point3>& points,
                                          unsigned hardware_threads) {
  const auto start = std::chrono::steady_clock::now();
  ScratchDir scratch(spec.engine == Engine::Peer);
  std::fflush(nullptr);  // nothing buffered is written twice
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error("pipe failed");
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    throw std::runtime_error("fork failed");
  }
  if (pid == 0) {
    setpgid(0, 0);
    close(fds[0]);
    child(fds[1], spec, points, scratch.path());
  }
  setpgid(pid, pid);  // also here: the group exists before the parent may kill it
  close(fds[1]);
  Cells cells = collect(pid, fds[0], spec.timeout_seconds);
  cells["seconds_wall"] =
      nlohmann::json(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count())
          .dump();
  add_run_cells(study, spec, hardware_threads, cells);
  std::vector<std::string> row;
  for (const std::string& column : run_columns()) {
    const auto it = cells.find(column);
    row.push_back(it == cells.end() ? std::string() : it->second);
  }
  return row;
}

}  // namespace dtlab::experiments
