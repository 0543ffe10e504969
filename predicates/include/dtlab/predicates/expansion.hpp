#pragma once
// Exact floating-point expansion arithmetic after Shewchuk (DCG 18, 1997, Sect. 2).
// An expansion is an array of doubles, nonoverlapping and sorted by increasing magnitude, whose
// exact sum is the represented value. Every routine here is exact provided that no operation
// overflows or underflows and that the compiler neither contracts a*b+c into a fused
// multiply-add nor reassociates: the predicates target is built with -ffp-contract=off.
#include <cmath>

#include "dtlab/predicates/error_bounds.hpp"

namespace dtlab::predicates::expansion {

// x + y == a + b exactly, x = fl(a + b). Requires |a| >= |b| (or a == 0).
inline void fast_two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double b_virtual = x - a;
  y = b - b_virtual;
}

// x + y == a + b exactly, x = fl(a + b), for any a, b (Knuth's Two-Sum).
inline void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double b_virtual = x - a;
  const double a_virtual = x - b_virtual;
  const double b_roundoff = b - b_virtual;
  const double a_roundoff = a - a_virtual;
  y = a_roundoff + b_roundoff;
}

// The roundoff y of x = fl(a - b), so that x + y == a - b exactly.
inline double two_diff_tail(double a, double b, double x) {
  const double b_virtual = a - x;
  const double a_virtual = x + b_virtual;
  const double b_roundoff = b_virtual - b;
  const double a_roundoff = a - a_virtual;
  return a_roundoff + b_roundoff;
}

// Dekker's split: a == hi + lo, each with at most 26 significant bits.
inline void split(double a, double& hi, double& lo) {
  const double c = bounds::kSplitter * a;
  const double a_big = c - a;
  hi = c - a_big;
  lo = a - hi;
}

// x + y == a * b exactly, x = fl(a * b). With hardware FMA (compiled with -mfma) the roundoff is
// one fused operation; otherwise Veltkamp-Dekker splitting.
inline void two_product(double a, double b, double& x, double& y) {
  x = a * b;
#if defined(__FMA__) && !defined(DTLAB_DEKKER_PRODUCT)
  y = std::fma(a, b, -x);
#else
  double a_hi = 0.0;
  double a_lo = 0.0;
  double b_hi = 0.0;
  double b_lo = 0.0;
  split(a, a_hi, a_lo);
  split(b, b_hi, b_lo);
  const double err1 = x - (a_hi * b_hi);
  const double err2 = err1 - (a_lo * b_hi);
  const double err3 = err2 - (a_hi * b_lo);
  y = (a_lo * b_lo) - err3;
#endif
}

// h = e + f (Shewchuk's Fast-Expansion-Sum, Theorem 13) with zero components removed.
// h needs room for elen + flen components; returns the length of h (at least 1).
inline int sum_zeroelim(int elen, const double* e, int flen, const double* f, double* h) {
  int ei = 0;
  int fi = 0;
  // Merge by magnitude: take the smaller of the next components of e and f.
  auto next = [&]() -> double {
    if (fi >= flen || (ei < elen && std::fabs(e[ei]) <= std::fabs(f[fi]))) return e[ei++];
    return f[fi++];
  };
  const int total = elen + flen;
  int hi = 0;
  double q = next();
  if (total > 1) {
    double hh = 0.0;
    const double g = next();
    fast_two_sum(g, q, q, hh);
    if (hh != 0.0) h[hi++] = hh;
    for (int k = 2; k < total; ++k) {
      const double gk = next();
      two_sum(q, gk, q, hh);
      if (hh != 0.0) h[hi++] = hh;
    }
  }
  if (q != 0.0 || hi == 0) h[hi++] = q;
  return hi;
}

// h = b * e (Shewchuk's Scale-Expansion, Theorem 19) with zero components removed.
// h needs room for 2 * elen components; returns the length of h (at least 1).
inline int scale_zeroelim(int elen, const double* e, double b, double* h) {
  int hi = 0;
  double q = 0.0;
  double hh = 0.0;
  two_product(e[0], b, q, hh);
  if (hh != 0.0) h[hi++] = hh;
  for (int i = 1; i < elen; ++i) {
    double product1 = 0.0;
    double product0 = 0.0;
    double sum = 0.0;
    two_product(e[i], b, product1, product0);
    two_sum(q, product0, sum, hh);
    if (hh != 0.0) h[hi++] = hh;
    fast_two_sum(product1, sum, q, hh);
    if (hh != 0.0) h[hi++] = hh;
  }
  if (q != 0.0 || hi == 0) h[hi++] = q;
  return hi;
}

// Shewchuk's Compress (Sect. 2.8): the same value in as few components as cheaply possible,
// largest component a good approximation of the whole. In place is allowed (h == e).
inline int compress(int elen, const double* e, double* h) {
  int bottom = elen - 1;
  double q = e[bottom];
  for (int i = elen - 2; i >= 0; --i) {
    double q_new = 0.0;
    double small = 0.0;
    fast_two_sum(q, e[i], q_new, small);
    if (small != 0.0) {
      h[bottom--] = q_new;
      q = small;
    } else {
      q = q_new;
    }
  }
  int top = 0;
  for (int i = bottom + 1; i < elen; ++i) {
    double q_new = 0.0;
    double small = 0.0;
    fast_two_sum(h[i], q, q_new, small);
    if (small != 0.0) h[top++] = small;
    q = q_new;
  }
  h[top++] = q;
  return top;
}

// Approximate value (sum of components, smallest first).
inline double estimate(int elen, const double* e) {
  double sum = 0.0;
  for (int i = 0; i < elen; ++i) sum += e[i];
  return sum;
}

// The sign of an expansion is the sign of its most significant (last) component.
inline int sign_of(int elen, const double* e) {
  const double top = e[elen - 1];
  return (top > 0.0) - (top < 0.0);
}

// Exact a*b - c*d as an expansion of up to 4 components; returns its length.
inline int two_two_diff_products(double a, double b, double c, double d, double* h) {
  double ab[2];
  double cd[2];
  two_product(a, b, ab[1], ab[0]);
  two_product(-c, d, cd[1], cd[0]);
  return sum_zeroelim(2, ab, 2, cd, h);
}

}  // namespace dtlab::predicates::expansion
