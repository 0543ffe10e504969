#pragma once
// The three predicate kernels behind one interface. Each is a stateless struct of static
// functions, so the engine takes the kernel as a template parameter and pays nothing for the
// choice. Every function returns a sign in {-1, 0, +1}.
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
#include <array>
#include <cstdint>

#include "dtlab/predicates/detail/float_determinants.hpp"
#include "dtlab/predicates/error_bounds.hpp"
#include "dtlab/predicates/point.hpp"

namespace dtlab::predicates {

// Which stage of the adaptive evaluation settled a call: A (float filter), B (exact on rounded
// differences), C (first-order tail correction), D (exact), or the exact fallback of a predicate
// that has only a filter and an exact stage.
enum class Stage : std::uint8_t { A = 0, B = 1, C = 2, D = 3 };
inline constexpr int kStageCount = 4;

struct StagedSign {
  int sign;
  Stage stage;
};

// Plain double arithmetic on coordinate differences, no filter. Wrong signs are possible and are
// what dtlab measures.
using Tetrahedron4 = std::array<Point3, 4>;

struct FastKernel {
  static constexpr const char* kName = "fast";
  static int orient3d_centroid(const Point3& a, const Point3& b, const Point3& c,
                               const Tetrahedron4& v);
  static int orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
    return -detail::sign_of(detail::orient3d_terms(a, b, c, d).det);  // dtlab sign = -Shewchuk's
  }
  static int insphere(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                      const Point3& e) {
    return -detail::sign_of(detail::insphere_terms(a, b, c, d, e).det);
  }
  static int orient2d(const Point3& a, const Point3& b, const Point3& c, int drop);
  static int incircle_lifted(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                             int drop);
};

// Shewchuk's adaptive-precision predicates, written for dtlab from the DCG 1997 paper. Exact for
// every input within the valid range (valid_range.hpp); thread safe, no global state.
struct AdaptiveKernel {
  static constexpr const char* kName = "adaptive";
  // Stage A inline; stages B, C and D out of line (adaptive_orient.cpp, adaptive_insphere.cpp).
  static StagedSign orient3d_staged(const Point3& a, const Point3& b, const Point3& c,
                                    const Point3& d) {
    const detail::DeterminantTerms t = detail::orient3d_terms(a, b, c, d);
    const double errbound = bounds::kOrient3dA * t.permanent;
    if (t.det > errbound || -t.det > errbound) return {-detail::sign_of(t.det), Stage::A};
    return orient3d_adapt(a, b, c, d, t.permanent);
  }
  static StagedSign insphere_staged(const Point3& a, const Point3& b, const Point3& c,
                                    const Point3& d, const Point3& e) {
    const detail::DeterminantTerms t = detail::insphere_terms(a, b, c, d, e);
    const double errbound = bounds::kInsphereA * t.permanent;
    if (t.det > errbound || -t.det > errbound) return {-detail::sign_of(t.det), Stage::A};
    return insphere_adapt(a, b, c, d, e, t.permanent);
  }
  // Stages B, C and D, with dtlab's sign; `permanent` from stage A.
  static StagedSign orient3d_adapt(const Point3& a, const Point3& b, const Point3& c,
                                   const Point3& d, double permanent);
  static StagedSign insphere_adapt(const Point3& a, const Point3& b, const Point3& c,
                                   const Point3& d, const Point3& e, double permanent);
  static StagedSign orient2d_staged(const Point3& a, const Point3& b, const Point3& c, int drop);
  static StagedSign incircle_lifted_staged(const Point3& a, const Point3& b, const Point3& c,
                                           const Point3& d, int drop);
  static StagedSign orient3d_centroid_staged(const Point3& a, const Point3& b, const Point3& c,
                                             const Tetrahedron4& v);
  static int orient3d_centroid(const Point3& a, const Point3& b, const Point3& c,
                               const Tetrahedron4& v) {
    return orient3d_centroid_staged(a, b, c, v).sign;
  }

  static int orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
    return orient3d_staged(a, b, c, d).sign;
  }
  static int insphere(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                      const Point3& e) {
    return insphere_staged(a, b, c, d, e).sign;
  }
  static int orient2d(const Point3& a, const Point3& b, const Point3& c, int drop) {
    return orient2d_staged(a, b, c, drop).sign;
  }
  static int incircle_lifted(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                             int drop) {
    return incircle_lifted_staged(a, b, c, d, drop).sign;
  }
};

// Arbitrary precision reference (GMP integers after an exact common power-of-two scaling).
// Exact for every finite double input, whatever its magnitude.
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
