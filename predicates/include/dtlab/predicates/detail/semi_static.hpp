#pragma once
// The semi-static filters of the filtered kernel (Lemma 5 in docs/predicates.md), inline like
// stage A of the adaptive kernel. The bound is a constant times the product of the largest
// absolute coordinate differences per axis, a bound on every monomial; it holds while each
// maximum lies in a window where underflow cannot matter and nothing overflows.
#include <algorithm>
#include <array>
#include <cmath>

#include "dtlab/predicates/detail/float_determinants.hpp"
#include "dtlab/predicates/error_bounds.hpp"
#include "dtlab/predicates/point.hpp"

namespace dtlab::predicates::detail {

// The constants with their underflow margin (kStaticOrient3d, ...) are in float_determinants.hpp,
// where the adaptive kernel's insphere uses one too.

// The filter's verdict: a sign, or kUndecided.
inline constexpr int kFilterUndecided = 2;

inline int semi_static_verdict(double det, double bound) {
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return kFilterUndecided;
}

struct AxisMaxima {
  double x = 0.0, y = 0.0, z = 0.0;
  void add(const Point3& p, const Point3& origin) {
    x = std::max(x, std::fabs(p.x - origin.x));
    y = std::max(y, std::fabs(p.y - origin.y));
    z = std::max(z, std::fabs(p.z - origin.z));
  }
  [[nodiscard]] double smallest() const { return std::min(x, std::min(y, z)); }
  [[nodiscard]] double largest() const { return std::max(x, std::max(y, z)); }
};

// orient3d: 6 monomials r_x s_z t_y, each at most mx my mz. A zero axis makes every monomial 0.
inline int orient3d_semi_static(const Point3& a, const Point3& b, const Point3& c,
                                const Point3& d) {
  AxisMaxima m;
  m.add(a, d);
  m.add(b, d);
  m.add(c, d);
  const double low = m.smallest();
  if (low == 0.0) return 0;
  if (low < 0x1p-190 || m.largest() > 0x1p190) return kFilterUndecided;
  return semi_static_verdict(orient3d_float(a, b, c, d).det, kStaticOrient3d * ((m.x * m.y) * m.z));
}

// insphere: 72 monomials x_i y_j z_k w_l^2, each at most mx my mz M^2 with M the largest maximum.
inline int insphere_semi_static(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                                const Point3& e) {
  AxisMaxima m;
  m.add(a, e);
  m.add(b, e);
  m.add(c, e);
  m.add(d, e);
  const double low = m.smallest();
  const double high = m.largest();
  if (low == 0.0) return 0;
  if (low < 0x1p-105 || high > 0x1p105) return kFilterUndecided;
  return semi_static_verdict(insphere_det(a, b, c, d, e),
                             kStaticInsphere * (((m.x * m.y) * m.z) * (high * high)));
}

// orient2d: 2 monomials, each at most mu mv.
inline int orient2d_semi_static(const Point3& a, const Point3& b, const Point3& c, int drop) {
  const int iu = (drop + 1) % 3;
  const int iv = (drop + 2) % 3;
  const double mu = std::max(std::fabs(coordinate(b, iu) - coordinate(a, iu)),
                             std::fabs(coordinate(c, iu) - coordinate(a, iu)));
  const double mv = std::max(std::fabs(coordinate(b, iv) - coordinate(a, iv)),
                             std::fabs(coordinate(c, iv) - coordinate(a, iv)));
  if (mu == 0.0 || mv == 0.0) return 0;
  if (std::min(mu, mv) < 0x1p-300 || std::max(mu, mv) > 0x1p300) return kFilterUndecided;
  return semi_static_verdict(orient2d_float(a, b, c, drop).det, kStaticOrient2d * (mu * mv));
}

// incircle_lifted: 18 monomials L_r u_s v_t, each at most mu mv M^2 (M over u, v and the dropped
// axis w). A zero u or v axis makes every monomial 0.
inline int incircle_lifted_semi_static(const Point3& a, const Point3& b, const Point3& c,
                                       const Point3& d, int drop) {
  const int iu = (drop + 1) % 3;
  const int iv = (drop + 2) % 3;
  double mu = 0.0;
  double mv = 0.0;
  double mw = 0.0;
  for (const Point3* p : {&a, &b, &c}) {
    mu = std::max(mu, std::fabs(coordinate(*p, iu) - coordinate(d, iu)));
    mv = std::max(mv, std::fabs(coordinate(*p, iv) - coordinate(d, iv)));
    mw = std::max(mw, std::fabs(coordinate(*p, drop) - coordinate(d, drop)));
  }
  if (mu == 0.0 || mv == 0.0) return 0;
  const double high = std::max(mu, std::max(mv, mw));
  if (std::min(mu, mv) < 0x1p-130 || high > 0x1p130) return kFilterUndecided;
  return semi_static_verdict(incircle_lifted_float(a, b, c, d, drop).det,
                             kStaticIncircleLifted * ((mu * mv) * (high * high)));
}

// orient3d_centroid: 24 monomials, each at most mx my mz over the differences of a, b, c from
// each of the four points of v (each orientation is taken about its own v_r).
inline int orient3d_centroid_semi_static(const Point3& a, const Point3& b, const Point3& c,
                                         const std::array<Point3, 4>& v) {
  AxisMaxima m;
  for (const Point3& p : v) {
    m.add(a, p);
    m.add(b, p);
    m.add(c, p);
  }
  const double low = m.smallest();
  if (low == 0.0) return 0;
  if (low < 0x1p-190 || m.largest() > 0x1p190) return kFilterUndecided;
  return semi_static_verdict(orient3d_centroid_float(a, b, c, v).det,
                             kStaticCentroid * ((m.x * m.y) * m.z));
}

}  // namespace dtlab::predicates::detail
