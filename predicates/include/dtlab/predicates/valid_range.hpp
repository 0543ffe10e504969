#pragma once
// The coordinate range on which expansion arithmetic (the exact stages B, C, D of the adaptive
// kernel and stage D of the filtered kernel) is exact (derivation in docs/predicates.md, Lemma 6).
// If every coordinate of a call is 0 or has magnitude in [2^-120, 2^120]:
//  * every such double is a multiple of 2^-172, so every exact intermediate of the degree-5
//    insphere polynomial of the differences (and of their tails), and every expansion component,
//    is a multiple of 2^-860, far above the smallest subnormal granularity 2^-1074: no product
//    loses bits to underflow;
//  * differences stay below 2^121 and degree-5 terms below 2^612, far below 2^1023 and the
//    Veltkamp-split limit 2^996: nothing overflows.
// A call with a coordinate outside this range that stage A (or the semi-static filter) cannot
// decide goes to the GMP evaluation instead (stage Gmp): adaptive and filtered decide every finite
// double. The engine scales its input by a power of two so that max |c| lies in [2^99, 2^100)
// when that is lossless, which puts ordinary inputs entirely inside the range.
#include <cmath>

#include "dtlab/predicates/point.hpp"

namespace dtlab::predicates {

inline constexpr int kRangeMinExponent = -120;
inline constexpr int kRangeMaxExponent = 120;
// The exponent the engine scales the largest coordinate magnitude to: max |c| in [2^99, 2^100).
// Leaves room above for the auxiliary tetrahedron (200 x box) and below for fine detail.
inline constexpr int kScaledMaxExponent = 100;

inline bool in_valid_range(double c) {
  const double m = std::fabs(c);
  return c == 0.0 || (m >= 0x1p-120 && m <= 0x1p120);
}

inline bool in_valid_range(const Point3& p) {
  return in_valid_range(p.x) && in_valid_range(p.y) && in_valid_range(p.z);
}

// Every point of a call within the range.
template <class... P>
bool in_expansion_range(const P&... points) {
  return (in_valid_range(points) && ...);
}

}  // namespace dtlab::predicates
