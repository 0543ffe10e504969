// Adaptive orient3d (stages B, C, D), the centroid test and orient2d, for dtlab's decomposition
// about d along the x column: with rows u = a - d, v = b - d, w = c - d and (r, s, t) running
// cyclically over (u, v, w), orient3d = sum r_x (s_z t_y - s_y t_z) (docs/predicates.md).
#include <array>
#include <cmath>

#include "dtlab/predicates/detail/grid_certificate.hpp"
#include "dtlab/predicates/error_bounds.hpp"
#include "dtlab/predicates/kernels.hpp"
#include "dtlab/predicates/valid_range.hpp"
#include "exact_stage.hpp"

namespace dtlab::predicates {
namespace {

using detail::Fixed;
using expansion::difference;

// A rounded difference and its tail: p - q == value + tail exactly.
struct Rounded {
  double value;
  double tail;
};
Rounded rounded_difference(double p, double q) {
  const expansion::Exact2 d = difference(p, q);
  return {d.hi, d.lo};
}

struct RoundedVector {
  Rounded x, y, z;
};
RoundedVector rounded_vector(const Point3& p, const Point3& q) {
  return {rounded_difference(p.x, q.x), rounded_difference(p.y, q.y), rounded_difference(p.z, q.z)};
}
bool has_tail(const RoundedVector& r) {
  return r.x.tail != 0.0 || r.y.tail != 0.0 || r.z.tail != 0.0;
}

// One (z, y) minor on the rounded values, exactly: p q' - p' q.
Fixed<4> exact_minor(double p, double q_prime, double p_prime, double q) {
  return detail::exact_product(p, q_prime) - detail::exact_product(p_prime, q);
}

}  // namespace

StagedSign AdaptiveKernel::orient3d_beyond_a(const Point3& a, const Point3& b, const Point3& c,
                                             const Point3& d,
                                             const detail::FilteredValue& stage_a) {
  if (!in_expansion_range(a, b, c, d)) return {ExactKernel::orient3d(a, b, c, d), Stage::Gmp};
  const double permanent = stage_a.permanent;
  const RoundedVector u = rounded_vector(a, d);
  const RoundedVector v = rounded_vector(b, d);
  const RoundedVector w = rounded_vector(c, d);
  const bool tails = has_tail(u) || has_tail(v) || has_tail(w);

  // Stage B on exact differences, the grid certificate (Lemma 8): a tie on a grid (coplanar
  // points of a lattice) is proven 0 from stage A's value, without the expansion.
  if (!tails) {
    const std::array<detail::RoundedRow, 3> rows{{{u.x.value, u.y.value, u.z.value},
                                                  {v.x.value, v.y.value, v.z.value},
                                                  {w.x.value, w.y.value, w.z.value}}};
    if (detail::stage_a_proves_zero(stage_a.det, stage_a.bound, detail::common_power_of_two(rows),
                                    3)) {
      return {0, Stage::B};
    }
  }

  // Stage B: the determinant of the rounded differences, exactly (Lemma 2).
  const Fixed<24> on_rounded =
      (exact_minor(v.z.value, w.y.value, v.y.value, w.z.value) * u.x.value +
       exact_minor(w.z.value, u.y.value, w.y.value, u.z.value) * v.x.value) +
      exact_minor(u.z.value, v.y.value, u.y.value, v.z.value) * w.x.value;
  double det = on_rounded.approximate();
  const double bound_b = bounds::kOrient3dB * permanent;
  if (det > bound_b || -det > bound_b) return {detail::sign_of(det), Stage::B};
  if (!tails) return {on_rounded.sign(), Stage::B};  // exact differences: so is the value

  // Stage C (Lemma 3): add the terms of first order in the tails: for each cyclic (r, s, t),
  //   tail(r_x) m_st + r_x (tail(s_z) t_y + s_z tail(t_y) - tail(s_y) t_z - s_y tail(t_z)),
  // m_st = s_z t_y - s_y t_z in floating point.
  auto first_order = [](const RoundedVector& r, const RoundedVector& s, const RoundedVector& t) {
    const double minor = s.z.value * t.y.value - s.y.value * t.z.value;
    const double change = (s.z.tail * t.y.value + s.z.value * t.y.tail) -
                          (s.y.tail * t.z.value + s.y.value * t.z.tail);
    return r.x.tail * minor + r.x.value * change;
  };
  det += (first_order(u, v, w) + first_order(v, w, u)) + first_order(w, u, v);
  const double bound_c =
      bounds::kOrient3dC * permanent + bounds::kCorrectedRelative * std::fabs(det);
  if (det > bound_c || -det > bound_c) return {detail::sign_of(det), Stage::C};

  // Stage D: exact, from the exact differences.
  return {detail::orient3d_exact_sign(a, b, c, d), Stage::D};
}

StagedSign AdaptiveKernel::orient3d_centroid_staged(const Point3& a, const Point3& b,
                                                    const Point3& c, const Tetrahedron4& v) {
  const detail::FilteredValue f = detail::orient3d_centroid_float(a, b, c, v);
  if (std::fabs(f.det) > f.bound) return {detail::sign_of(f.det), Stage::A};
  if (!in_expansion_range(a, b, c, v[0], v[1], v[2], v[3])) {
    return {ExactKernel::orient3d_centroid(a, b, c, v), Stage::Gmp};
  }
  return {detail::orient3d_centroid_exact_sign(a, b, c, v), Stage::D};
}

StagedSign AdaptiveKernel::orient2d_staged(const Point3& a, const Point3& b, const Point3& c,
                                           int drop) {
  const detail::FilteredValue f = detail::orient2d_float(a, b, c, drop);
  if (std::fabs(f.det) > f.bound) return {detail::sign_of(f.det), Stage::A};
  if (!in_expansion_range(a, b, c)) return {ExactKernel::orient2d(a, b, c, drop), Stage::Gmp};
  return {detail::orient2d_exact_sign(a, b, c, drop), Stage::D};
}

}  // namespace dtlab::predicates
