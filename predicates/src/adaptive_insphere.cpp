// Adaptive insphere (stages B, C, D) by the Laplace expansion along the column pair
// (x, y) | (z, lift), and the lifted in-circle test of four coplanar points
// (docs/predicates.md).
#include <array>
#include <cmath>

#include "dtlab/predicates/detail/insphere_double_word.hpp"
#include "dtlab/predicates/error_bounds.hpp"
#include "dtlab/predicates/kernels.hpp"
#include "dtlab/predicates/valid_range.hpp"
#include "exact_stage.hpp"

namespace dtlab::predicates {
namespace {

using detail::Fixed;

// One row p - e: rounded coordinates, their tails, and the squared length of the rounded values
// in floating point (for stage C).
struct Row {
  double x, y, z;
  double tx, ty, tz;
  double lift;
};

Row make_row(const Point3& p, const Point3& e) {
  const expansion::Exact2 dx = expansion::difference(p.x, e.x);
  const expansion::Exact2 dy = expansion::difference(p.y, e.y);
  const expansion::Exact2 dz = expansion::difference(p.z, e.z);
  Row r{dx.hi, dy.hi, dz.hi, dx.lo, dy.lo, dz.lo, 0.0};
  r.lift = (r.x * r.x + r.y * r.y) + r.z * r.z;
  return r;
}

bool has_tail(const Row& r) {
  return r.tx != 0.0 || r.ty != 0.0 || r.tz != 0.0;
}

// The squared length of a row's rounded values, exactly.
Fixed<6> exact_lift(const Row& r) {
  return (detail::exact_product(r.x, r.x) + detail::exact_product(r.y, r.y)) +
         detail::exact_product(r.z, r.z);
}

// The exact products m_ij n_kl + m_kl n_ij of the rounded rows for the complementary pairs
// {i, j} and {k, l}: xy minor times z-lift minor, both ways round. lift[i]: exact_lift of row i.
Fixed<384> complementary_pair(const std::array<Row, 4>& r, const std::array<Fixed<6>, 4>& lift,
                              std::size_t i, std::size_t j, std::size_t k, std::size_t l) {
  const Fixed<4> m_ij =
      detail::exact_product(r[i].x, r[j].y) - detail::exact_product(r[j].x, r[i].y);
  const Fixed<4> m_kl =
      detail::exact_product(r[k].x, r[l].y) - detail::exact_product(r[l].x, r[k].y);
  const Fixed<24> n_kl = lift[l] * r[k].z - lift[k] * r[l].z;
  const Fixed<24> n_ij = lift[j] * r[i].z - lift[i] * r[j].z;
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
                                             const Point3& d, const Point3& e,
                                             const detail::FilteredValue& stage_a) {
  if (!in_expansion_range(a, b, c, d, e)) {
    return {ExactKernel::insphere(a, b, c, d, e), Stage::Gmp};
  }
  const std::array<Row, 4> rows{make_row(a, e), make_row(b, e), make_row(c, e), make_row(d, e)};
  const Row& r0 = rows[0];
  const Row& r1 = rows[1];
  const Row& r2 = rows[2];
  const Row& r3 = rows[3];
  const bool tails = has_tail(r0) || has_tail(r1) || has_tail(r2) || has_tail(r3);
  const double permanent = stage_a.permanent;
  const std::array<detail::RoundedRow, 4> rounded{
      {{r0.x, r0.y, r0.z}, {r1.x, r1.y, r1.z}, {r2.x, r2.y, r2.z}, {r3.x, r3.y, r3.z}}};

  // Stage B on exact rows, the grid certificate from stage A's value (Lemma 8): the ties of a
  // lattice (cospherical grid points) are proven 0 before any double word.
  if (!tails && detail::stage_a_proves_zero(stage_a.det, stage_a.bound,
                                            detail::common_power_of_two(rounded), 5)) {
    return {0, Stage::B};
  }

  // Stage B (Lemmas 2 and 7): -det4 of the rounded rows, X, in double words (D); exactly, as an
  // expansion in the grouping of stage A, only where the rows are exact and D cannot settle it.
  double det = detail::insphere_rounded_double_word(rounded).hi;
  if (!tails) {
    const int sign = detail::insphere_exact_rows_sign(rounded, det, permanent);
    if (sign != detail::kRowsUndecided) return {sign, Stage::B};
    const std::array<Fixed<6>, 4> lift{exact_lift(r0), exact_lift(r1), exact_lift(r2),
                                       exact_lift(r3)};
    const Fixed<1152> on_rounded =
        complementary_pair(rows, lift, 0, 2, 1, 3) -
        (complementary_pair(rows, lift, 0, 1, 2, 3) + complementary_pair(rows, lift, 0, 3, 1, 2));
    return {on_rounded.sign(), Stage::B};  // exact differences: the value is exact
  }
  const double bound_b = bounds::kInsphereBDoubleWord * permanent;
  if (det > bound_b || -det > bound_b) return {detail::sign_of(det), Stage::B};

  // Stage C (Lemma 3): the first-order change of each complementary pair, in floating point,
  // added to D (whose distance from X, Lemma 7, the bound adds).
  const double correction =
      pair_change(r0, r2, r1, r3) - (pair_change(r0, r1, r2, r3) + pair_change(r0, r3, r1, r2));
  det += correction;
  const double bound_c =
      bounds::kInsphereCDoubleWord * permanent + bounds::kCorrectedRelative * std::fabs(det);
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
