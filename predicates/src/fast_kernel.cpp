// Plain double predicates: the same determinants as stage A of the adaptive kernel, with no
// error bound. Their wrong signs on near-degenerate input are an object of study.
#include "dtlab/predicates/kernels.hpp"

namespace dtlab::predicates {
namespace {
int sign_of(double v) {
  return (v > 0.0) - (v < 0.0);
}
}  // namespace

int FastKernel::orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  const double adx = a.x - d.x, ady = a.y - d.y, adz = a.z - d.z;
  const double bdx = b.x - d.x, bdy = b.y - d.y, bdz = b.z - d.z;
  const double cdx = c.x - d.x, cdy = c.y - d.y, cdz = c.z - d.z;
  const double det =
      adz * (bdx * cdy - cdx * bdy) + bdz * (cdx * ady - adx * cdy) + cdz * (adx * bdy - bdx * ady);
  return -sign_of(det);  // dtlab's sign is the negation of Shewchuk's
}

int FastKernel::orient3d_centroid(const Point3& a, const Point3& b, const Point3& c,
                                  const Tetrahedron4& v) {
  double sum = 0.0;
  for (const Point3& d : v) {
    const double adx = a.x - d.x, ady = a.y - d.y, adz = a.z - d.z;
    const double bdx = b.x - d.x, bdy = b.y - d.y, bdz = b.z - d.z;
    const double cdx = c.x - d.x, cdy = c.y - d.y, cdz = c.z - d.z;
    sum += adz * (bdx * cdy - cdx * bdy) + bdz * (cdx * ady - adx * cdy) +
           cdz * (adx * bdy - bdx * ady);
  }
  return -sign_of(sum);
}

int FastKernel::insphere(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                         const Point3& e) {
  const double adx = a.x - e.x, ady = a.y - e.y, adz = a.z - e.z;
  const double bdx = b.x - e.x, bdy = b.y - e.y, bdz = b.z - e.z;
  const double cdx = c.x - e.x, cdy = c.y - e.y, cdz = c.z - e.z;
  const double ddx = d.x - e.x, ddy = d.y - e.y, ddz = d.z - e.z;
  const double ab = adx * bdy - bdx * ady;
  const double bc = bdx * cdy - cdx * bdy;
  const double cd = cdx * ddy - ddx * cdy;
  const double da = ddx * ady - adx * ddy;
  const double ac = adx * cdy - cdx * ady;
  const double bd = bdx * ddy - ddx * bdy;
  const double abc = adz * bc - bdz * ac + cdz * ab;
  const double bcd = bdz * cd - cdz * bd + ddz * bc;
  const double cda = cdz * da + ddz * ac + adz * cd;
  const double dab = ddz * ab + adz * bd + bdz * da;
  const double alift = adx * adx + ady * ady + adz * adz;
  const double blift = bdx * bdx + bdy * bdy + bdz * bdz;
  const double clift = cdx * cdx + cdy * cdy + cdz * cdz;
  const double dlift = ddx * ddx + ddy * ddy + ddz * ddz;
  return -sign_of((dlift * abc - clift * dab) + (blift * cda - alift * bcd));
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
