#pragma once
// Error bounds of dtlab's filters, computed from rounding counts (docs/predicates.md, "Error
// bounds"). eps = 2^-53 is the unit roundoff of IEEE double with round to nearest.
//
// Notation: an expression is evaluated in floating point from the rounded coordinate
// differences. k1 = the largest number of rounded operations on the path of any monomial of the
// determinant before the final operation (whose rounding cannot change the sign), kp = the same
// count for the permanent (the expression with every term replaced by its absolute value), the
// difference roundings included in both. Then (Lemma 1 in docs/predicates.md)
//     C >= gamma(k1) (1 + eps) / (1 - eps)^(kp + 1),   gamma(k) = k eps / (1 - k eps),
// makes |det| > C * permanent (evaluated in floating point) a proof of the sign. For k eps <= 2^-40
// the right side is at most (k1 + (2 k1^2 + k1 (kp + 2) + 1) eps) eps. Every constant is computed
// as (lead + second eps) eps times (1 + 2^-45): the one rounded addition and the one rounded
// product lose at most 2 eps, which the factor more than makes up, so no constant is rounded
// below its derivation.
namespace dtlab::predicates::bounds {

inline constexpr double kEpsilon = 0x1p-53;
inline constexpr double kSplitter = 0x1p27 + 1.0;  // Dekker's split of a 53-bit significand

constexpr double rounded_up(double lead, double second) {
  return (lead + second * kEpsilon) * kEpsilon * (1.0 + 0x1p-45);
}

// Lemma 1: a filter that evaluates the determinant in floating point.
constexpr double float_filter(int k1, int kp) {
  return rounded_up(k1, 2.0 * k1 * k1 + k1 * (kp + 2.0) + 1.0);
}

// Lemma 2: the determinant of the rounded differences, evaluated exactly, approximated by the
// largest component of its compressed expansion (relative error at most 2 eps), against the true
// determinant.
// `degree` factors per monomial, each one rounded difference away from the truth:
//     B >= gamma(degree) (1 + 2 eps) / (1 - eps)^(kp + 1).
constexpr double exact_on_rounded(int degree, int kp) {
  return rounded_up(degree, 2.0 * degree * degree + 2.0 * degree + degree * (kp + 1.0) + 1.0);
}

// Rounding counts of dtlab's evaluation orders (detail/float_determinants.hpp; each count is
// derived in docs/predicates.md, "Operation counts").
inline constexpr double kOrient3dA = float_filter(7, 8);
inline constexpr double kInsphereA = float_filter(15, 16);
inline constexpr double kOrient2dA = float_filter(3, 4);
inline constexpr double kIncircleLiftedA = float_filter(11, 12);
inline constexpr double kCentroidA = float_filter(10, 11);

inline constexpr double kOrient3dB = exact_on_rounded(3, 8);
inline constexpr double kInsphereB = exact_on_rounded(5, 16);

// Stage C (Lemma 3): |true - corrected| <= c2 eps^2 permanent + c1 eps |corrected|. c2 counts the
// second-order tail terms, the float error of the first-order correction and the error of using
// rounded minors inside it; c1 the estimate of stage B (2 eps) and the final addition (eps).
inline constexpr double kOrient3dC = (40.0 + 512.0 * kEpsilon) * kEpsilon * kEpsilon;
inline constexpr double kInsphereC = (192.0 + 4096.0 * kEpsilon) * kEpsilon * kEpsilon;
inline constexpr double kCorrectedRelative = (3.0 + 16.0 * kEpsilon) * kEpsilon;

// Stage B's fast path (Lemma 7): the double-word value D of the rounded determinant X satisfies
// |D - X| <= 73 eps^2 * permanent (9 roundings of at most 8 eps^2 (1 + 4 eps) each, and stage A's
// permanent low by at most (1 - eps)^16); 80 eps^2 is exact in binary. Stage B's own test is then
// run against kInsphereB (1 + 2^-39), whose surplus over kInsphereB covers that error (the
// static_assert) and the roundings of the test. Stage C starts from D instead of X, so its constant
// grows by the same 80 eps^2.
inline constexpr double kInsphereDoubleWord = 80.0 * kEpsilon * kEpsilon;
inline constexpr double kInsphereBDoubleWord = kInsphereB * (1.0 + 0x1p-39);
static_assert(kInsphereB * 0x1p-41 > kInsphereDoubleWord);
inline constexpr double kInsphereCDoubleWord = (272.0 + 4096.0 * kEpsilon) * kEpsilon * kEpsilon;
static_assert(kInsphereCDoubleWord >= kInsphereC + kInsphereDoubleWord);

// Underflow (Lemma 4): a product whose exact value lies below 2^-1022 is off by up to 2^-1075
// absolutely; additions and subtractions of doubles are exact there. The unit used is 2^-960,
// far more than the 2^-1075 per unit of cofactor the lemma needs, because it must be a normal
// number: arithmetic on subnormals takes a microcode assist (about 100 cycles on x86) and stage A
// runs on every call. The only cost is that a determinant below about 2^-950 is left to the
// exact stages.
inline constexpr double kUnderflowUnit = 0x1p-960;

// Semi-static filters (FilteredKernel, Lemma 5): every monomial is at most the product M of the
// per-axis maxima of the rounded differences, so with N monomials the permanent of the exact
// differences is at most N M / (1 - eps)^degree, and M evaluated in floating point (degree - 1
// products) is low by at most (1 - eps)^(degree - 1): Lemma 1 with kp = 2 degree - 1, times N.
constexpr double semi_static(int monomials, int k1, int degree) {
  const double k = k1;
  const double kp = 2.0 * degree - 1.0;
  return rounded_up(monomials * k, monomials * (2.0 * k * k + k * (kp + 2.0) + 1.0));
}
inline constexpr double kStaticOrient3d = semi_static(6, 7, 3);
inline constexpr double kStaticInsphere = semi_static(72, 15, 5);
inline constexpr double kStaticOrient2d = semi_static(2, 3, 2);
inline constexpr double kStaticIncircleLifted = semi_static(18, 11, 4);
inline constexpr double kStaticCentroid = semi_static(24, 10, 3);

static_assert(kEpsilon * 2.0 == 0x1p-52, "epsilon must be 2^-53");
static_assert(kOrient3dA > 7.0 * kEpsilon && kOrient3dA < 7.001 * kEpsilon);

}  // namespace dtlab::predicates::bounds
