#pragma once
// The float determinants of orient3d and insphere (Shewchuk's sign) with their permanents: the
// fast kernel's whole computation and the adaptive kernel's stage A. Inline so that both kernels
// cost no call; every target that includes this is compiled with -ffp-contract=off (the flag is
// an interface option of dtlab::predicates) so the stage A error bounds hold as derived.
#include <cmath>

#include "dtlab/predicates/point.hpp"

namespace dtlab::predicates::detail {

struct DeterminantTerms {
  double det;
  double permanent;
};

// det[a - d; b - d; c - d] and its permanent.
inline DeterminantTerms orient3d_terms(const Point3& a, const Point3& b, const Point3& c,
                                       const Point3& d) {
  const double adx = a.x - d.x, bdx = b.x - d.x, cdx = c.x - d.x;
  const double ady = a.y - d.y, bdy = b.y - d.y, cdy = c.y - d.y;
  const double adz = a.z - d.z, bdz = b.z - d.z, cdz = c.z - d.z;
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
  const double permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * std::fabs(adz) +
                           (std::fabs(cdxady) + std::fabs(adxcdy)) * std::fabs(bdz) +
                           (std::fabs(adxbdy) + std::fabs(bdxady)) * std::fabs(cdz);
  return {det, permanent};
}

// Shewchuk's insphere determinant (rows a - e, b - e, c - e, d - e with their squared lengths)
// and its permanent.
inline DeterminantTerms insphere_terms(const Point3& a, const Point3& b, const Point3& c,
                                       const Point3& d, const Point3& e) {
  const double adx = a.x - e.x, ady = a.y - e.y, adz = a.z - e.z;
  const double bdx = b.x - e.x, bdy = b.y - e.y, bdz = b.z - e.z;
  const double cdx = c.x - e.x, cdy = c.y - e.y, cdz = c.z - e.z;
  const double ddx = d.x - e.x, ddy = d.y - e.y, ddz = d.z - e.z;
  const double aexbey = adx * bdy, bexaey = bdx * ady;
  const double bexcey = bdx * cdy, cexbey = cdx * bdy;
  const double cexdey = cdx * ddy, dexcey = ddx * cdy;
  const double dexaey = ddx * ady, aexdey = adx * ddy;
  const double aexcey = adx * cdy, cexaey = cdx * ady;
  const double bexdey = bdx * ddy, dexbey = ddx * bdy;
  const double ab = aexbey - bexaey;
  const double bc = bexcey - cexbey;
  const double cd = cexdey - dexcey;
  const double da = dexaey - aexdey;
  const double ac = aexcey - cexaey;
  const double bd = bexdey - dexbey;
  const double abc = adz * bc - bdz * ac + cdz * ab;
  const double bcd = bdz * cd - cdz * bd + ddz * bc;
  const double cda = cdz * da + ddz * ac + adz * cd;
  const double dab = ddz * ab + adz * bd + bdz * da;
  const double alift = adx * adx + ady * ady + adz * adz;
  const double blift = bdx * bdx + bdy * bdy + bdz * bdz;
  const double clift = cdx * cdx + cdy * cdy + cdz * cdz;
  const double dlift = ddx * ddx + ddy * ddy + ddz * ddz;
  const double det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);
  const double p_ab = std::fabs(aexbey) + std::fabs(bexaey);
  const double p_bc = std::fabs(bexcey) + std::fabs(cexbey);
  const double p_cd = std::fabs(cexdey) + std::fabs(dexcey);
  const double p_da = std::fabs(dexaey) + std::fabs(aexdey);
  const double p_ac = std::fabs(aexcey) + std::fabs(cexaey);
  const double p_bd = std::fabs(bexdey) + std::fabs(dexbey);
  const double az = std::fabs(adz), bz = std::fabs(bdz), cz = std::fabs(cdz), dz = std::fabs(ddz);
  const double permanent =
      (p_cd * bz + p_bd * cz + p_bc * dz) * alift + (p_da * cz + p_ac * dz + p_cd * az) * blift +
      (p_ab * dz + p_bd * az + p_da * bz) * clift + (p_bc * az + p_ac * bz + p_ab * cz) * dlift;
  return {det, permanent};
}

inline int sign_of(double v) {
  return (v > 0.0) - (v < 0.0);
}

}  // namespace dtlab::predicates::detail
