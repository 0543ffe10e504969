#pragma once
// The fast path of the adaptive insphere's stage B (docs/predicates.md, Lemma 7): the determinant
// of the rounded differences in double-word arithmetic, in stage A's grouping, within
// bounds::kInsphereDoubleWord * permanent of its exact value; and the grid certificate that proves
// that value 0. Inline and header-only so that the tests can hold the bound against GMP.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include "dtlab/predicates/detail/grid_certificate.hpp"
#include "dtlab/predicates/double_word.hpp"
#include "dtlab/predicates/error_bounds.hpp"

namespace dtlab::predicates::detail {

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

// What insphere_exact_rows_sign returns when it cannot decide (the caller forms the expansion).
inline constexpr int kRowsUndecided = 2;

// Stage B on exact rows (no tails: X, the determinant of the rows, is the true one), from
// `value`, the leading word of insphere_rounded_double_word(rows), and stage A's permanent: X's
// sign when the double word is clear of 0; 0 when the grid certificate proves X = 0 (X is a
// multiple of 2^(5 g), and |X| <= |value| (1 + eps) + error < 2 |value| + 2 error < 2^(5 g));
// else kRowsUndecided.
inline int insphere_exact_rows_sign(const std::array<RoundedRow, 4>& rows, double value,
                                    double permanent) {
  const double size = std::fabs(value);
  const double error = bounds::kInsphereDoubleWord * permanent;
  if (size > 2.0 * error) return (value > 0.0) - (value < 0.0);
  const int g = common_power_of_two(rows);
  if (g == kAllZero) return 0;
  if (2.0 * size + 2.0 * error < power_of_two(5 * g)) return 0;
  return kRowsUndecided;
}

}  // namespace dtlab::predicates::detail
