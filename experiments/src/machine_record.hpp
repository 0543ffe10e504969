#pragma once
// DIR/machine.json: what the figures were measured on (CPU model, cores, memory, compiler and
// flags, commit, date), so that a table is never read without its machine.
#include <string>

namespace dtlab::experiments {

// The record as JSON text. `source_dir` is asked for the commit (git), when it is a checkout.
std::string machine_json(const std::string& source_dir, const std::string& command_line);

// The checkout's commit (with "+uncommitted" when tracked files differ from it), or "unknown".
std::string git_commit(const std::string& source_dir);
// The time now, as 2026-11-22T20:15:00Z.
std::string utc_now();

// One line for the top of a summary: "CPU, N hardware threads, M GiB, commit abc1234".
std::string machine_line(const std::string& source_dir);

}  // namespace dtlab::experiments
