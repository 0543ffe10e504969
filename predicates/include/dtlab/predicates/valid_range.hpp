#pragma once
// The input range on which the adaptive kernel is exact (derivation in docs/predicates.md).
// Expansion arithmetic is exact only while no intermediate value overflows or underflows. If
// every coordinate is 0 or has magnitude in [2^-120, 2^120]:
//  * every double of magnitude >= 2^-120 is a multiple of 2^-172, so every exact intermediate of
//    the degree-5 insphere polynomial (and every expansion component) is a multiple of 2^-860,
//    far above the smallest normal double 2^-1022: nothing underflows, the error bounds' own
//    products included;
//  * coordinate differences stay below 2^121 and degree-5 terms below 2^612, far below 2^1023
//    and the Dekker-split limit 2^996: nothing overflows.
// The engine maps any input into this range with an exact power-of-two scaling (which changes no
// predicate sign) and refuses the input when its dynamic range does not fit.
#include <cmath>

#include "dtlab/predicates/point.hpp"

namespace dtlab::predicates {

inline constexpr int kRangeMinExponent = -120;
inline constexpr int kRangeMaxExponent = 120;
// The exponent the engine scales the largest coordinate magnitude to: max |c| in [2^99, 2^100).
// Leaves room above for the auxiliary tetrahedron (200 x box) and below for fine detail.
inline constexpr int kScaledMaxExponent = 100;

inline bool in_valid_range(double c) {
  if (c == 0.0) return true;
  const double m = std::fabs(c);
  return m >= std::ldexp(1.0, kRangeMinExponent) && m <= std::ldexp(1.0, kRangeMaxExponent);
}

inline bool in_valid_range(const Point3& p) {
  return in_valid_range(p.x) && in_valid_range(p.y) && in_valid_range(p.z);
}

}  // namespace dtlab::predicates
