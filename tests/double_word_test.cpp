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
#include <cstdint>
#include <cstdio>
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
// The per-operation errors of docs/predicates.md, Lemma 7: 8 eps^2 (1 + 4 eps) for a product of
// two double words, 3 eps^2 (1 + 2 eps) for a sum and for a product by a double.
const mpq_class kProductError = mpq_class(8) * kEps * kEps * (1 + 4 * mpq_class(kEps));
const mpq_class kSumError = mpq_class(3) * kEps * kEps * (1 + 2 * mpq_class(kEps));

mpq_class value(DoubleWord w) {
  return mpq_class(w.hi) + mpq_class(w.lo);
}
mpq_class magnitude(const mpq_class& q) {
  return q < 0 ? mpq_class(-q) : q;
}

// A full 53-bit significand in [0.5, 1): 52 random bits below the leading one.
rc::Gen<double> significand() {
  return rc::gen::map(
      rc::gen::inRange<std::uint64_t>(0, std::uint64_t{1} << 52), [](std::uint64_t bits) {
        return std::ldexp(static_cast<double>(bits | (std::uint64_t{1} << 52)), -53);
      });
}

// A double word of either sign: a full random leading word (random exponent) and a trailing word
// within half an ulp of it, as the operations produce.
rc::Gen<DoubleWord> double_word_gen() {
  return rc::gen::apply(
      [](double lead, int exponent, bool negative, double tail, bool tail_negative) {
        const double hi = std::ldexp(negative ? -lead : lead, exponent);
        const double lo = std::ldexp(tail_negative ? -tail : tail, exponent - 54);
        const auto sum = predicates::expansion::sum_any(hi, lo);
        return DoubleWord{sum.hi, sum.lo};
      },
      significand(), rc::gen::inRange(-40, 40), rc::gen::arbitrary<bool>(), significand(),
      rc::gen::arbitrary<bool>());
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
  RC_ASSERT(error <= kSumError * (magnitude(value(a)) + magnitude(value(b))));
}

RC_GTEST_PROP(DoubleWord, ProductsWithinTheirBound, ()) {
  const DoubleWord a = *double_word_gen();
  const DoubleWord b = *double_word_gen();
  const DoubleWord ab = a * b;
  expect_normalized(ab);
  RC_ASSERT(magnitude(value(ab) - value(a) * value(b)) <=
            kProductError * magnitude(value(a) * value(b)));
  const double y = b.hi;
  const DoubleWord ay = a * y;
  expect_normalized(ay);
  RC_ASSERT(magnitude(value(ay) - value(a) * mpq_class(y)) <=
            kSumError * magnitude(value(a) * mpq_class(y)));
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
  EXPECT_EQ(detail::lowest_bit_exponent(3 * 0x1p-1074), -1074);
  EXPECT_EQ(detail::lowest_bit_exponent(0x1p-1040), -1040);  // a subnormal's one bit
  EXPECT_EQ(detail::lowest_bit_exponent(0x1p-1022), -1022);  // the smallest normal
  EXPECT_EQ(detail::lowest_bit_exponent(-0x1p1023), 1023);
  EXPECT_EQ(detail::common_power_of_two(
                std::array<detail::RoundedRow, 3>{{{-0.0, 0.5, 0.0}, {0.0, -0.0, 3.0}, {0, 0, 0}}}),
            -1);
  EXPECT_EQ(detail::common_power_of_two(
                std::array<detail::RoundedRow, 4>{{{4, 0, 8}, {12, 0, 0}, {0, 16, 0}, {0, 0, 0}}}),
            2);
  EXPECT_EQ(detail::common_power_of_two(
                std::array<detail::RoundedRow, 4>{{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}}}),
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

// The certificate's rule, on rows whose power of two is chosen, against values and permanents
// placed on both sides of each threshold (error = 80 eps^2 perm; 2^(5 g) the grid of X).
TEST(InsphereDoubleWord, CertificateThresholds) {
  const double unit_error = predicates::bounds::kInsphereDoubleWord;
  auto rows_on = [](int g) {  // rows whose coordinates are multiples of 2^g, one exactly 2^g
    const double s = std::ldexp(1.0, g);
    return std::array<detail::RoundedRow, 4>{
        {{s, 3 * s, 0}, {-5 * s, 0, 7 * s}, {0, 2 * s, -4 * s}, {6 * s, -s, s}}};
  };
  for (const int g : {0, 3, -2, 40, -60}) {
    const auto rows = rows_on(g);
    ASSERT_EQ(detail::common_power_of_two(rows), g);
    const double grid = std::ldexp(1.0, 5 * g);
    // error = grid / 8: a value above 2 error is a sign; below it, and small, is 0.
    const double perm = grid / 8 / unit_error;
    EXPECT_EQ(detail::insphere_exact_rows_sign(rows, grid * 0.3, perm), 1) << g;
    EXPECT_EQ(detail::insphere_exact_rows_sign(rows, -grid * 0.3, perm), -1) << g;
    EXPECT_EQ(detail::insphere_exact_rows_sign(rows, grid * 0.2, perm), 0) << g;
    EXPECT_EQ(detail::insphere_exact_rows_sign(rows, 0.0, perm), 0) << g;
    // error = 3 grid / 8: 0.2 grid is within 2 error, and 2 (0.2) + 2 (0.375) = 1.15 grids is not
    // below one grid, so neither rule decides.
    const double wide = 3 * grid / 8 / unit_error;
    EXPECT_EQ(detail::insphere_exact_rows_sign(rows, grid * 0.2, wide), detail::kRowsUndecided)
        << g;
    // error = grid / 4: 2 (0.24) + 0.5 = 0.98 grids decides 0; 2 (0.26) + 0.5 = 1.02 does not.
    const double edge = grid / 4 / unit_error;
    EXPECT_EQ(detail::insphere_exact_rows_sign(rows, grid * 0.24, edge), 0) << g;
    EXPECT_EQ(detail::insphere_exact_rows_sign(rows, grid * 0.26, edge), detail::kRowsUndecided)
        << g;
  }
}

// The rule on real exact rows: whatever it decides (a sign, or 0 by the certificate) is what GMP
// says, on integer and dyadic point sets from small to large magnitudes, cospherical ones (five
// points of a sphere of radius 5 k) included.
TEST(InsphereDoubleWord, ExactRowsDecisionsAgreeWithGmp) {
  int signs = 0;  // cases the rule decided: a sign, and 0
  int zeros = 0;
  const bool passed = rc::check("the exact-rows rule agrees with GMP", [&] {
    const int scale = *rc::gen::inRange(-40, 40);
    const int span = 1 << *rc::gen::inRange(1, 24);
    const std::array<Point3, 6> on{
        {{5, 0, 0}, {0, 5, 0}, {0, 0, 5}, {3, 4, 0}, {0, -3, 4}, {-4, 0, 3}}};
    const bool cospherical = *rc::gen::arbitrary<bool>();
    const auto k = static_cast<double>(*rc::gen::inRange(1, span));
    std::array<Point3, 5> p{};
    for (std::size_t i = 0; i < 5; ++i) {
      Point3 q{};
      if (cospherical) {
        q = {on[i].x * k, on[i].y * k, on[i].z * k};
      } else {
        q = {static_cast<double>(*rc::gen::inRange(-span, span)),
             static_cast<double>(*rc::gen::inRange(-span, span)),
             static_cast<double>(*rc::gen::inRange(-span, span))};
      }
      p[i] = {std::ldexp(q.x, scale), std::ldexp(q.y, scale), std::ldexp(q.z, scale)};
    }
    const std::array<detail::RoundedRow, 4> rows = rounded_rows(p);
    for (std::size_t i = 0; i < 4; ++i) {  // exact rows only (the rule's precondition)
      RC_PRE(mpq_class(rows[i].x) == mpq_class(p[i].x) - mpq_class(p[4].x));
      RC_PRE(mpq_class(rows[i].y) == mpq_class(p[i].y) - mpq_class(p[4].y));
      RC_PRE(mpq_class(rows[i].z) == mpq_class(p[i].z) - mpq_class(p[4].z));
    }
    const double permanent = detail::insphere_float(p[0], p[1], p[2], p[3], p[4]).permanent;
    const double value = detail::insphere_rounded_double_word(rows).hi;
    const int decided = detail::insphere_exact_rows_sign(rows, value, permanent);
    const mpq_class exact = rounded_determinant(rows);
    const int exact_sign = (exact > 0) - (exact < 0);
    RC_TAG(decided == detail::kRowsUndecided ? "undecided" : decided == 0 ? "zero" : "sign");
    if (decided != detail::kRowsUndecided) RC_ASSERT(decided == exact_sign);
    signs += decided == 1 || decided == -1 ? 1 : 0;
    zeros += decided == 0 ? 1 : 0;
    RC_ASSERT(AdaptiveKernel::insphere(p[0], p[1], p[2], p[3], p[4]) ==
              ExactKernel::insphere(p[0], p[1], p[2], p[3], p[4]));
  });
  EXPECT_TRUE(passed);
  // The comparison runs only where the rule decides: it must have decided both ways.
  std::printf("exact rows: %d signs and %d zeros decided\n", signs, zeros);
  EXPECT_GE(signs, 3);
  EXPECT_GE(zeros, 3);
}

// Exact rows whose determinant is 0 but too large for the certificate (a sphere of radius
// 5 (2^25 + 1): the grid is 1, the double word's error about 2^40): the rule cannot decide, and
// stage B's expansion answers 0, as GMP does.
TEST(InsphereDoubleWord, LargeExactTiesGoToTheExpansion) {
  const double k = 0x1p25 + 1.0;
  const std::array<Point3, 5> p{
      {{5 * k, 0, 0}, {0, 5 * k, 0}, {0, 0, 5 * k}, {3 * k, 4 * k, 0}, {0, -3 * k, 4 * k}}};
  ASSERT_NE(ExactKernel::orient3d(p[0], p[1], p[2], p[3]), 0);
  const std::array<detail::RoundedRow, 4> rows = rounded_rows(p);
  const double permanent = detail::insphere_float(p[0], p[1], p[2], p[3], p[4]).permanent;
  const double value = detail::insphere_rounded_double_word(rows).hi;
  EXPECT_EQ(detail::insphere_exact_rows_sign(rows, value, permanent), detail::kRowsUndecided);
  const predicates::StagedSign s = AdaptiveKernel::insphere_staged(p[0], p[1], p[2], p[3], p[4]);
  EXPECT_EQ(s.sign, 0);
  EXPECT_EQ(s.stage, Stage::B);
  EXPECT_EQ(ExactKernel::insphere(p[0], p[1], p[2], p[3], p[4]), 0);
  // One unit off the sphere: not 0, and the adaptive kernel agrees with GMP.
  const Point3 off{0, -3 * k, 4 * k + 1};
  EXPECT_NE(ExactKernel::insphere(p[0], p[1], p[2], p[3], off), 0);
  EXPECT_EQ(AdaptiveKernel::insphere(p[0], p[1], p[2], p[3], off),
            ExactKernel::insphere(p[0], p[1], p[2], p[3], off));
}

// Lemma 8: stage A's value proves a tie on a grid. The rule at its threshold, then on real exact
// inputs: whenever it says 0, GMP says 0 (orient3d, degree 3, and insphere, degree 5), and ties
// of scaled lattices are decided 0 in stage B.
// The certificates' threshold 2^k from its bits is ldexp's, normal, subnormal, 0 and infinite.
TEST(GridCertificate, PowerOfTwoIsLdexps) {
  for (int k = -1200; k <= 1200; ++k) {
    EXPECT_EQ(detail::power_of_two(k), std::ldexp(1.0, k)) << k;
  }
}

TEST(GridCertificate, StageAThreshold) {
  for (const int g : {0, 7, -30}) {
    for (const int degree : {3, 5}) {
      const double grid = std::ldexp(1.0, degree * g);
      EXPECT_TRUE(detail::stage_a_proves_zero(0.2 * grid, 0.2 * grid, g, degree));
      EXPECT_FALSE(detail::stage_a_proves_zero(0.3 * grid, 0.2 * grid, g, degree));
      EXPECT_FALSE(detail::stage_a_proves_zero(0.0, 0.5 * grid, g, degree));
      EXPECT_TRUE(detail::stage_a_proves_zero(0.0, 0.49 * grid, g, degree));
    }
  }
  EXPECT_TRUE(detail::stage_a_proves_zero(1.0, 1.0, detail::kAllZero, 3));
}

TEST(GridCertificate, StageAZeroOnlyWhereGmpSaysZero) {
  int orient_zeros = 0;  // cases where stage A's certificate declared 0
  int insphere_zeros = 0;
  const bool passed = rc::check("stage A declares 0 only where GMP does", [&] {
    const int scale = *rc::gen::inRange(-60, 60);
    const int span = 1 << *rc::gen::inRange(1, 22);
    const bool flat = *rc::gen::arbitrary<bool>();  // points of one lattice plane: orient3d ties
    std::array<Point3, 5> p{};
    for (auto& q : p) {
      const auto x = static_cast<double>(*rc::gen::inRange(-span, span));
      const auto y = static_cast<double>(*rc::gen::inRange(-span, span));
      const auto z = flat ? 3.0 : static_cast<double>(*rc::gen::inRange(-span, span));
      q = {std::ldexp(x, scale), std::ldexp(y, scale), std::ldexp(z, scale)};
    }
    auto exact_rows = [&](std::size_t count, const Point3& base) {
      std::array<detail::RoundedRow, 4> r{};
      for (std::size_t i = 0; i < count; ++i) {
        r[i] = {p[i].x - base.x, p[i].y - base.y, p[i].z - base.z};
        RC_PRE(mpq_class(r[i].x) == mpq_class(p[i].x) - mpq_class(base.x));
        RC_PRE(mpq_class(r[i].y) == mpq_class(p[i].y) - mpq_class(base.y));
        RC_PRE(mpq_class(r[i].z) == mpq_class(p[i].z) - mpq_class(base.z));
      }
      return r;
    };
    const auto orient_rows = exact_rows(3, p[3]);
    const std::array<detail::RoundedRow, 3> three{{orient_rows[0], orient_rows[1], orient_rows[2]}};
    const detail::FilteredValue o = detail::orient3d_float(p[0], p[1], p[2], p[3]);
    if (detail::stage_a_proves_zero(o.det, o.bound, detail::common_power_of_two(three), 3)) {
      RC_ASSERT(ExactKernel::orient3d(p[0], p[1], p[2], p[3]) == 0);
      RC_TAG("orient3d proven 0");
      ++orient_zeros;
    }
    const auto sphere_rows = exact_rows(4, p[4]);
    const detail::FilteredValue s = detail::insphere_float(p[0], p[1], p[2], p[3], p[4]);
    if (detail::stage_a_proves_zero(s.det, s.bound, detail::common_power_of_two(sphere_rows), 5)) {
      RC_ASSERT(ExactKernel::insphere(p[0], p[1], p[2], p[3], p[4]) == 0);
      RC_TAG("insphere proven 0");
      ++insphere_zeros;
    }
    RC_ASSERT(AdaptiveKernel::orient3d(p[0], p[1], p[2], p[3]) ==
              ExactKernel::orient3d(p[0], p[1], p[2], p[3]));
    RC_ASSERT(AdaptiveKernel::insphere(p[0], p[1], p[2], p[3], p[4]) ==
              ExactKernel::insphere(p[0], p[1], p[2], p[3], p[4]));
  });
  EXPECT_TRUE(passed);
  // The comparison runs only where the certificate declares 0: it must have, for both.
  std::printf("stage A certificate: %d orient3d and %d insphere zeros\n", orient_zeros,
              insphere_zeros);
  EXPECT_GE(orient_zeros, 3);
  EXPECT_GE(insphere_zeros, 3);
}

TEST(GridCertificate, LatticeTiesStopInStageB) {
  for (const int scale : {-80, -3, 0, 5, 90}) {
    auto at = [&](double x, double y, double z) {
      return Point3{std::ldexp(x, scale), std::ldexp(y, scale), std::ldexp(z, scale)};
    };
    // Four coplanar lattice points, and the cube's corners (cospherical).
    const predicates::StagedSign flat =
        AdaptiveKernel::orient3d_staged(at(0, 0, 7), at(3, 1, 7), at(-2, 5, 7), at(4, 4, 7));
    EXPECT_EQ(flat.sign, 0) << scale;
    EXPECT_EQ(flat.stage, Stage::B) << scale;
    const predicates::StagedSign cube = AdaptiveKernel::insphere_staged(
        at(0, 0, 0), at(2, 0, 0), at(0, 2, 0), at(0, 0, 2), at(2, 2, 2));
    EXPECT_EQ(cube.sign, 0) << scale;
    EXPECT_EQ(cube.stage, Stage::B) << scale;
  }
}

}  // namespace
}  // namespace dtlab::test
