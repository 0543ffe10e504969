#pragma once
// INPUT arguments: a point file or a generator spec such as uniform:100000.
#include <cstdint>
#include <string>
#include <vector>

#include "dtlab/predicates/point.hpp"

namespace dtlab::cli {

std::vector<predicates::Point3> load_input(const std::string& input, std::uint64_t seed);

}  // namespace dtlab::cli
