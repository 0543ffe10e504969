#pragma once
// What a run measures, in the forked child: the engine's (or CGAL's) stats, the validator's
// report and the predicate audit, as cells named by run_columns().
#include <map>
#include <string>
#include <vector>

#include "dtlab/engine/validator.hpp"
#include "dtlab/predicates/point.hpp"
#include "study.hpp"

namespace dtlab::experiments {

using Cells = std::map<std::string, std::string>;

// Throws what the engine throws (TriangulationError, ...) and what a peer throws (PeerRefused,
// PeerCrashed, PeerInvalidOutput): the caller records it. `scratch_dir`: an empty folder for a
// peer's files (the caller removes it).
Cells measure_run(const RunSpec& spec, std::vector<predicates::Point3>& points,
                  const std::string& scratch_dir);

// What a validated result is: "valid" or "invalid" (the outcome column).
std::string outcome_of(const engine::ValidationReport& report);

}  // namespace dtlab::experiments
