#pragma once
// The fast path of the adaptive insphere's stage B (docs/predicates.md, Lemma 7): the determinant
// of the rounded differences in double-word arithmetic, in stage A's grouping, within
// bounds::kInsphereDoubleWord * permanent of its exact value; and the grid certificate that proves
// that value 0. Inline and header-only so that the tests can hold the bound against GMP.
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>

#include "dtlab/predicates/double_word.hpp"

namespace dtlab::predicates::detail {

// One rounded row p - e (its squared length is formed here).
struct RoundedRow {
  double x, y, z;
};

// dtlab's insphere sign of the four rows, as a double word:
//   (m02 n13 + m13 n02) - ((m01 n23 + m23 n01) + (m03 n12 + m12 n03)),
// m_ij = x_i y_j - x_j y_i, n_kl = z_k L_l - z_l L_k, L = x^2 + y^2 + z^2. The rounding count of
// every monomial is at most 9 (m 1, L 2, L z 3, n 4, m n 6, pair 7, sum of pairs 8, result 9).
inline double_word::DoubleWord insphere_rounded_double_word(const std::array<RoundedRow, 4>& r) {
  using double_word::DoubleWord;
  using double_word::exact_product;
  std::array<DoubleWord, 4> lift{};
  for (std::size_t i = 0; i < 4; ++i) {
    lift[i] = (exact_product(r[i].x, r[i].x) + exact_product(r[i].y, r[i].y)) +
              exact_product(r[i].z, r[i].z);
  }
  auto m = [&](std::size_t i, std::size_t j) {
    return exact_product(r[i].x, r[j].y) - exact_product(r[j].x, r[i].y);
  };
  auto n = [&](std::size_t k, std::size_t l) { return lift[l] * r[k].z - lift[k] * r[l].z; };
  auto pair = [&](std::size_t i, std::size_t j, std::size_t k, std::size_t l) {
    return m(i, j) * n(k, l) + m(k, l) * n(i, j);
  };
  return pair(0, 2, 1, 3) - (pair(0, 1, 2, 3) + pair(0, 3, 1, 2));
}

// The exponent of the lowest set bit of a finite nonzero double: x is a multiple of 2^result.
inline int lowest_bit_exponent(double x) {
  const auto bits = std::bit_cast<std::uint64_t>(x);
  const auto biased = static_cast<int>((bits >> 52) & 0x7ffU);
  std::uint64_t significand = bits & ((std::uint64_t{1} << 52) - 1);
  if (biased != 0) significand |= std::uint64_t{1} << 52;  // the hidden bit of a normal number
  return std::max(biased, 1) - 1075 + std::countr_zero(significand);
}

// The largest g such that every coordinate of every row is a multiple of 2^g (the determinant,
// an integer polynomial of degree 5 in them, is then a multiple of 2^(5 g)); `kAllZero` when
// every coordinate is 0.
inline constexpr int kAllZero = 1 << 20;
inline int common_power_of_two(const std::array<RoundedRow, 4>& r) {
  int g = kAllZero;
  for (const RoundedRow& row : r) {
    for (const double c : {row.x, row.y, row.z}) {
      if (c != 0.0) g = std::min(g, lowest_bit_exponent(c));
    }
  }
  return g;
}

}  // namespace dtlab::predicates::detail
