// Stage B's fast path (docs/predicates.md, Lemma 7) held against exact rational arithmetic: each
// double-word operation within its stated error, the insphere determinant of the rounded rows
// within bounds::kInsphereDoubleWord times stage A's permanent, and the grid certificate that
// declares a determinant 0 only where it is 0.
#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "dtlab/predicates/detail/float_determinants.hpp"
#include "dtlab/predicates/detail/insphere_double_word.hpp"
#include "dtlab/predicates/error_bounds.hpp"
#include "dtlab/predicates/kernels.hpp"
#include "predicate_inputs.hpp"

namespace dtlab::test {
namespace {

using predicates::AdaptiveKernel;
using predicates::ExactKernel;
using predicates::Stage;
using predicates::double_word::DoubleWord;
namespace detail = predicates::detail;

constexpr double kEps = predicates::bounds::kEpsilon;
// The per-operation error of docs/predicates.md, Lemma 7: 8 eps^2 (1 + 4 eps), rounded up.
const mpq_class kOperationError = mpq_class(8) * kEps * kEps * (1 + 4 * mpq_class(kEps));

mpq_class value(DoubleWord w) {
  return mpq_class(w.hi) + mpq_class(w.lo);
}
mpq_class magnitude(const mpq_class& q) {
  return q < 0 ? mpq_class(-q) : q;
}

// A double word with a random leading word (random exponent) and a trailing word within half an
// ulp of it, as the operations produce.
rc::Gen<DoubleWord> double_word_gen() {
  return rc::gen::apply(
      [](double mantissa, int exponent, double tail_fraction) {
        const double hi = std::ldexp(0.5 + mantissa, exponent);
        const auto sum =
            predicates::expansion::sum_any(hi, std::ldexp(tail_fraction, exponent - 53));
        return DoubleWord{sum.hi, sum.lo};
      },
      unit_double(), rc::gen::inRange(-40, 40),
      rc::gen::map(unit_double(), [](double u) { return 2.0 * u - 1.0; }));
}

void expect_normalized(DoubleWord w) {
  RC_ASSERT(std::fabs(w.lo) <= kEps * std::fabs(w.hi));
}

RC_GTEST_PROP(DoubleWord, AdditionWithinItsBound, ()) {
  const DoubleWord a = *double_word_gen();
  DoubleWord b = *double_word_gen();
  if (*rc::gen::arbitrary<bool>()) b = {-a.hi * (1 + 0x1p-40), -a.lo};  // heavy cancellation
  const DoubleWord s = a + b;
  expect_normalized(s);
  const mpq_class error = magnitude(value(s) - (value(a) + value(b)));
  RC_ASSERT(error <= kOperationError * (magnitude(value(a)) + magnitude(value(b))));
}

RC_GTEST_PROP(DoubleWord, ProductsWithinTheirBound, ()) {
  const DoubleWord a = *double_word_gen();
  const DoubleWord b = *double_word_gen();
  const DoubleWord ab = a * b;
  expect_normalized(ab);
  RC_ASSERT(magnitude(value(ab) - value(a) * value(b)) <=
            kOperationError * magnitude(value(a) * value(b)));
  const double y = b.hi;
  const DoubleWord ay = a * y;
  expect_normalized(ay);
  RC_ASSERT(magnitude(value(ay) - value(a) * mpq_class(y)) <=
            kOperationError * magnitude(value(a) * mpq_class(y)));
  const DoubleWord exact = predicates::double_word::exact_product(a.hi, y);
  RC_ASSERT(value(exact) == mpq_class(a.hi) * mpq_class(y));
}

// -det4 of the rounded rows of (a, b, c, d) about e, exactly: the value stage B computes.
mpq_class rounded_determinant(const std::array<detail::RoundedRow, 4>& r) {
  std::array<std::array<mpq_class, 4>, 4> m;
  for (std::size_t i = 0; i < 4; ++i) {
    const mpq_class x = r[i].x, y = r[i].y, z = r[i].z;
    m[i] = {x, y, z, x * x + y * y + z * z};
  }
  // Laplace along the first row of 3x3 cofactors (plain cofactor expansion).
  auto det3 = [&](std::size_t skip_row, std::size_t c0, std::size_t c1,
                  std::size_t c2) -> mpq_class {
    std::array<std::size_t, 3> rows{};
    std::size_t k = 0;
    for (std::size_t i = 0; i < 4; ++i) {
      if (i != skip_row) rows[k++] = i;
    }
    const auto& a = m[rows[0]];
    const auto& b = m[rows[1]];
    const auto& c = m[rows[2]];
    return a[c0] * (b[c1] * c[c2] - b[c2] * c[c1]) - a[c1] * (b[c0] * c[c2] - b[c2] * c[c0]) +
           a[c2] * (b[c0] * c[c1] - b[c1] * c[c0]);
  };
  mpq_class det4 = 0;
  for (std::size_t i = 0; i < 4; ++i) {
    const mpq_class term = m[i][3] * det3(i, 0, 1, 2);
    det4 += (i % 2 == 0 ? -1 : 1) * term;  // cofactor sign (-1)^(i + 3)
  }
  return -det4;
}

std::array<detail::RoundedRow, 4> rounded_rows(const std::array<Point3, 5>& p) {
  std::array<detail::RoundedRow, 4> r{};
  for (std::size_t i = 0; i < 4; ++i) {
    r[i] = {p[i].x - p[4].x, p[i].y - p[4].y, p[i].z - p[4].z};
  }
  return r;
}

void expect_within_bound(const std::array<Point3, 5>& p) {
  const std::array<detail::RoundedRow, 4> rows = rounded_rows(p);
  const mpq_class exact = rounded_determinant(rows);
  const DoubleWord d = detail::insphere_rounded_double_word(rows);
  const double permanent = detail::insphere_float(p[0], p[1], p[2], p[3], p[4]).permanent;
  RC_ASSERT(magnitude(value(d) - exact) <=
            mpq_class(predicates::bounds::kInsphereDoubleWord) * mpq_class(permanent));
  // Where the determinant is not 0 and the bound is far below it, the fast path has its sign.
  if (exact != 0 && magnitude(exact) > mpq_class(1024 * predicates::bounds::kInsphereDoubleWord) *
                                           mpq_class(permanent)) {
    RC_ASSERT((d.hi > 0) == (exact > 0));
  }
}

std::array<Point3, 5> five(const std::vector<Point3>& v) {
  return {v[0], v[1], v[2], v[3], v[4]};
}

RC_GTEST_PROP(InsphereDoubleWord, RandomPointsWithinBound, ()) {
  expect_within_bound(five(*rc::gen::container<std::vector<Point3>>(5, unit_point())));
}

RC_GTEST_PROP(InsphereDoubleWord, NearlyCosphericalWithinBound, ()) {
  const Point3 centre = *unit_point();
  const double r = std::ldexp(0.25 + *unit_double(), *rc::gen::inRange(-20, 20));
  std::array<Point3, 5> p{};
  for (auto& q : p)
    q = near_sphere(centre, r, *unit_double(), *unit_double(), *rc::gen::inRange(-2, 3));
  expect_within_bound(p);
}

RC_GTEST_PROP(InsphereDoubleWord, GridWithLargeOffsetsWithinBound, ()) {
  const double offset = std::ldexp(1.0, *rc::gen::inRange(0, 60));
  auto p = five(*rc::gen::container<std::vector<Point3>>(5, grid_point()));
  for (auto& q : p) q = {offset + q.x, offset * 0.5 + q.y, q.z - offset};
  expect_within_bound(p);
}

TEST(InsphereDoubleWord, LowestBitExponent) {
  EXPECT_EQ(detail::lowest_bit_exponent(1.0), 0);
  EXPECT_EQ(detail::lowest_bit_exponent(-6.0), 1);
  EXPECT_EQ(detail::lowest_bit_exponent(0.75), -2);
  EXPECT_EQ(detail::lowest_bit_exponent(0x1p-120), -120);
  EXPECT_EQ(detail::lowest_bit_exponent(1.0 + 0x1p-52), -52);
  EXPECT_EQ(detail::lowest_bit_exponent(0x1p-1074), -1074);  // the smallest subnormal
  EXPECT_EQ(detail::common_power_of_two({{{4, 0, 8}, {12, 0, 0}, {0, 16, 0}, {0, 0, 0}}}), 2);
  EXPECT_EQ(detail::common_power_of_two({{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}}}),
            detail::kAllZero);
}

// Cospherical points on scaled integer grids: the certificate must answer 0 in stage B (the
// scale moves the grid's power of two), and a point an ulp away must not be called 0.
RC_GTEST_PROP(InsphereDoubleWord, GridCertificateDecidesTiesInStageB, ()) {
  const int scale = *rc::gen::inRange(-100, 100);
  // Six points of the sphere x^2 + y^2 + z^2 = 25 about a random integer centre.
  const std::array<Point3, 6> on{
      {{5, 0, 0}, {0, 5, 0}, {0, 0, 5}, {3, 4, 0}, {0, -3, 4}, {-4, 0, 3}}};
  const Point3 centre = *grid_point();
  std::array<Point3, 5> p{};
  const auto left_out = *rc::gen::inRange<std::size_t>(0, 6);
  const auto rotation = *rc::gen::inRange<std::size_t>(0, 5);
  for (std::size_t i = 0, k = 0; i < 6; ++i) {
    if (i == left_out) continue;
    const Point3 q = add(on[i], centre);
    p[(k++ + rotation) % 5] = {std::ldexp(q.x, scale), std::ldexp(q.y, scale),
                               std::ldexp(q.z, scale)};
  }
  RC_PRE(ExactKernel::orient3d(p[0], p[1], p[2], p[3]) != 0);
  const predicates::StagedSign tie = AdaptiveKernel::insphere_staged(p[0], p[1], p[2], p[3], p[4]);
  RC_ASSERT(tie.sign == 0);
  RC_ASSERT(tie.stage == Stage::B);
  p[4] = nudge(p[4], *rc::gen::element(-1, 1));
  RC_ASSERT(AdaptiveKernel::insphere(p[0], p[1], p[2], p[3], p[4]) ==
            ExactKernel::insphere(p[0], p[1], p[2], p[3], p[4]));
  RC_ASSERT(ExactKernel::insphere(p[0], p[1], p[2], p[3], p[4]) != 0);
}

}  // namespace
}  // namespace dtlab::test
