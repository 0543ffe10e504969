#pragma once
// Double-word arithmetic: a value held as hi + lo (about 106 significant bits), for the fast path
// of the adaptive insphere's stage B (docs/predicates.md, Lemma 7). Not exact: each operation
// below errs by at most v = 8 eps^2 (1 + 4 eps) times the sum (additions) or the product
// (multiplications) of its operands' magnitudes, which is what a permanent-based forward error
// bound needs. The proofs of those per-operation bounds are in docs/predicates.md; they assume
// round to nearest, every operation rounded on its own (-ffp-contract=off), and no underflow or
// overflow (Lemma 6's range supplies that on the insphere's inputs).
#include "dtlab/predicates/expansion.hpp"

namespace dtlab::predicates::double_word {

// hi + lo with |lo| <= eps |hi| (hi is the rounded value of the pair).
struct DoubleWord {
  double hi;
  double lo;
};

// a * b exactly (Dekker's product): no error.
inline DoubleWord exact_product(double a, double b) {
  const expansion::Exact2 p = expansion::product(a, b);
  return {p.hi, p.lo};
}

// a + b: the leading words summed exactly, the trailing words and that sum's error added in
// floating point, renormalized exactly. |error| <= 3 eps^2 (1 + 2 eps) (|a| + |b|).
inline DoubleWord operator+(DoubleWord a, DoubleWord b) {
  const expansion::Exact2 lead = expansion::sum_any(a.hi, b.hi);
  const double trail = a.lo + b.lo;
  const double rest = lead.lo + trail;
  const expansion::Exact2 r = expansion::sum_any(lead.hi, rest);
  return {r.hi, r.lo};
}

inline DoubleWord operator-(DoubleWord a, DoubleWord b) {
  return a + DoubleWord{-b.hi, -b.lo};
}

// a * y for a double y: hi * y exactly, lo * y rounded. |error| <= 3 eps^2 (1 + 2 eps) |a| |y|.
inline DoubleWord operator*(DoubleWord a, double y) {
  const expansion::Exact2 lead = expansion::product(a.hi, y);
  const double cross = a.lo * y;
  const double rest = lead.lo + cross;
  const expansion::Exact2 r = expansion::sum_any(lead.hi, rest);
  return {r.hi, r.lo};
}

// a * b: hi * hi exactly, the two cross products rounded, lo * lo dropped.
// |error| <= 8 eps^2 (1 + 4 eps) |a| |b|.
inline DoubleWord operator*(DoubleWord a, DoubleWord b) {
  const expansion::Exact2 lead = expansion::product(a.hi, b.hi);
  const double cross = a.hi * b.lo + a.lo * b.hi;
  const double rest = lead.lo + cross;
  const expansion::Exact2 r = expansion::sum_any(lead.hi, rest);
  return {r.hi, r.lo};
}

}  // namespace dtlab::predicates::double_word
