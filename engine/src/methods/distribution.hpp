#pragma once
// How the points of a parallel run are split among its threads (paper Sect. 6).
#include <cstdint>
#include <vector>

#include "dtlab/engine/options.hpp"
#include "dtlab/predicates/point.hpp"

namespace dtlab::engine {

// The points of `order` split among `threads` per the distribution (static, strips, blocks;
// dynamic is handled by the caller with a shared index, and auto resolved by
// effective_distribution). Each part keeps the random order.
std::vector<std::vector<std::uint32_t>> distribute(const std::vector<predicates::Point3>& points,
                                                   const std::vector<std::uint32_t>& order,
                                                   Distribution distribution, int threads);

}  // namespace dtlab::engine
