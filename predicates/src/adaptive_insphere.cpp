// Adaptive insphere (stages B, C, D) by the Laplace expansion along the column pair
// (x, y) | (z, lift), and the lifted in-circle test of four coplanar points
// (docs/predicates.md).
#include <cmath>

#include "dtlab/predicates/error_bounds.hpp"
#include "dtlab/predicates/kernels.hpp"
#include "dtlab/predicates/valid_range.hpp"
#include "exact_stage.hpp"

namespace dtlab::predicates {
namespace {

using detail::Fixed;

// One row p - e: rounded coordinates, their tails, and the squared length of the rounded values
// (exactly and in floating point).
struct Row {
  double x, y, z;
  double tx, ty, tz;
  Fixed<6> lift_exact;
  double lift;
};

Row make_row(const Point3& p, const Point3& e) {
  const expansion::Exact2 dx = expansion::difference(p.x, e.x);
  const expansion::Exact2 dy = expansion::difference(p.y, e.y);
  const expansion::Exact2 dz = expansion::difference(p.z, e.z);
  Row r{dx.hi, dy.hi, dz.hi, dx.lo, dy.lo, dz.lo, {}, 0.0};
  r.lift_exact = (detail::exact_product(r.x, r.x) + detail::exact_product(r.y, r.y)) +
                 detail::exact_product(r.z, r.z);
  r.lift = (r.x * r.x + r.y * r.y) + r.z * r.z;
  return r;
}

bool has_tail(const Row& r) {
  return r.tx != 0.0 || r.ty != 0.0 || r.tz != 0.0;
}

// The exact products m_ij n_kl + m_kl n_ij of the rounded rows for the complementary pairs
// {i, j} and {k, l}: xy minor times z-lift minor, both ways round.
Fixed<384> complementary_pair(const Row& ri, const Row& rj, const Row& rk, const Row& rl) {
  const Fixed<4> m_ij = detail::exact_product(ri.x, rj.y) - detail::exact_product(rj.x, ri.y);
  const Fixed<4> m_kl = detail::exact_product(rk.x, rl.y) - detail::exact_product(rl.x, rk.y);
  const Fixed<24> n_kl = rl.lift_exact * rk.z - rk.lift_exact * rl.z;
  const Fixed<24> n_ij = rj.lift_exact * ri.z - ri.lift_exact * rj.z;
  return m_ij * n_kl + m_kl * n_ij;
}

// First-order changes caused by the tails, with the float values of the rounded rows.
double xy_change(const Row& p, const Row& q) {
  return (p.tx * q.y + p.x * q.ty) - (q.tx * p.y + q.x * p.ty);
}
double lift_change(const Row& p) {
  return 2.0 * ((p.x * p.tx + p.y * p.ty) + p.z * p.tz);
}
double zl_change(const Row& p, const Row& q) {
  return (p.tz * q.lift + p.z * lift_change(q)) - (q.tz * p.lift + q.z * lift_change(p));
}
// d(m_ij n_kl + m_kl n_ij) to first order.
double pair_change(const Row& ri, const Row& rj, const Row& rk, const Row& rl) {
  const double m_ij = ri.x * rj.y - rj.x * ri.y;
  const double m_kl = rk.x * rl.y - rl.x * rk.y;
  const double n_kl = rk.z * rl.lift - rl.z * rk.lift;
  const double n_ij = ri.z * rj.lift - rj.z * ri.lift;
  return (xy_change(ri, rj) * n_kl + m_ij * zl_change(rk, rl)) +
         (xy_change(rk, rl) * n_ij + m_kl * zl_change(ri, rj));
}

}  // namespace

StagedSign AdaptiveKernel::insphere_beyond_a(const Point3& a, const Point3& b, const Point3& c,
                                             const Point3& d, const Point3& e, double permanent) {
  if (!in_expansion_range(a, b, c, d, e)) {
    return {ExactKernel::insphere(a, b, c, d, e), Stage::Gmp};
  }
  const Row r0 = make_row(a, e);
  const Row r1 = make_row(b, e);
  const Row r2 = make_row(c, e);
  const Row r3 = make_row(d, e);

  // Stage B (Lemma 2): -det4 of the rounded rows exactly, in the grouping of stage A.
  const Fixed<1152> on_rounded =
      complementary_pair(r0, r2, r1, r3) -
      (complementary_pair(r0, r1, r2, r3) + complementary_pair(r0, r3, r1, r2));
  double det = on_rounded.approximate();
  const double bound_b = bounds::kInsphereB * permanent;
  if (det > bound_b || -det > bound_b) return {detail::sign_of(det), Stage::B};
  if (!has_tail(r0) && !has_tail(r1) && !has_tail(r2) && !has_tail(r3)) {
    return {on_rounded.sign(), Stage::B};  // exact differences: the value is exact
  }

  // Stage C (Lemma 3): the first-order change of each complementary pair, in floating point.
  const double correction =
      pair_change(r0, r2, r1, r3) - (pair_change(r0, r1, r2, r3) + pair_change(r0, r3, r1, r2));
  det += correction;
  const double bound_c =
      bounds::kInsphereC * permanent + bounds::kCorrectedRelative * std::fabs(det);
  if (det > bound_c || -det > bound_c) return {detail::sign_of(det), Stage::C};

  // Stage D: exact from the exact differences.
  const int exact = detail::insphere_exact_sign(a, b, c, d, e);
  if (exact == detail::kUndecided) return {ExactKernel::insphere(a, b, c, d, e), Stage::Gmp};
  return {exact, Stage::D};
}

StagedSign AdaptiveKernel::incircle_lifted_staged(const Point3& a, const Point3& b, const Point3& c,
                                                  const Point3& d, int drop) {
  const detail::FilteredValue f = detail::incircle_lifted_float(a, b, c, d, drop);
  if (std::fabs(f.det) > f.bound) return {detail::sign_of(f.det), Stage::A};
  if (!in_expansion_range(a, b, c, d)) {
    return {ExactKernel::incircle_lifted(a, b, c, d, drop), Stage::Gmp};
  }
  const int exact = detail::incircle_lifted_exact_sign(a, b, c, d, drop);
  if (exact == detail::kUndecided) {
    return {ExactKernel::incircle_lifted(a, b, c, d, drop), Stage::Gmp};
  }
  return {exact, Stage::D};
}

}  // namespace dtlab::predicates
