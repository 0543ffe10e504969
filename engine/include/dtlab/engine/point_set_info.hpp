#pragma once
// Exact facts about a point set: duplicates, affine dimension, magnitudes, and the power-of-two
// scaling the engine applies (and whether the scaled coordinates lie in the range where the
// expansion arithmetic of the adaptive and filtered kernels is exact).
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "dtlab/predicates/point.hpp"

namespace dtlab::engine {

using predicates::Point3;

struct PointSetInfo {
  Point3 min{0, 0, 0};  // the bounding box
  Point3 max{0, 0, 0};
  std::uint64_t count = 0;
  std::uint64_t distinct = 0;
  std::uint64_t duplicates = 0;  // count - distinct
  int dimension = -1;  // affine dimension of the distinct points: -1 (empty), 0, 1, 2 or 3
  double min_abs_nonzero = 0.0;  // smallest nonzero |coordinate| (0 if none)
  double max_abs = 0.0;
  // After the engine's scaling every nonzero coordinate lies in the expansion range
  // (valid_range.hpp): no adaptive or filtered call needs the GMP fallback. Informational: every
  // finite input is triangulated exactly either way.
  bool within_expansion_range = true;
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

// The coordinates' largest magnitude and smallest nonzero one (0 where every coordinate is 0),
// and whether all are finite: what the engine, the validator and the repair scale by.
struct CoordinateMagnitudes {
  double max_abs = 0.0;
  double min_abs_nonzero = 0.0;
  bool finite = true;
};
CoordinateMagnitudes coordinate_magnitudes(const std::vector<Point3>& points);

// The power-of-two scaling of the engine and the validator.
struct RangeScaling {
  int exponent = 0;  // 2^exponent * max|coordinate| lies in [2^99, 2^100)
  // Scaling by 2^exponent is exact: no nonzero coordinate becomes subnormal or zero (the scaled
  // smallest nonzero magnitude stays >= 2^-1022). Only then may it be applied.
  bool lossless = true;
  // After the scaling (applied only when lossless) every nonzero coordinate has magnitude in
  // [2^kRangeMinExponent, 2^kRangeMaxExponent] (valid_range.hpp): no predicate call of the
  // adaptive or filtered kernel needs the GMP fallback.
  bool within_expansion_range = true;
};
RangeScaling adaptive_range_scaling(double max_abs, double min_abs_nonzero);

std::string dimension_name(int dimension);

}  // namespace dtlab::engine
