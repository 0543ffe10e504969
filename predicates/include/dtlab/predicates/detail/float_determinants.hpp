#pragma once
// The floating-point determinants of dtlab's decompositions (docs/predicates.md), each with its
// permanent and its proven stage A bound: the fast kernel's whole computation and the adaptive
// kernel's stage A. Inline so that both kernels cost no call; every target that includes this is
// compiled with -ffp-contract=off (an interface option of dtlab::predicates), so the operations
// are rounded one by one as the operation counts assume.
//
// Every value here carries dtlab's sign directly (kernels.hpp). The bound is
//   C * permanent + (underflow term),
// C from error_bounds.hpp for this evaluation order, the underflow term from Lemma 4. A
// difference or product that overflows makes the bound infinite or NaN, so the comparison
// |det| > bound fails and the call goes on to the exact stages.
#include <algorithm>
#include <array>
#include <cmath>

#if defined(__x86_64__)
#include <emmintrin.h>
#endif

#include "dtlab/predicates/error_bounds.hpp"
#include "dtlab/predicates/point.hpp"

namespace dtlab::predicates::detail {

// The semi-static filters' constants (Lemma 5 in docs/predicates.md; semi_static.hpp). Inside a
// window the underflow errors are below 2^-60 of the bound, so this relative margin covers them.
constexpr double with_underflow_margin(double k) {
  return k * (1.0 + 0x1p-20);
}
inline constexpr double kStaticOrient3d = with_underflow_margin(bounds::kStaticOrient3d);
inline constexpr double kStaticInsphere = with_underflow_margin(bounds::kStaticInsphere);
inline constexpr double kStaticOrient2d = with_underflow_margin(bounds::kStaticOrient2d);
inline constexpr double kStaticIncircleLifted =
    with_underflow_margin(bounds::kStaticIncircleLifted);
inline constexpr double kStaticCentroid = with_underflow_margin(bounds::kStaticCentroid);

struct FilteredValue {
  double det;        // the determinant in floating point, dtlab's sign
  double bound;      // |det| > bound proves the sign of the exact determinant
  double permanent;  // for the later stages' bounds
  double underflow;  // the part of bound that Lemma 4 adds
};

inline int sign_of(double v) {
  return (v > 0.0) - (v < 0.0);
}

// Lemma 4 for orient3d: six products with cofactor |r_x|, three with cofactor 1.
inline double orient3d_underflow(double abs_ux, double abs_vx, double abs_wx) {
  // unit (2 S + 3) = 2 unit ((|ux| + |vx|) + (|wx| + 1.5)), grouped for parallel evaluation.
  return (2.0 * bounds::kUnderflowUnit) * ((abs_ux + abs_vx) + (abs_wx + 1.5));
}

// orient3d about the last point d: rows u = a - d, v = b - d, w = c - d, and
// det[b - a; c - a; d - a] = -det[u; v; w], expanded along the x column in cyclic order:
//   det = u_x (v_z w_y - v_y w_z) + v_x (w_z u_y - w_y u_z) + w_x (u_z v_y - u_y v_z),
// summed as (u-term + v-term) + w-term. Why a column and d: every 2x2 minor is antisymmetric in
// its two rows, so two equal arguments give two terms that cancel exactly in floating point (or a
// zero row when one of them is d), and every kernel, fast included, returns an exact 0 when the
// engine's query point duplicates a vertex, wherever it stands among the arguments.
// Always inlined: out of line (GCC's choice in the engine) the four doubles came back through
// memory, a call of 77 instructions where stage A's test needs the determinant and the bound.
[[gnu::always_inline]] inline FilteredValue orient3d_float(const Point3& a, const Point3& b,
                                                           const Point3& c, const Point3& d) {
  const double ux = a.x - d.x, uy = a.y - d.y, uz = a.z - d.z;
  const double vx = b.x - d.x, vy = b.y - d.y, vz = b.z - d.z;
  const double wx = c.x - d.x, wy = c.y - d.y, wz = c.z - d.z;
  const double vzwy = vz * wy, vywz = vy * wz;  // the (z, y) minor of rows v, w
  const double wzuy = wz * uy, wyuz = wy * uz;  // of rows w, u
  const double uzvy = uz * vy, uyvz = uy * vz;  // of rows u, v
  const double det = (ux * (vzwy - vywz) + vx * (wzuy - wyuz)) + wx * (uzvy - uyvz);
  const double aux = std::fabs(ux), avx = std::fabs(vx), awx = std::fabs(wx);
  const double permanent =
      (aux * (std::fabs(vzwy) + std::fabs(vywz)) + avx * (std::fabs(wzuy) + std::fabs(wyuz))) +
      awx * (std::fabs(uzvy) + std::fabs(uyvz));
  const double underflow = orient3d_underflow(aux, avx, awx);
  return {det, bounds::kOrient3dA * permanent + underflow, permanent, underflow};
}

// insphere by the Laplace expansion along the column pair (x, y) | (z, lift): with rows
// r = a - e, b - e, c - e, d - e (indices 0..3), m_ij = x_i y_j - x_j y_i and
// n_kl = z_k L_l - z_l L_k (L = x^2 + y^2 + z^2),
//   det4 = (m01 n23 + m23 n01) - (m02 n13 + m13 n02) + (m03 n12 + m12 n03),
// and dtlab's insphere is the sign of -det4, evaluated as
//   (m02 n13 + m13 n02) - ((m01 n23 + m23 n01) + (m03 n12 + m12 n03)).
// The bound computed with the determinant: none (the semi-static filter computes its own), the
// permanent's (stage A), or the semi-static one first and the permanent's only when that one does
// not decide (the permanent is most of the work after the determinant). The same operations give
// the determinant in every mode, so the same rounded value.
enum class InsphereBound { kNone, kPermanent, kSemiStaticFirst };

template <InsphereBound kBound>
inline FilteredValue insphere_evaluate(const Point3& a, const Point3& b, const Point3& c,
                                       const Point3& d, const Point3& e) {
  const double x0 = a.x - e.x, y0 = a.y - e.y, z0 = a.z - e.z;
  const double x1 = b.x - e.x, y1 = b.y - e.y, z1 = b.z - e.z;
  const double x2 = c.x - e.x, y2 = c.y - e.y, z2 = c.z - e.z;
  const double x3 = d.x - e.x, y3 = d.y - e.y, z3 = d.z - e.z;
  const double lift0 = (x0 * x0 + y0 * y0) + z0 * z0;
  const double lift1 = (x1 * x1 + y1 * y1) + z1 * z1;
  const double lift2 = (x2 * x2 + y2 * y2) + z2 * z2;
  const double lift3 = (x3 * x3 + y3 * y3) + z3 * z3;
  // x_i y_j products
  const double x0y1 = x0 * y1, x1y0 = x1 * y0, x0y2 = x0 * y2, x2y0 = x2 * y0;
  const double x0y3 = x0 * y3, x3y0 = x3 * y0, x1y2 = x1 * y2, x2y1 = x2 * y1;
  const double x1y3 = x1 * y3, x3y1 = x3 * y1, x2y3 = x2 * y3, x3y2 = x3 * y2;
  // z_k L_l products
  const double z0l1 = z0 * lift1, z1l0 = z1 * lift0, z0l2 = z0 * lift2, z2l0 = z2 * lift0;
  const double z0l3 = z0 * lift3, z3l0 = z3 * lift0, z1l2 = z1 * lift2, z2l1 = z2 * lift1;
  const double z1l3 = z1 * lift3, z3l1 = z3 * lift1, z2l3 = z2 * lift3, z3l2 = z3 * lift2;
  const double m01 = x0y1 - x1y0, m02 = x0y2 - x2y0, m03 = x0y3 - x3y0;
  const double m12 = x1y2 - x2y1, m13 = x1y3 - x3y1, m23 = x2y3 - x3y2;
  const double n01 = z0l1 - z1l0, n02 = z0l2 - z2l0, n03 = z0l3 - z3l0;
  const double n12 = z1l2 - z2l1, n13 = z1l3 - z3l1, n23 = z2l3 - z3l2;
  const double det = (m02 * n13 + m13 * n02) - ((m01 * n23 + m23 * n01) + (m03 * n12 + m12 * n03));
  using std::fabs;
  if constexpr (kBound == InsphereBound::kNone) return {det, 0.0, 0.0, 0.0};
  if constexpr (kBound == InsphereBound::kSemiStaticFirst) {
    // Lemma 5 on the same differences (semi_static.hpp's insphere_semi_static, its window too).
    using std::max;
    const double mx = max(max(fabs(x0), fabs(x1)), max(fabs(x2), fabs(x3)));
    const double my = max(max(fabs(y0), fabs(y1)), max(fabs(y2), fabs(y3)));
    const double mz = max(max(fabs(z0), fabs(z1)), max(fabs(z2), fabs(z3)));
    const double low = std::min(mx, std::min(my, mz));
    const double high = max(mx, max(my, mz));
    if (low >= 0x1p-105 && high <= 0x1p105) {
      const double bound = kStaticInsphere * (((mx * my) * mz) * (high * high));
      if (fabs(det) > bound) return {det, bound, 0.0, 0.0};  // decided: no permanent needed
    }
  }

  const double pm01 = fabs(x0y1) + fabs(x1y0), pm02 = fabs(x0y2) + fabs(x2y0);
  const double pm03 = fabs(x0y3) + fabs(x3y0), pm12 = fabs(x1y2) + fabs(x2y1);
  const double pm13 = fabs(x1y3) + fabs(x3y1), pm23 = fabs(x2y3) + fabs(x3y2);
  const double pn01 = fabs(z0l1) + fabs(z1l0), pn02 = fabs(z0l2) + fabs(z2l0);
  const double pn03 = fabs(z0l3) + fabs(z3l0), pn12 = fabs(z1l2) + fabs(z2l1);
  const double pn13 = fabs(z1l3) + fabs(z3l1), pn23 = fabs(z2l3) + fabs(z3l2);
  const double permanent =
      ((pm02 * pn13 + pm13 * pn02) + (pm01 * pn23 + pm23 * pn01)) + (pm03 * pn12 + pm12 * pn03);
  // Lemma 4 with R = the sum of the lifts: the cofactors of all 42 products add up to at most
  // 96 R^1.5 + 24 R + 6 <= 96 (R + 1)^2.
  const double r1 = ((lift0 + lift1) + (lift2 + lift3)) + 1.0;
  const double underflow = (96.0 * bounds::kUnderflowUnit) * (r1 * r1);
  return {det, bounds::kInsphereA * permanent + underflow, permanent, underflow};
}

#if defined(__x86_64__)
// insphere_evaluate, two values at a time in SSE2's two lanes. Each lane makes the scalar
// evaluation's operations on its values in the same order (IEEE arithmetic is the same per lane),
// so the determinant, the permanent, the underflow term and both bounds are the scalar ones bit for
// bit and the error analysis of docs/predicates.md holds unchanged; only the maxima of the
// semi-static bound are taken in another order, which does not change a maximum. The scalar code
// runs out of registers (half its instructions were moves).
//
// The core: the determinant, and with kAxes the axes' maxima (Lemma 5), with kPermanent the
// permanent and Lemma 4's term.
struct PackedInsphere {
  double det = 0.0;
  double mx = 0.0, my = 0.0, mz = 0.0;
  double permanent = 0.0;
  double underflow = 0.0;
};

template <bool kAxes, bool kPermanent>
[[gnu::always_inline]] inline PackedInsphere insphere_packed_core(const Point3& a, const Point3& b,
                                                                  const Point3& c, const Point3& d,
                                                                  const Point3& e) {
  PackedInsphere r;
  // Lanes (row 0, row 1) and (row 2, row 3) of x, y, z relative to e, and their lifts.
  const __m128d ex = _mm_set1_pd(e.x), ey = _mm_set1_pd(e.y), ez = _mm_set1_pd(e.z);
  const __m128d x01 = _mm_sub_pd(_mm_setr_pd(a.x, b.x), ex);
  const __m128d x23 = _mm_sub_pd(_mm_setr_pd(c.x, d.x), ex);
  const __m128d y01 = _mm_sub_pd(_mm_setr_pd(a.y, b.y), ey);
  const __m128d y23 = _mm_sub_pd(_mm_setr_pd(c.y, d.y), ey);
  const __m128d z01 = _mm_sub_pd(_mm_setr_pd(a.z, b.z), ez);
  const __m128d z23 = _mm_sub_pd(_mm_setr_pd(c.z, d.z), ez);
  auto lift = [](__m128d x, __m128d y, __m128d z) {
    return _mm_add_pd(_mm_add_pd(_mm_mul_pd(x, x), _mm_mul_pd(y, y)), _mm_mul_pd(z, z));
  };
  const __m128d l01 = lift(x01, y01, z01);
  const __m128d l23 = lift(x23, y23, z23);
  // The twelve products u_i v_j of columns (u, v) as six lane pairs, in the three pairings of the
  // rows: [0] (u0 v2, u1 v3) and (u2 v0, u3 v1), [1] (u0 v3, u1 v2) and (u3 v0, u2 v1), [2]
  // (u0 v1, u2 v3) and (u1 v0, u3 v2). Minor ij = u_i v_j - u_j v_i and its permanent
  // |u_i v_j| + |u_j v_i| as in the scalar code: lanes (02, 13), (03, 12) and (01, 23).
  struct Products {
    __m128d first[3];  // a C array: std::array would drop __m128d's alignment attribute
    __m128d second[3];
  };
  auto products = [](__m128d u01, __m128d u23, __m128d v01, __m128d v23) {
    const __m128d u32 = _mm_shuffle_pd(u23, u23, 1), v32 = _mm_shuffle_pd(v23, v23, 1);
    const __m128d u02 = _mm_unpacklo_pd(u01, u23), u13 = _mm_unpackhi_pd(u01, u23);
    const __m128d v02 = _mm_unpacklo_pd(v01, v23), v13 = _mm_unpackhi_pd(v01, v23);
    return Products{{_mm_mul_pd(u01, v23), _mm_mul_pd(u01, v32), _mm_mul_pd(u02, v13)},
                    {_mm_mul_pd(u23, v01), _mm_mul_pd(u32, v01), _mm_mul_pd(u13, v02)}};
  };
  const Products xy = products(x01, x23, y01, y23);
  const Products zl = products(z01, z23, l01, l23);
  auto swapped = [](__m128d v) { return _mm_shuffle_pd(v, v, 1); };
  auto low = [](__m128d v) { return _mm_cvtsd_f64(v); };
  auto high = [](__m128d v) { return _mm_cvtsd_f64(_mm_unpackhi_pd(v, v)); };
  // Pairing k of the 4x4 determinant: (m_02 n_13, m_13 n_02), (m_03 n_12, m_12 n_03),
  // (m_01 n_23, m_23 n_01), each minor times its complement.
  __m128d terms[3];
  for (std::size_t k = 0; k < 3; ++k) {
    const __m128d m = _mm_sub_pd(xy.first[k], xy.second[k]);
    const __m128d n = _mm_sub_pd(zl.first[k], zl.second[k]);
    terms[k] = _mm_mul_pd(m, swapped(n));
  }
  // (m01 n23 + m23 n01, m03 n12 + m12 n03) in one addition.
  const __m128d sums =
      _mm_add_pd(_mm_unpacklo_pd(terms[2], terms[1]), _mm_unpackhi_pd(terms[2], terms[1]));
  r.det = (low(terms[0]) + high(terms[0])) - (low(sums) + high(sums));

  const __m128d magnitude = _mm_castsi128_pd(_mm_set1_epi64x(0x7FFFFFFFFFFFFFFF));
  auto absolute = [&](__m128d v) { return _mm_and_pd(v, magnitude); };
  if constexpr (kAxes) {  // Lemma 5's maxima over the four rows
    auto axis_max = [&](__m128d v01, __m128d v23) {
      const __m128d both = _mm_max_pd(absolute(v01), absolute(v23));
      return _mm_cvtsd_f64(_mm_max_sd(both, _mm_unpackhi_pd(both, both)));
    };
    r.mx = axis_max(x01, x23);
    r.my = axis_max(y01, y23);
    r.mz = axis_max(z01, z23);
  }
  if constexpr (kPermanent) {
    // ((pm02 pn13 + pm13 pn02) + (pm01 pn23 + pm23 pn01)) + (pm03 pn12 + pm12 pn03), and Lemma
    // 4's term with the lifts' sum, as in insphere_evaluate.
    __m128d magnitudes[3];
    for (std::size_t k = 0; k < 3; ++k) {
      const __m128d pm = _mm_add_pd(absolute(xy.first[k]), absolute(xy.second[k]));
      const __m128d pn = _mm_add_pd(absolute(zl.first[k]), absolute(zl.second[k]));
      magnitudes[k] = _mm_mul_pd(pm, swapped(pn));
    }
    r.permanent =
        ((low(magnitudes[0]) + high(magnitudes[0])) + (low(magnitudes[2]) + high(magnitudes[2]))) +
        (low(magnitudes[1]) + high(magnitudes[1]));
    // ((lift0 + lift1) + (lift2 + lift3)) + 1
    const __m128d lift_pairs = _mm_add_pd(_mm_unpacklo_pd(l01, l23), _mm_unpackhi_pd(l01, l23));
    const double r1 = (low(lift_pairs) + high(lift_pairs)) + 1.0;
    r.underflow = (96.0 * bounds::kUnderflowUnit) * (r1 * r1);
  }
  return r;
}

// The permanent's stage A value, out of line: where the semi-static bound does not decide, the
// products are computed again rather than kept alive through the semi-static try (kept, they
// spilled registers on its path: 35 more instructions a call).
[[gnu::noinline]] inline FilteredValue insphere_packed_with_permanent(
    const Point3& a, const Point3& b, const Point3& c, const Point3& d, const Point3& e) {
  const PackedInsphere r = insphere_packed_core<false, true>(a, b, c, d, e);
  return {r.det, bounds::kInsphereA * r.permanent + r.underflow, r.permanent, r.underflow};
}

template <InsphereBound kBound>
[[gnu::always_inline]] inline FilteredValue insphere_packed(const Point3& a, const Point3& b,
                                                            const Point3& c, const Point3& d,
                                                            const Point3& e) {
  if constexpr (kBound == InsphereBound::kNone) {
    return {insphere_packed_core<false, false>(a, b, c, d, e).det, 0.0, 0.0, 0.0};
  } else if constexpr (kBound == InsphereBound::kPermanent) {
    return insphere_packed_with_permanent(a, b, c, d, e);
  } else {
    const PackedInsphere r = insphere_packed_core<true, false>(a, b, c, d, e);
    const double smallest = std::min(r.mx, std::min(r.my, r.mz));
    const double largest = std::max(r.mx, std::max(r.my, r.mz));
    if (smallest >= 0x1p-105 && largest <= 0x1p105) {
      const double bound = kStaticInsphere * (((r.mx * r.my) * r.mz) * (largest * largest));
      if (std::fabs(r.det) > bound) return {r.det, bound, 0.0, 0.0};
    }
    return insphere_packed_with_permanent(a, b, c, d, e);  // the same determinant
  }
}
#endif

// The kernels' entry points: the packed evaluation on x86-64 (SSE2 there is also the scalar
// arithmetic), else the scalar one (the
// same values).
template <InsphereBound kBound>
inline FilteredValue insphere_float_with(const Point3& a, const Point3& b, const Point3& c,
                                         const Point3& d, const Point3& e) {
#if defined(__x86_64__)
  return insphere_packed<kBound>(a, b, c, d, e);
#else
  return insphere_evaluate<kBound>(a, b, c, d, e);
#endif
}

// Stage A of insphere: the determinant with the permanent's bound.
inline FilteredValue insphere_float(const Point3& a, const Point3& b, const Point3& c,
                                    const Point3& d, const Point3& e) {
  return insphere_float_with<InsphereBound::kPermanent>(a, b, c, d, e);
}

// insphere_float's determinant alone.
inline double insphere_det(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                           const Point3& e) {
  return insphere_float_with<InsphereBound::kNone>(a, b, c, d, e).det;
}

// insphere_float, whose bound is the semi-static one where that decides (|det| > bound; then
// permanent and underflow are not computed), else the permanent's.
inline FilteredValue insphere_float_semi_static_first(const Point3& a, const Point3& b,
                                                      const Point3& c, const Point3& d,
                                                      const Point3& e) {
  return insphere_float_with<InsphereBound::kSemiStaticFirst>(a, b, c, d, e);
}

// orient2d in the projection that drops `drop`: det[b - a; c - a] of the kept coordinates
// (u, v) = ((drop + 1) % 3, (drop + 2) % 3).
inline FilteredValue orient2d_float(const Point3& a, const Point3& b, const Point3& c, int drop) {
  const int iu = (drop + 1) % 3;
  const int iv = (drop + 2) % 3;
  const double bu = coordinate(b, iu) - coordinate(a, iu);
  const double bv = coordinate(b, iv) - coordinate(a, iv);
  const double cu = coordinate(c, iu) - coordinate(a, iu);
  const double cv = coordinate(c, iv) - coordinate(a, iv);
  const double left = bu * cv;
  const double right = bv * cu;
  const double det = left - right;
  const double permanent = std::fabs(left) + std::fabs(right);
  const double underflow = 2.0 * bounds::kUnderflowUnit;
  return {det, bounds::kOrient2dA * permanent + underflow, permanent, underflow};
}

// The lifted in-circle determinant of four coplanar points: rows (u, v, L) of p - d for
// p = a, b, c, L the 3D squared length, expanded along the lift column:
//   det = L_a (u_b v_c - u_c v_b) + L_b (u_c v_a - u_a v_c) + L_c (u_a v_b - u_b v_a),
// summed as (a-term + b-term) + c-term.
inline FilteredValue incircle_lifted_float(const Point3& a, const Point3& b, const Point3& c,
                                           const Point3& d, int drop) {
  const int iu = (drop + 1) % 3;
  const int iv = (drop + 2) % 3;
  const double ua = coordinate(a, iu) - coordinate(d, iu);
  const double va = coordinate(a, iv) - coordinate(d, iv);
  const double wa = coordinate(a, drop) - coordinate(d, drop);
  const double ub = coordinate(b, iu) - coordinate(d, iu);
  const double vb = coordinate(b, iv) - coordinate(d, iv);
  const double wb = coordinate(b, drop) - coordinate(d, drop);
  const double uc = coordinate(c, iu) - coordinate(d, iu);
  const double vc = coordinate(c, iv) - coordinate(d, iv);
  const double wc = coordinate(c, drop) - coordinate(d, drop);
  const double lift_a = (ua * ua + va * va) + wa * wa;
  const double lift_b = (ub * ub + vb * vb) + wb * wb;
  const double lift_c = (uc * uc + vc * vc) + wc * wc;
  const double ubvc = ub * vc, ucvb = uc * vb;
  const double ucva = uc * va, uavc = ua * vc;
  const double uavb = ua * vb, ubva = ub * va;
  const double det = (lift_a * (ubvc - ucvb) + lift_b * (ucva - uavc)) + lift_c * (uavb - ubva);
  using std::fabs;
  const double permanent =
      (lift_a * (fabs(ubvc) + fabs(ucvb)) + lift_b * (fabs(ucva) + fabs(uavc))) +
      lift_c * (fabs(uavb) + fabs(ubva));
  // Lemma 4 with R = the sum of the lifts: six products with cofactor <= R, nine squares with
  // cofactor <= 2 R, three products with cofactor 1.
  const double r = (lift_a + lift_b) + lift_c;
  const double underflow = bounds::kUnderflowUnit * (24.0 * r + 3.0);
  return {det, bounds::kIncircleLiftedA * permanent + underflow, permanent, underflow};
}

// orient3d against the exact centroid of v: the sum of the four orientations (orient3d is affine
// in its last point), summed as (o0 + o1) + (o2 + o3).
inline FilteredValue orient3d_centroid_float(const Point3& a, const Point3& b, const Point3& c,
                                             const std::array<Point3, 4>& v) {
  const FilteredValue o0 = orient3d_float(a, b, c, v[0]);
  const FilteredValue o1 = orient3d_float(a, b, c, v[1]);
  const FilteredValue o2 = orient3d_float(a, b, c, v[2]);
  const FilteredValue o3 = orient3d_float(a, b, c, v[3]);
  const double det = (o0.det + o1.det) + (o2.det + o3.det);
  const double permanent = (o0.permanent + o1.permanent) + (o2.permanent + o3.permanent);
  const double underflow = (o0.underflow + o1.underflow) + (o2.underflow + o3.underflow);
  return {det, bounds::kCentroidA * permanent + underflow, permanent, underflow};
}

}  // namespace dtlab::predicates::detail
