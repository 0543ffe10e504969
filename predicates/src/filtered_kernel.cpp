// The filtered kernel's exact path, taken when its semi-static filter (detail/semi_static.hpp)
// cannot decide: the exact expansions of stage D, or GMP for coordinates outside the expansion
// range (valid_range.hpp) or an expansion that outgrew its bounded capacity.
#include "dtlab/predicates/kernels.hpp"
#include "dtlab/predicates/valid_range.hpp"
#include "exact_stage.hpp"

namespace dtlab::predicates {

StagedSign FilteredKernel::orient3d_exact(const Point3& a, const Point3& b, const Point3& c,
                                          const Point3& d) {
  if (!in_expansion_range(a, b, c, d)) return {ExactKernel::orient3d(a, b, c, d), Stage::Gmp};
  return {detail::orient3d_exact_sign(a, b, c, d), Stage::D};
}

StagedSign FilteredKernel::insphere_exact(const Point3& a, const Point3& b, const Point3& c,
                                          const Point3& d, const Point3& e) {
  if (in_expansion_range(a, b, c, d, e)) {
    const int exact = detail::insphere_exact_sign(a, b, c, d, e);
    if (exact != detail::kUndecided) return {exact, Stage::D};
  }
  return {ExactKernel::insphere(a, b, c, d, e), Stage::Gmp};
}

StagedSign FilteredKernel::orient2d_exact(const Point3& a, const Point3& b, const Point3& c,
                                          int drop) {
  if (!in_expansion_range(a, b, c)) return {ExactKernel::orient2d(a, b, c, drop), Stage::Gmp};
  return {detail::orient2d_exact_sign(a, b, c, drop), Stage::D};
}

StagedSign FilteredKernel::incircle_lifted_exact(const Point3& a, const Point3& b, const Point3& c,
                                                 const Point3& d, int drop) {
  if (in_expansion_range(a, b, c, d)) {
    const int exact = detail::incircle_lifted_exact_sign(a, b, c, d, drop);
    if (exact != detail::kUndecided) return {exact, Stage::D};
  }
  return {ExactKernel::incircle_lifted(a, b, c, d, drop), Stage::Gmp};
}

StagedSign FilteredKernel::orient3d_centroid_exact(const Point3& a, const Point3& b,
                                                   const Point3& c, const Tetrahedron4& v) {
  if (!in_expansion_range(a, b, c, v[0], v[1], v[2], v[3])) {
    return {ExactKernel::orient3d_centroid(a, b, c, v), Stage::Gmp};
  }
  return {detail::orient3d_centroid_exact_sign(a, b, c, v), Stage::D};
}

}  // namespace dtlab::predicates
