#pragma once
// Deterministic point set generators (same bytes for the same family, N and seed on every run).
// The paper's distributions in the unit cube plus degenerate families for robustness work; see
// docs/generators.md for each family's definition.
#include <cstdint>
#include <string>
#include <vector>

#include "dtlab/predicates/point.hpp"

namespace dtlab::generators {

using predicates::Point3;

struct GeneratedPoints {
  std::vector<Point3> points;
  std::string note;  // set when the family could not produce exactly N points
};

inline constexpr std::int64_t kMaxPoints = 200'000'000;

// Throws std::invalid_argument for an unknown family or N outside [1, kMaxPoints].
GeneratedPoints generate(const std::string& family, std::int64_t n, std::uint64_t seed);

const std::vector<std::string>& families();

// "family:N" (e.g. "uniform:100000"): true and the parts if `spec` has that form and names a
// known family; throws std::invalid_argument for a malformed N or an unknown family.
bool parse_spec(const std::string& spec, std::string& family, std::int64_t& n);

}  // namespace dtlab::generators
