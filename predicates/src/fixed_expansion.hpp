#pragma once
// Expansions held in fixed-capacity arrays on the stack (for the hot exact stages), and bounded
// ones (for the stages whose worst-case length is large). Capacities follow the length rules of
// the theorems: a sum has at most ne + nf components, a scaling at most 2 ne.
//
// Invariant: every expansion that enters a sum is strongly nonoverlapping, as the expansion sum
// (Theorem 13) requires. The outputs of Knuth's sum and Dekker's product are nonadjacent, a sum of
// strongly nonoverlapping expansions is strongly nonoverlapping, and a scaling is only proven
// nonoverlapping (Theorem 19), so every scaled expansion is compressed (nonadjacent afterwards,
// Sect. 2.8) before it is used. Private to the predicates target (strict floating point flags).
#include <utility>

#include "dtlab/predicates/expansion.hpp"

namespace dtlab::predicates::detail {

template <int N>
struct Fixed {
  double c[N];
  int n = 0;
  [[nodiscard]] int sign() const { return expansion::sign(c, n); }
  // Within one ulp of the value (2 eps relative): the largest component after compression.
  [[nodiscard]] double approximate() const {
    double h[N];
    const int nh = expansion::compress(c, n, h);
    return h[nh - 1];
  }
};

// b * e, compressed (see the invariant above).
template <int A>
int scale_compressed(const Fixed<A>& e, double b, double* h) {
  const int n = expansion::scale(e.c, e.n, b, h);
  return expansion::compress(h, n, h);
}

// hi + lo as an expansion (lo first, dropped when 0).
inline Fixed<2> as_expansion(expansion::Exact2 x) {
  Fixed<2> h;
  if (x.lo != 0.0) h.c[h.n++] = x.lo;
  h.c[h.n++] = x.hi;
  return h;
}
inline Fixed<2> exact_difference(double a, double b) {
  return as_expansion(expansion::difference(a, b));
}
inline Fixed<2> exact_product(double a, double b) {
  return as_expansion(expansion::product(a, b));
}

template <int A, int B>
Fixed<A + B> operator+(const Fixed<A>& e, const Fixed<B>& f) {
  Fixed<A + B> h;
  h.n = expansion::add(e.c, e.n, f.c, f.n, h.c);
  return h;
}

template <int A>
Fixed<A> operator-(Fixed<A> e) {
  expansion::negate(e.c, e.n);
  return e;
}

template <int A, int B>
Fixed<A + B> operator-(const Fixed<A>& e, const Fixed<B>& f) {
  return e + (-f);
}

template <int A>
Fixed<2 * A> operator*(const Fixed<A>& e, double b) {
  Fixed<2 * A> h;
  h.n = scale_compressed(e, b, h.c);
  return h;
}

// e * f as the sum of f scaled by each component of e; two buffers take turns as the running sum.
template <int A, int B>
Fixed<2 * A * B> operator*(const Fixed<A>& e, const Fixed<B>& f) {
  Fixed<2 * A * B> result;
  if (e.n == 1) {
    result.n = scale_compressed(f, e.c[0], result.c);
    return result;
  }
  double spare[2 * A * B];
  double* sum = spare;
  double* other = result.c;
  // Start in the buffer that the last addition will not write to, so the result lands in place.
  if ((e.n - 1) % 2 == 0) std::swap(sum, other);
  int n = scale_compressed(f, e.c[0], sum);
  for (int i = 1; i < e.n; ++i) {
    double part[2 * B];
    const int np = scale_compressed(f, e.c[i], part);
    n = expansion::add(sum, n, part, np, other);
    std::swap(sum, other);
  }
  result.n = n;
  return result;
}

// An expansion for the exact stages whose worst-case length is too long for fixed types
// (insphere and incircle_lifted from exact differences): a bounded stack array, compressed after
// every product so that lengths stay near what the values need (a few components in practice).
// An operation whose result could exceed the capacity marks the value as overflowed instead; the
// caller then decides the call with GMP. Exactness never depends on the capacity.
class Bounded {
 public:
  static constexpr int kCapacity = 192;

  Bounded() : n_(1) { c_[0] = 0.0; }
  template <int N>
  explicit Bounded(const Fixed<N>& f) : n_(f.n) {
    static_assert(N <= kCapacity);
    for (int i = 0; i < f.n; ++i) c_[i] = f.c[i];
  }

  // Copies move only the components in use.
  Bounded(const Bounded& other) : n_(other.n_) { copy_from(other); }
  Bounded& operator=(const Bounded& other) {
    n_ = other.n_;
    copy_from(other);
    return *this;
  }
  ~Bounded() = default;

  [[nodiscard]] bool overflowed() const { return n_ < 0; }
  [[nodiscard]] int sign() const { return expansion::sign(c_, n_); }

  friend Bounded operator+(const Bounded& e, const Bounded& f) {
    Bounded h;
    if (e.overflowed() || f.overflowed() || e.n_ + f.n_ > kCapacity) return overflow();
    h.n_ = expansion::add(e.c_, e.n_, f.c_, f.n_, h.c_);
    return h;
  }
  friend Bounded operator-(const Bounded& e, const Bounded& f) {
    if (f.overflowed()) return overflow();
    Bounded negated = f;
    expansion::negate(negated.c_, negated.n_);
    return e + negated;
  }
  // e * f as the sum of e scaled by each component of f, then compressed.
  friend Bounded operator*(const Bounded& e, const Bounded& f) {
    if (e.overflowed() || f.overflowed() || 2 * e.n_ * f.n_ > kCapacity) return overflow();
    Bounded total;
    double spare[kCapacity];
    double* sum = total.c_;
    double* other = spare;
    int n = e.scaled(f.c_[0], sum);
    for (int i = 1; i < f.n_; ++i) {
      double part[kCapacity];
      const int np = e.scaled(f.c_[i], part);
      n = expansion::add(sum, n, part, np, other);
      std::swap(sum, other);
    }
    total.n_ = expansion::compress(sum, n, total.c_);  // lands in total whichever buffer held it
    return total;
  }

 private:
  int scaled(double b, double* h) const {
    const int n = expansion::scale(c_, n_, b, h);
    return expansion::compress(h, n, h);
  }
  // The first n_ components are always written (by the routine that returned n_); clang-analyzer
  // cannot follow that through compress() and reports a garbage read.
  void copy_from(const Bounded& other) {
    // NOLINTNEXTLINE(clang-analyzer-core.uninitialized.Assign)
    for (int i = 0; i < other.n_; ++i) c_[i] = other.c_[i];
  }
  static Bounded overflow() {
    Bounded h;
    h.n_ = -1;
    return h;
  }
  double c_[kCapacity];
  int n_;
};

}  // namespace dtlab::predicates::detail
