#include "machine_record.hpp"

#include <sys/utsname.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>
#include <utility>

#include "dtlab/engine/methods.hpp"

namespace dtlab::experiments {
namespace {

// The first line of /proc/cpuinfo (or /proc/meminfo) that starts with `key`, after its colon.
std::string proc_field(const char* file, const std::string& key) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(key, 0) == 0) {
      const std::size_t colon = line.find(':');
      if (colon == std::string::npos) continue;
      std::size_t start = line.find_first_not_of(" \t", colon + 1);
      return start == std::string::npos ? std::string() : line.substr(start);
    }
  }
  return "";
}

}  // namespace

std::string command_output(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return "";
  std::array<char, 256> buffer{};
  std::string out;
  while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) out += buffer.data();
  pclose(pipe);
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  const std::size_t newline = out.find('\n');
  return newline == std::string::npos ? out : out.substr(0, newline);
}

namespace {

// Distinct (physical id, core id) pairs of /proc/cpuinfo; the logical CPUs when it has none.
unsigned physical_cores() {
  std::ifstream in("/proc/cpuinfo");
  std::set<std::pair<std::string, std::string>> cores;
  std::string line;
  std::string package;
  while (std::getline(in, line)) {
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    const std::string value = colon + 2 <= line.size() ? line.substr(colon + 2) : "";
    if (line.rfind("physical id", 0) == 0) package = value;
    if (line.rfind("core id", 0) == 0) cores.emplace(package, value);
  }
  return cores.empty() ? std::thread::hardware_concurrency() : static_cast<unsigned>(cores.size());
}

double memory_gib() {
  const std::string kib = proc_field("/proc/meminfo", "MemTotal");
  return kib.empty() ? 0.0 : std::stod(kib) / (1024.0 * 1024.0);
}

}  // namespace

std::string git_commit(const std::string& source_dir) {
  if (source_dir.find('\'') != std::string::npos) return "unknown";  // no quoting games
  const std::string git = "git -C '" + source_dir + "' ";
  std::string hash = command_output(git + "rev-parse HEAD 2>/dev/null");
  if (hash.empty()) return "unknown";
  if (!command_output(git + "status --porcelain --untracked-files=no 2>/dev/null").empty()) {
    hash += "+uncommitted";
  }
  return hash;
}

std::string utc_now() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

std::string machine_json(const std::string& source_dir, const std::string& command_line) {
  nlohmann::ordered_json j;
  j["cpu_model"] = proc_field("/proc/cpuinfo", "model name");
  j["hardware_threads"] = std::thread::hardware_concurrency();  // logical CPUs online
  j["cpus_available"] = available_cpus();  // this process's affinity: the oversubscription line
  j["physical_cores"] = physical_cores();
  j["memory_gib"] = memory_gib();
  utsname uts{};
  if (uname(&uts) == 0) j["os"] = std::string(uts.sysname) + " " + uts.release + " " + uts.machine;
  j["compiler"] = std::string(DTLAB_COMPILER_ID) + " " + __VERSION__;
  j["build_type"] = DTLAB_BUILD_TYPE;
  j["cxx_flags"] = DTLAB_CXX_FLAGS;
  j["predicates_flags"] = DTLAB_PREDICATES_FLAGS;  // and -ffp-contract=off wherever they are used
  j["cgal_flags"] = DTLAB_CGAL_FLAGS;
  j["commit"] = git_commit(source_dir);
  j["date_utc"] = utc_now();
  j["command"] = command_line;
  return j.dump(2);
}

std::string short_commit(const std::string& commit) {
  const std::size_t mark = commit.find('+');
  return commit.substr(0, std::min<std::size_t>(12, mark)) +
         (mark == std::string::npos ? std::string() : commit.substr(mark));
}

unsigned available_cpus() {
  return static_cast<unsigned>(engine::cpus_available());
}

std::string machine_line() {
  char text[512];
  std::snprintf(text, sizeof text, "%s, %u CPUs available (%u cores), %.0f GiB, %s %s, %s",
                proc_field("/proc/cpuinfo", "model name").c_str(), available_cpus(),
                physical_cores(), memory_gib(), DTLAB_COMPILER_ID, __VERSION__, DTLAB_BUILD_TYPE);
  return text;
}

std::string machine_line(const nlohmann::json& record) {
  const auto text = [&](const char* key) {
    const auto it = record.find(key);
    if (it == record.end()) return std::string("?");
    return it->is_string() ? it->get<std::string>() : it->dump();
  };
  char memory[32];
  std::snprintf(memory, sizeof memory, "%.0f",
                record.value("memory_gib", nlohmann::json(0.0)).get<double>());
  return text("cpu_model") + ", " + text("cpus_available") + " CPUs available (" +
         text("physical_cores") + " cores), " + memory + " GiB, " + text("compiler") + ", " +
         text("build_type");
}

}  // namespace dtlab::experiments
