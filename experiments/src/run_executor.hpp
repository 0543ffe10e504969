#pragma once
// Runs one RunSpec in a forked child and returns its row, in the columns of run_columns(): the
// child measures (child_run.hpp) and sends its cells through a pipe; the parent adds the run's
// own columns. The child has its own audit counters and peak memory (its RSS starts with the
// parent's pages: the points), and a crash or a throw in it is a row, not the end of the study.
// The child moves `points` into the engine (its own copy-on-write image of them, which the
// engine scales and reorders in place); the parent's points never change.
#include <string>
#include <vector>

#include "dtlab/predicates/point.hpp"
#include "study.hpp"

namespace dtlab::experiments {

std::vector<std::string> execute_isolated(const std::string& study, const RunSpec& spec,
                                          std::vector<predicates::Point3>& points,
                                          unsigned hardware_threads);

}  // namespace dtlab::experiments
