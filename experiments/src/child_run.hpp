#pragma once
// What a run measures, in the forked child: the engine's (or CGAL's) stats, the validator's
// report and the predicate audit, as cells named by run_columns().
#include <map>
#include <string>
#include <vector>

#include "dtlab/predicates/point.hpp"
#include "study.hpp"

namespace dtlab::experiments {

using Cells = std::map<std::string, std::string>;

// Throws what the engine throws (TriangulationError, ...): the caller records it.
Cells measure_run(const RunSpec& spec, std::vector<predicates::Point3>& points);

}  // namespace dtlab::experiments
