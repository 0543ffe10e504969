#pragma once
// Runs one RunSpec in a forked child and returns its row: every option and every stat of the run
// (the engine's stats JSON, flattened), the validator's verdict and the predicate audit, in the
// fixed columns of run_columns(). The child has its own peak memory, audit counters and crashes.
#include <string>
#include <vector>

#include "dtlab/predicates/point.hpp"
#include "study.hpp"

namespace dtlab::experiments {

// Every study's CSV has these columns, in this order.
const std::vector<std::string>& run_columns();

// Identifies a run within its study (the resume key).
std::string run_key(const RunSpec& spec);

std::vector<std::string> execute_isolated(const std::string& study, const RunSpec& spec,
                                          const std::vector<predicates::Point3>& points,
                                          unsigned hardware_threads);

}  // namespace dtlab::experiments
