// Pins dtlab's sign convention to CGAL's orientation and side_of_oriented_sphere (Shewchuk's
// orient3d and insphere have the opposite sign; see docs/predicates.md).
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include "dtlab/predicates/kernels.hpp"
#include "predicate_inputs.hpp"

namespace dtlab::test {
namespace {

using CgalKernel = CGAL::Exact_predicates_exact_constructions_kernel;
using CgalPoint = CgalKernel::Point_3;

CgalPoint cgal(const Point3& p) {
  return {p.x, p.y, p.z};
}

int cgal_orientation(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  return static_cast<int>(CGAL::orientation(cgal(a), cgal(b), cgal(c), cgal(d)));
}
int cgal_side_of_oriented_sphere(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                                 const Point3& e) {
  return static_cast<int>(
      CGAL::side_of_oriented_sphere(cgal(a), cgal(b), cgal(c), cgal(d), cgal(e)));
}

TEST(SignConvention, PositiveTetrahedronAndInside) {
  const Point3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0}, d{0, 0, 1};
  EXPECT_EQ(predicates::AdaptiveKernel::orient3d(a, b, c, d), 1);
  EXPECT_EQ(cgal_orientation(a, b, c, d), 1);
  const Point3 inside{0.25, 0.25, 0.25};
  EXPECT_EQ(predicates::AdaptiveKernel::insphere(a, b, c, d, inside), 1);
  EXPECT_EQ(cgal_side_of_oriented_sphere(a, b, c, d, inside), 1);  // ON_POSITIVE_SIDE
}

RC_GTEST_PROP(SignConvention, MatchesCgal, ()) {
  const auto p =
      *rc::gen::container<std::vector<Point3>>(5, rc::gen::oneOf(unit_point(), grid_point()));
  RC_ASSERT(predicates::AdaptiveKernel::orient3d(p[0], p[1], p[2], p[3]) ==
            cgal_orientation(p[0], p[1], p[2], p[3]));
  RC_ASSERT(predicates::ExactKernel::orient3d(p[0], p[1], p[2], p[3]) ==
            cgal_orientation(p[0], p[1], p[2], p[3]));
  RC_ASSERT(predicates::AdaptiveKernel::insphere(p[0], p[1], p[2], p[3], p[4]) ==
            cgal_side_of_oriented_sphere(p[0], p[1], p[2], p[3], p[4]));
}

}  // namespace
}  // namespace dtlab::test
