#pragma once
// Exact facts about a point set: duplicates, affine dimension, magnitudes, and the power-of-two
// scaling that brings it into the adaptive kernel's valid range.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "dtlab/predicates/point.hpp"

namespace dtlab::engine {

using predicates::Point3;

struct PointSetInfo {
  std::uint64_t count = 0;
  std::uint64_t distinct = 0;
  std::uint64_t duplicates = 0;  // count - distinct
  Point3 min{0, 0, 0};
  Point3 max{0, 0, 0};
  int dimension = -1;  // affine dimension of the distinct points: -1 (empty), 0, 1, 2 or 3
  double min_abs_nonzero = 0.0;  // smallest nonzero |coordinate| (0 if none)
  double max_abs = 0.0;
  bool adaptive_range_ok = true;  // fits the adaptive kernel after exact power-of-two scaling
};

PointSetInfo analyze(const std::vector<Point3>& points);

// Indices of four affinely independent points, taken in `order`, in the order found; nullopt with
// the dimension reached when none exist. Decided with the exact kernel.
struct SimplexSearch {
  std::optional<std::array<std::uint32_t, 4>> simplex;
  int dimension = -1;
};
SimplexSearch find_simplex(const std::vector<Point3>& points,
                           const std::vector<std::uint32_t>& order);

// The exponent k such that 2^k * max|coordinate| lies in [2^99, 2^100), and whether every
// nonzero coordinate then stays within the adaptive kernel's valid range.
struct RangeScaling {
  int exponent = 0;
  bool fits = true;
};
RangeScaling adaptive_range_scaling(double max_abs, double min_abs_nonzero);

std::string dimension_name(int dimension);

}  // namespace dtlab::engine
