#pragma once
// Error bounds of Shewchuk's adaptive predicates (DCG 18, 1997, Sect. 4 and 6), as constexpr
// values of epsilon = 2^-53, the relative error bound of one rounded IEEE double operation.
// The stage names follow the paper: A (float filter), B (exact on rounded differences),
// C (first-order tail correction); D is exact and needs no bound.

namespace dtlab::predicates::bounds {

inline constexpr double kEpsilon = 1.0 / 9007199254740992.0;  // 2^-53
inline constexpr double kSplitter = 134217729.0;              // 2^27 + 1 (Dekker split)

inline constexpr double kResultErrBound = (3.0 + 8.0 * kEpsilon) * kEpsilon;

inline constexpr double kOrient2dA = (3.0 + 16.0 * kEpsilon) * kEpsilon;

inline constexpr double kOrient3dA = (7.0 + 56.0 * kEpsilon) * kEpsilon;
inline constexpr double kOrient3dB = (3.0 + 28.0 * kEpsilon) * kEpsilon;
inline constexpr double kOrient3dC = (26.0 + 288.0 * kEpsilon) * kEpsilon * kEpsilon;

inline constexpr double kInsphereA = (16.0 + 224.0 * kEpsilon) * kEpsilon;
inline constexpr double kInsphereB = (5.0 + 72.0 * kEpsilon) * kEpsilon;
inline constexpr double kInsphereC = (71.0 + 1408.0 * kEpsilon) * kEpsilon * kEpsilon;

// The lifted in-circle test of four coplanar points (3D lift in a 2D projection) is not in the
// paper. Its float evaluation has at most 12 rounded operations on any monomial's path
// (difference 1, square 1, two lift additions, minor 3, product 1, two sums), so 12*eps plus
// second-order terms bounds the error; 16*eps leaves room for the rounding of the permanent.
inline constexpr double kIncircleLiftedA = 16.0 * kEpsilon;

static_assert(kEpsilon * 2.0 == 1.0 / 4503599627370496.0, "epsilon must be 2^-53");

}  // namespace dtlab::predicates::bounds
