// Plain double predicates: the same determinants as stage A of the adaptive kernel, with no
// error bound. Their wrong signs on near-degenerate input are an object of study.
#include "dtlab/predicates/kernels.hpp"

namespace dtlab::predicates {

using detail::sign_of;

int FastKernel::orient3d_centroid(const Point3& a, const Point3& b, const Point3& c,
                                  const Tetrahedron4& v) {
  double sum = 0.0;
  for (const Point3& d : v) sum += detail::orient3d_terms(a, b, c, d).det;
  return -sign_of(sum);
}

int FastKernel::orient2d(const Point3& a, const Point3& b, const Point3& c, int drop) {
  const int u = projection_u(drop);
  const int v = projection_v(drop);
  return sign_of((coordinate(a, u) - coordinate(c, u)) * (coordinate(b, v) - coordinate(c, v)) -
                 (coordinate(a, v) - coordinate(c, v)) * (coordinate(b, u) - coordinate(c, u)));
}

int FastKernel::incircle_lifted(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                                int drop) {
  const int u = projection_u(drop);
  const int v = projection_v(drop);
  const double adu = coordinate(a, u) - coordinate(d, u), adv = coordinate(a, v) - coordinate(d, v);
  const double bdu = coordinate(b, u) - coordinate(d, u), bdv = coordinate(b, v) - coordinate(d, v);
  const double cdu = coordinate(c, u) - coordinate(d, u), cdv = coordinate(c, v) - coordinate(d, v);
  const double adw = coordinate(a, drop) - coordinate(d, drop);
  const double bdw = coordinate(b, drop) - coordinate(d, drop);
  const double cdw = coordinate(c, drop) - coordinate(d, drop);
  const double alift = adu * adu + adv * adv + adw * adw;
  const double blift = bdu * bdu + bdv * bdv + bdw * bdw;
  const double clift = cdu * cdu + cdv * cdv + cdw * cdw;
  return sign_of(alift * (bdu * cdv - cdu * bdv) + blift * (cdu * adv - adu * cdv) +
                 clift * (adu * bdv - bdu * adv));
}

}  // namespace dtlab::predicates
