#pragma once
// Fixed-capacity expansions on the stack, for the exact stages of the adaptive kernel. Private to
// the predicates target (compiled with strict floating point flags).
#include "dtlab/predicates/expansion.hpp"
#include "dtlab/predicates/point.hpp"

namespace dtlab::predicates::detail {

template <int N>
struct Exp {
  double c[N];
  int n = 0;
  [[nodiscard]] int sign() const { return expansion::sign_of(n, c); }
  [[nodiscard]] double estimate() const { return expansion::estimate(n, c); }
};

template <int A, int B>
Exp<A + B> add(const Exp<A>& e, const Exp<B>& f) {
  Exp<A + B> h;
  h.n = expansion::sum_zeroelim(e.n, e.c, f.n, f.c, h.c);
  return h;
}

template <int A>
Exp<2 * A> scale(const Exp<A>& e, double b) {
  Exp<2 * A> h;
  h.n = expansion::scale_zeroelim(e.n, e.c, b, h.c);
  return h;
}

// Exact p_u * q_v - q_u * p_v.
inline Exp<4> minor2(double pu, double pv, double qu, double qv) {
  Exp<4> h;
  h.n = expansion::two_two_diff_products(pu, qv, qu, pv, h.c);
  return h;
}

// Exact value * (x^2 + y^2 + z^2) for an expansion `value`; `sign` = -1 negates.
template <int A>
Exp<12 * A> times_squared_length(const Exp<A>& value, double x, double y, double z, double sign) {
  return add(add(scale(scale(value, sign * x), x), scale(scale(value, sign * y), y)),
             scale(scale(value, sign * z), z));
}

// Exact det[p q r] of raw xyz coordinates.
inline Exp<24> det3_raw(const Point3& p, const Point3& q, const Point3& r) {
  const Exp<4> qr = minor2(q.x, q.y, r.x, r.y);
  const Exp<4> pr = minor2(p.x, p.y, r.x, r.y);
  const Exp<4> pq = minor2(p.x, p.y, q.x, q.y);
  return add(add(scale(qr, p.z), scale(pr, -q.z)), scale(pq, r.z));
}

// Exact det[[a 1]; [b 1]; [c 1]; [d 1]] of raw coordinates, Shewchuk's orient3d sign
// (equal to det[a - d; b - d; c - d]).
inline Exp<96> orient3d_raw(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  Exp<24> bcd = det3_raw(b, c, d);
  for (int i = 0; i < bcd.n; ++i) bcd.c[i] = -bcd.c[i];
  Exp<24> abd = det3_raw(a, b, d);
  for (int i = 0; i < abd.n; ++i) abd.c[i] = -abd.c[i];
  return add(add(bcd, det3_raw(a, c, d)), add(abd, det3_raw(a, b, c)));
}

// Exact det[[u v 1]] of three projected points (Shewchuk's orient2d sign).
inline Exp<12> orient2d_raw(const Point3& p, const Point3& q, const Point3& r, int u, int v) {
  const double pu = coordinate(p, u);
  const double pv = coordinate(p, v);
  const double qu = coordinate(q, u);
  const double qv = coordinate(q, v);
  const double ru = coordinate(r, u);
  const double rv = coordinate(r, v);
  Exp<4> pr = minor2(pu, pv, ru, rv);
  for (int i = 0; i < pr.n; ++i) pr.c[i] = -pr.c[i];
  return add(add(minor2(qu, qv, ru, rv), pr), minor2(pu, pv, qu, qv));
}

}  // namespace dtlab::predicates::detail
