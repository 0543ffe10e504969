#pragma once
// DIR/machine.json: what the figures were measured on (CPU model, cores, memory, compiler and
// flags, commit, date), so that a table is never read without its machine.
#include <string>

namespace dtlab::experiments {

// The record as JSON text. `source_dir` is asked for the commit (git), when it is a checkout.
std::string machine_json(const std::string& source_dir, const std::string& command_line);

// One line for the top of a summary: "CPU, N hardware threads, M GiB, commit abc1234".
std::string machine_line(const std::string& source_dir);

}  // namespace dtlab::experiments
