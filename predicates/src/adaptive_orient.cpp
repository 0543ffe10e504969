// Adaptive orient3d (stages B, C, D), the centroid test and orient2d, for dtlab's triple-product
// decomposition u . (v x w) with u = b - a, v = c - a, w = d - a (docs/predicates.md).
#include <cmath>

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

// One component of the cross product v x w on the rounded values, exactly: p q' - p' q.
Fixed<4> exact_minor(double p, double q_prime, double p_prime, double q) {
  return detail::exact_product(p, q_prime) - detail::exact_product(p_prime, q);
}

}  // namespace

StagedSign AdaptiveKernel::orient3d_beyond_a(const Point3& a, const Point3& b, const Point3& c,
                                             const Point3& d, double permanent) {
  if (!in_expansion_range(a, b, c, d)) return {ExactKernel::orient3d(a, b, c, d), Stage::Gmp};
  const RoundedVector u = rounded_vector(b, a);
  const RoundedVector v = rounded_vector(c, a);
  const RoundedVector w = rounded_vector(d, a);

  // Stage B: the triple product of the rounded differences, exactly (Lemma 2).
  const Fixed<24> on_rounded =
      (exact_minor(v.y.value, w.z.value, v.z.value, w.y.value) * u.x.value +
       exact_minor(v.z.value, w.x.value, v.x.value, w.z.value) * u.y.value) +
      exact_minor(v.x.value, w.y.value, v.y.value, w.x.value) * u.z.value;
  double det = on_rounded.approximate();
  const double bound_b = bounds::kOrient3dB * permanent;
  if (det > bound_b || -det > bound_b) return {detail::sign_of(det), Stage::B};
  if (!has_tail(u) && !has_tail(v) && !has_tail(w)) {
    return {on_rounded.sign(), Stage::B};  // the differences were exact: so is the value
  }

  // Stage C (Lemma 3): add the terms of first order in the tails,
  //   tail(u) . (v x w) + u . (tail(v) x w + v x tail(w)),
  // with the cross product v x w in floating point.
  const double cx = v.y.value * w.z.value - v.z.value * w.y.value;
  const double cy = v.z.value * w.x.value - v.x.value * w.z.value;
  const double cz = v.x.value * w.y.value - v.y.value * w.x.value;
  const double dx =
      (v.y.tail * w.z.value + v.y.value * w.z.tail) - (v.z.tail * w.y.value + v.z.value * w.y.tail);
  const double dy =
      (v.z.tail * w.x.value + v.z.value * w.x.tail) - (v.x.tail * w.z.value + v.x.value * w.z.tail);
  const double dz =
      (v.x.tail * w.y.value + v.x.value * w.y.tail) - (v.y.tail * w.x.value + v.y.value * w.x.tail);
  const double correction = ((u.x.tail * cx + u.x.value * dx) + (u.y.tail * cy + u.y.value * dy)) +
                            (u.z.tail * cz + u.z.value * dz);
  det += correction;
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
