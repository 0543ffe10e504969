#pragma once
// Stage D: the exact value of each determinant from the exact coordinate differences (each a
// two-component expansion: rounded difference plus its tail), in the same decompositions as the
// float evaluations (detail/float_determinants.hpp). Valid when every coordinate of the call is
// within the expansion range (valid_range.hpp); the callers check that and use GMP otherwise.
// Shared by the adaptive and the filtered kernel.
#include "dtlab/predicates/kernels.hpp"
#include "fixed_expansion.hpp"

namespace dtlab::predicates::detail {

// Returned by the bounded-length evaluations (insphere, incircle_lifted) when an intermediate
// outgrew its capacity: the caller decides with GMP (fixed_expansion.hpp, Bounded).
inline constexpr int kUndecided = 2;

// det[b - a; c - a; d - a] exactly, in the column form of detail::orient3d_float.
Fixed<192> orient3d_exact(const Point3& a, const Point3& b, const Point3& c, const Point3& d);

int orient3d_exact_sign(const Point3& a, const Point3& b, const Point3& c, const Point3& d);
int insphere_exact_sign(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                        const Point3& e);
int orient2d_exact_sign(const Point3& a, const Point3& b, const Point3& c, int drop);
int incircle_lifted_exact_sign(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                               int drop);
int orient3d_centroid_exact_sign(const Point3& a, const Point3& b, const Point3& c,
                                 const Tetrahedron4& v);

}  // namespace dtlab::predicates::detail
