#pragma once
// DIR/machine.json: what the figures were measured on (CPU model, cores, memory, compiler and
// flags, commit, date), so that a table is never read without its machine.
#include <nlohmann/json.hpp>
#include <string>

namespace dtlab::experiments {

// The record as JSON text. `source_dir` is asked for the commit (git), when it is a checkout.
std::string machine_json(const std::string& source_dir, const std::string& command_line);

// The first line a shell command writes to its standard output, or empty.
std::string command_output(const std::string& command);

// The checkout's commit (with "+uncommitted" when tracked files differ from it), or "unknown".
std::string git_commit(const std::string& source_dir);
// The time now, as 2026-11-22T20:15:00Z.
std::string utc_now();

// The first 12 digits of a commit, with its "+uncommitted" mark.
std::string short_commit(const std::string& commit);

// The CPUs this process may run on (its affinity mask, which taskset and cgroups narrow): the
// count above which a thread count is oversubscribed.
unsigned available_cpus();

// One line for the top of a summary: "CPU, N CPUs available (C cores), M GiB, compiler, build".
std::string machine_line();
// The same line from a machine.json record (a shard's, for a merged summary).
std::string machine_line(const nlohmann::json& record);

}  // namespace dtlab::experiments
