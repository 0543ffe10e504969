#pragma once
// The columns of every study's CSV and the key that names a run in it.
#include <string>
#include <vector>

#include "study.hpp"

namespace dtlab::experiments {

// The run's own columns (key, study, input, status, ...), the options the engine's JSON does not
// carry (options.*), every key of the engine's stats JSON flattened, the validator's report
// (validation.*) and the predicate audit (audit.*), in this order.
const std::vector<std::string>& run_columns();

// The index of `column` in run_columns(); throws std::out_of_range for an unknown one.
std::size_t run_column(const std::string& column);

// Identifies a run within its study (the resume key).
std::string run_key(const RunSpec& spec);

}  // namespace dtlab::experiments
