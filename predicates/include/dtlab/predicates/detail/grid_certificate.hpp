#pragma once
// The grid certificate of stage B (docs/predicates.md, Lemmas 7 and 8): when every coordinate
// difference of a call is exact and a multiple of 2^g, its determinant, an integer polynomial of
// degree k in them, is a multiple of 2^(k g); an approximation closer to 0 than half of that,
// with a proven error, proves the determinant 0.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

namespace dtlab::predicates::detail {

// One row of coordinate differences p - e.
struct RoundedRow {
  double x, y, z;
};

// The exponent of the lowest set bit of a finite nonzero double: x is a multiple of 2^result.
// The hidden bit is set even for a subnormal: its stored significand is nonzero, so the bit above
// it does not change where its lowest set bit is; a subnormal's exponent is that of biased 1.
// Without branches, so that the compiler does not split normal from subnormal numbers.
inline int lowest_bit_exponent(double x) {
  const auto bits = std::bit_cast<std::uint64_t>(x);
  const auto biased = static_cast<int>((bits >> 52) & 0x7ffU);
  const std::uint64_t significand = bits | (std::uint64_t{1} << 52);
  return std::max(biased, 1) - 1075 + std::countr_zero(significand);
}

// The largest g such that every coordinate of every row is a multiple of 2^g (a determinant that
// is an integer polynomial of degree k in them is then a multiple of 2^(k g)); `kAllZero` when
// every coordinate is 0. Without branches: on grids, which coordinates are 0 is unpredictable.
inline constexpr int kAllZero = 1 << 20;
inline int lowest_bit_or_all_zero(double c) {
  const int zero = -static_cast<int>((std::bit_cast<std::uint64_t>(c) << 1) == 0);  // +-0.0
  return (lowest_bit_exponent(c) & ~zero) | (kAllZero & zero);
}
template <std::size_t N>
int common_power_of_two(const std::array<RoundedRow, N>& r) {
  int g = kAllZero;
  for (const RoundedRow& row : r) {
    g = std::min({g, lowest_bit_or_all_zero(row.x), lowest_bit_or_all_zero(row.y),
                  lowest_bit_or_all_zero(row.z)});
  }
  return g;
}

// 2^k, as std::ldexp(1.0, k) gives it: from its bits where it is a normal double (ldexp, a library
// call, was about 1 % of a grid run's samples), else from ldexp (subnormal or 0 below, infinity
// above).
inline double power_of_two(int k) {
  if (k >= -1022 && k <= 1023) {
    return std::bit_cast<double>(static_cast<std::uint64_t>(k + 1023) << 52);
  }
  return std::ldexp(1.0, k);
}

// Stage A's value proves an exact determinant of degree `degree` on the grid 2^g to be 0 (Lemma
// 8): |exact| <= |det| / (1 - eps) + bound (Lemma 1's proof, with Lemma 4's underflow term in
// `bound`) < 2 (|det| + bound) < 2^(degree g).
inline bool stage_a_proves_zero(double det, double bound, int g, int degree) {
  if (g == kAllZero) return true;
  return 2.0 * (std::fabs(det) + bound) < power_of_two(degree * g);
}

}  // namespace dtlab::predicates::detail
