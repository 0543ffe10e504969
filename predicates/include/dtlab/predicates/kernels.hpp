#pragma once
// The predicate kernels behind one interface. Each is a stateless struct of static functions, so
// the engine takes the kernel as a template parameter and pays nothing for the choice. Every
// function returns a sign in {-1, 0, +1}.
//
// Sign convention (docs/predicates.md), the same as CGAL's and the opposite of Shewchuk's:
//   orient3d(a, b, c, d) > 0  iff  det[b - a; c - a; d - a] > 0, i.e. d lies on the side of the
//                              plane abc into which (b - a) x (c - a) points. A tetrahedron abcd
//                              is positively oriented iff orient3d(a, b, c, d) > 0.
//   insphere(a, b, c, d, e) > 0 iff e lies strictly inside the sphere through a, b, c, d, when
//                              abcd is positively oriented (the sign flips for a negative one).
//   orient2d(a, b, c, drop) > 0 iff a, b, c turn counterclockwise in the projection that drops
//                              coordinate `drop` (0 = x, 1 = y, 2 = z), the remaining two taken in
//                              cyclic order ((y, z), (z, x) or (x, y)).
//   incircle_lifted(a, b, c, d, drop): for four coplanar points, the in-circle determinant of the
//                              projection that drops `drop`, with the full 3D squared length as
//                              the lifting. d is strictly inside the 3D circle through a, b, c
//                              iff its sign equals orient2d(a, b, c, drop) (which must be nonzero).
//   orient3d_centroid(a, b, c, v) = orient3d(a, b, c, (v0 + v1 + v2 + v3) / 4), the centroid taken
//                              exactly (orient3d is affine in its last point, so this is the sign
//                              of the sum of the four orientations). The engine's symbolic
//                              interior point.
//
// Kernels: `fast` (plain doubles, wrong signs possible: an object of study), `adaptive`
// (Shewchuk's adaptive stages A-D, derived and written for dtlab), `filtered` (a semi-static
// filter in the style of Meyer and Pion, then exact), `exact` (GMP). adaptive and filtered decide
// every finite double input exactly: where the expansion arithmetic of their exact stages could
// underflow or overflow they hand the call to the GMP evaluation (stage Gmp in the audit).
#include <array>
#include <cmath>
#include <cstdint>

#include "dtlab/predicates/detail/float_determinants.hpp"
#include "dtlab/predicates/detail/semi_static.hpp"
#include "dtlab/predicates/point.hpp"

namespace dtlab::predicates {

// Which stage settled a call. adaptive: A (float filter), B (exact on the rounded differences),
// C (first-order tail correction), D (exact expansions). filtered: A (semi-static filter), D
// (exact expansions). Both: Gmp, the exact GMP evaluation for a call whose coordinates lie
// outside the range where expansion arithmetic is exact (valid_range.hpp).
enum class Stage : std::uint8_t { A = 0, B = 1, C = 2, D = 3, Gmp = 4 };
inline constexpr int kStageCount = 5;
const char* stage_name(Stage s);

struct StagedSign {
  int sign;
  Stage stage;
};

using Tetrahedron4 = std::array<Point3, 4>;

// Plain double arithmetic: the float determinants of stage A, no error bound.
struct FastKernel {
  static constexpr const char* kName = "fast";
  static int orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
    return detail::sign_of(detail::orient3d_float(a, b, c, d).det);
  }
  static int insphere(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                      const Point3& e) {
    return detail::sign_of(detail::insphere_det(a, b, c, d, e));  // no bound computed
  }
  static int orient2d(const Point3& a, const Point3& b, const Point3& c, int drop) {
    return detail::sign_of(detail::orient2d_float(a, b, c, drop).det);
  }
  static int incircle_lifted(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                             int drop) {
    return detail::sign_of(detail::incircle_lifted_float(a, b, c, d, drop).det);
  }
  static int orient3d_centroid(const Point3& a, const Point3& b, const Point3& c,
                               const Tetrahedron4& v) {
    return detail::sign_of(detail::orient3d_centroid_float(a, b, c, v).det);
  }
};

// The plain sign functions of a kernel that reports stages: each is its *_staged function's sign.
template <class Staged>
struct SignsFromStages {
  static int orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
    return Staged::orient3d_staged(a, b, c, d).sign;
  }
  static int insphere(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                      const Point3& e) {
    return Staged::insphere_staged(a, b, c, d, e).sign;
  }
  static int orient2d(const Point3& a, const Point3& b, const Point3& c, int drop) {
    return Staged::orient2d_staged(a, b, c, drop).sign;
  }
  static int incircle_lifted(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                             int drop) {
    return Staged::incircle_lifted_staged(a, b, c, d, drop).sign;
  }
  static int orient3d_centroid(const Point3& a, const Point3& b, const Point3& c,
                               const Tetrahedron4& v) {
    return Staged::orient3d_centroid_staged(a, b, c, v).sign;
  }
};

// Shewchuk's adaptive-precision scheme (DCG 18, 1997), derived for dtlab's own decompositions
// (docs/predicates.md). Exact for every finite double; thread safe, no global state.
struct AdaptiveKernel : SignsFromStages<AdaptiveKernel> {
  static constexpr const char* kName = "adaptive";
  // Stage A inline; the later stages out of line.
  static StagedSign orient3d_staged(const Point3& a, const Point3& b, const Point3& c,
                                    const Point3& d) {
    const detail::FilteredValue f = detail::orient3d_float(a, b, c, d);
    if (std::fabs(f.det) > f.bound) return {detail::sign_of(f.det), Stage::A};
    return orient3d_beyond_a(a, b, c, d, f);
  }
  static StagedSign insphere_staged(const Point3& a, const Point3& b, const Point3& c,
                                    const Point3& d, const Point3& e) {
    // Stage A tries the semi-static bound first (Lemma 5: a constant times the axes' largest
    // differences, usually looser than the permanent's and much cheaper), then the permanent's.
    const detail::FilteredValue f = detail::insphere_float_semi_static_first(a, b, c, d, e);
    if (std::fabs(f.det) > f.bound) return {detail::sign_of(f.det), Stage::A};
    return insphere_beyond_a(a, b, c, d, e, f);
  }
  // Stages B, C, D (or Gmp), from stage A's value, bound and permanent.
  static StagedSign orient3d_beyond_a(const Point3& a, const Point3& b, const Point3& c,
                                      const Point3& d, const detail::FilteredValue& stage_a);
  static StagedSign insphere_beyond_a(const Point3& a, const Point3& b, const Point3& c,
                                      const Point3& d, const Point3& e,
                                      const detail::FilteredValue& stage_a);
  static StagedSign orient2d_staged(const Point3& a, const Point3& b, const Point3& c, int drop);
  static StagedSign incircle_lifted_staged(const Point3& a, const Point3& b, const Point3& c,
                                           const Point3& d, int drop);
  static StagedSign orient3d_centroid_staged(const Point3& a, const Point3& b, const Point3& c,
                                             const Tetrahedron4& v);
};

// A semi-static filter: the error bound is a precomputed constant times the product of the
// largest coordinate differences per axis (the scheme of Meyer and Pion's filter generator and of
// CGAL's static filters, derived here for dtlab's evaluation orders), valid on a stated magnitude
// window; outside it, or when the filter cannot decide, the exact expansion evaluation (stage D)
// or GMP decides. Exact for every finite double.
struct FilteredKernel : SignsFromStages<FilteredKernel> {
  static constexpr const char* kName = "filtered";
  // The filters inline (detail/semi_static.hpp); the exact evaluation out of line.
  static StagedSign orient3d_staged(const Point3& a, const Point3& b, const Point3& c,
                                    const Point3& d) {
    const int s = detail::orient3d_semi_static(a, b, c, d);
    return s != detail::kFilterUndecided ? StagedSign{s, Stage::A} : orient3d_exact(a, b, c, d);
  }
  static StagedSign insphere_staged(const Point3& a, const Point3& b, const Point3& c,
                                    const Point3& d, const Point3& e) {
    const int s = detail::insphere_semi_static(a, b, c, d, e);
    return s != detail::kFilterUndecided ? StagedSign{s, Stage::A} : insphere_exact(a, b, c, d, e);
  }
  static StagedSign orient2d_staged(const Point3& a, const Point3& b, const Point3& c, int drop) {
    const int s = detail::orient2d_semi_static(a, b, c, drop);
    return s != detail::kFilterUndecided ? StagedSign{s, Stage::A} : orient2d_exact(a, b, c, drop);
  }
  static StagedSign incircle_lifted_staged(const Point3& a, const Point3& b, const Point3& c,
                                           const Point3& d, int drop) {
    const int s = detail::incircle_lifted_semi_static(a, b, c, d, drop);
    return s != detail::kFilterUndecided ? StagedSign{s, Stage::A}
                                         : incircle_lifted_exact(a, b, c, d, drop);
  }
  static StagedSign orient3d_centroid_staged(const Point3& a, const Point3& b, const Point3& c,
                                             const Tetrahedron4& v) {
    const int s = detail::orient3d_centroid_semi_static(a, b, c, v);
    return s != detail::kFilterUndecided ? StagedSign{s, Stage::A}
                                         : orient3d_centroid_exact(a, b, c, v);
  }
  // Stage D (exact expansions), or Gmp outside the expansion range.
  static StagedSign orient3d_exact(const Point3& a, const Point3& b, const Point3& c,
                                   const Point3& d);
  static StagedSign insphere_exact(const Point3& a, const Point3& b, const Point3& c,
                                   const Point3& d, const Point3& e);
  static StagedSign orient2d_exact(const Point3& a, const Point3& b, const Point3& c, int drop);
  static StagedSign incircle_lifted_exact(const Point3& a, const Point3& b, const Point3& c,
                                          const Point3& d, int drop);
  static StagedSign orient3d_centroid_exact(const Point3& a, const Point3& b, const Point3& c,
                                            const Tetrahedron4& v);
};

// Arbitrary precision reference (GMP integers after an exact common power-of-two scaling).
// Exact for every finite double input, whatever its magnitude. Shares no code with the others.
struct ExactKernel {
  static constexpr const char* kName = "exact";
  static int orient3d_centroid(const Point3& a, const Point3& b, const Point3& c,
                               const Tetrahedron4& v);
  static int orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d);
  static int insphere(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                      const Point3& e);
  static int orient2d(const Point3& a, const Point3& b, const Point3& c, int drop);
  static int incircle_lifted(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                             int drop);
};

// The two coordinates kept by a projection that drops `drop`, in cyclic order.
inline int projection_u(int drop) {
  return (drop + 1) % 3;
}
inline int projection_v(int drop) {
  return (drop + 2) % 3;
}

}  // namespace dtlab::predicates
