#pragma once
// Error-free transformations and expansion arithmetic, implemented from the theorems of
// Shewchuk, "Adaptive precision floating-point arithmetic and fast robust geometric predicates",
// DCG 18 (1997), Sect. 2 (Dekker's and Knuth's sums, Dekker's product, Theorems 6, 7, 13, 17-19
// and the compression of Sect. 2.8). Statements and proofs in docs/predicates.md.
//
// An expansion is a sequence of doubles whose exact sum is the value it represents, sorted by
// increasing magnitude, nonoverlapping (the lowest set bit of each component lies above the
// highest set bit of the one before), zeros removed except that the value 0 is the single
// component 0. Every routine is exact when no operation overflows or underflows, with round to
// nearest even, and with every operation rounded on its own: the predicates target is built with
// -ffp-contract=off (no fused multiply-add behind our back) and without -ffast-math.
#include <cmath>

#include "dtlab/predicates/error_bounds.hpp"

namespace dtlab::predicates::expansion {

// hi + lo == the exact result, hi == the rounded result, |lo| <= half an ulp of hi.
struct Exact2 {
  double hi;
  double lo;
};

// Dekker's sum (Theorem 6): for |big| >= |small| (or big == 0), the rounded sum and its error.
// s - big is exact, so is small - (s - big).
inline Exact2 sum_big_small(double big, double small) {
  const double s = big + small;
  const double small_in_s = s - big;
  return {s, small - small_in_s};
}

// Knuth's sum (Theorem 7): the same for any two doubles, at three more operations. Both
// summands' contributions to s are recovered and their losses added.
inline Exact2 sum_any(double a, double b) {
  const double s = a + b;
  const double b_in_s = s - a;
  const double a_in_s = s - b_in_s;
  return {s, (a - a_in_s) + (b - b_in_s)};
}

// a - b exactly (negation is exact).
inline Exact2 difference(double a, double b) {
  return sum_any(a, -b);
}

// Veltkamp's split (Theorem 17): a == high + low with both halves of at most 26 significant
// bits, so that products of halves are exact.
inline Exact2 split_halves(double a) {
  const double scaled = bounds::kSplitter * a;
  const double high = scaled - (scaled - a);
  return {high, a - high};
}

// Dekker's product (Theorem 18): the rounded product and its error. With a hardware fused
// multiply-add (-mfma) the error is one fused operation; otherwise the four partial products of
// the halves are subtracted from the rounded product, largest first, each step exact.
inline Exact2 product(double a, double b) {
  const double p = a * b;
#if defined(__FMA__) && !defined(DTLAB_DEKKER_PRODUCT)
  return {p, std::fma(a, b, -p)};
#else
  const Exact2 ha = split_halves(a);
  const Exact2 hb = split_halves(b);
  double rest = p - ha.hi * hb.hi;
  rest -= ha.lo * hb.hi;
  rest -= ha.hi * hb.lo;
  return {p, ha.lo * hb.lo - rest};
#endif
}

// Expansion sum (Theorem 13): h = e + f, for strongly nonoverlapping e and f (then h is too;
// exact for any inputs, but the ordering that sign() relies on needs that hypothesis). The
// components of both are taken in one merged order of increasing magnitude and folded into a
// running rounded total with Knuth's sum; every nonzero error that falls out is final and is
// emitted in order. h needs room for ne + nf components; returns its length (at least 1).
inline int add(const double* e, int ne, const double* f, int nf, double* h) {
  int ie = 0;
  int jf = 0;
  // Called exactly ne + nf times, so it never reads past either input. (clang-analyzer cannot
  // follow the lengths and reports reading an unwritten component; it does not.)
  auto next_smallest = [&]() -> double {
    // NOLINTNEXTLINE(clang-analyzer-core.uninitialized.UndefReturn)
    if (jf == nf || (ie < ne && std::fabs(e[ie]) <= std::fabs(f[jf]))) return e[ie++];
    return f[jf++];
  };
  int nh = 0;
  double total = next_smallest();
  for (int k = ne + nf - 1; k > 0; --k) {
    const Exact2 s = sum_any(total, next_smallest());
    if (s.lo != 0.0) h[nh++] = s.lo;
    total = s.hi;
  }
  if (total != 0.0 || nh == 0) h[nh++] = total;
  return nh;
}

// Scaling (Theorem 19): h = b * e, nonoverlapping for nonoverlapping e. Each component's exact
// product is two doubles; the low one is folded into the running total with Knuth's sum, the high
// one with Dekker's sum (it dominates the total by the nonoverlapping property). h needs room for 2
// ne components.
inline int scale(const double* e, int ne, double b, double* h) {
  int nh = 0;
  const Exact2 first = product(e[0], b);
  if (first.lo != 0.0) h[nh++] = first.lo;
  double total = first.hi;
  for (int i = 1; i < ne; ++i) {
    const Exact2 p = product(e[i], b);
    const Exact2 low = sum_any(total, p.lo);
    if (low.lo != 0.0) h[nh++] = low.lo;
    const Exact2 high = sum_big_small(p.hi, low.hi);
    if (high.lo != 0.0) h[nh++] = high.lo;
    total = high.hi;
  }
  if (total != 0.0 || nh == 0) h[nh++] = total;
  return nh;
}

// Compression (Sect. 2.8): the same value in few components, the largest one within an ulp of the
// whole. First from the top down: Dekker's sum of the running value and the next smaller
// component; where it leaves an error, the rounded part is set aside (it is final at its
// magnitude). Then from the bottom up over what was set aside, again keeping the nonzero errors.
// h may be e.
inline int compress(const double* e, int ne, double* h) {
  int set_aside = ne;  // h[set_aside .. ne) holds the parts set aside, smallest first
  double running = e[ne - 1];
  for (int i = ne - 2; i >= 0; --i) {
    const Exact2 s = sum_big_small(running, e[i]);
    if (s.lo != 0.0) {
      h[--set_aside] = s.hi;
      running = s.lo;
    } else {
      running = s.hi;
    }
  }
  int nh = 0;
  for (int i = set_aside; i < ne; ++i) {
    const Exact2 s = sum_big_small(h[i], running);
    if (s.lo != 0.0) h[nh++] = s.lo;
    running = s.hi;
  }
  h[nh++] = running;
  return nh;
}

// The sign of the value is the sign of its largest component.
inline int sign(const double* e, int ne) {
  const double top = e[ne - 1];
  return (top > 0.0) - (top < 0.0);
}

inline void negate(double* e, int ne) {
  for (int i = 0; i < ne; ++i) e[i] = -e[i];
}

}  // namespace dtlab::predicates::expansion
