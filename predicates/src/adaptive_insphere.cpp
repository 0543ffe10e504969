// Adaptive insphere (Shewchuk, DCG 18, 1997, Sect. 4.4 and 6) and the lifted in-circle test of
// four coplanar points that the infinite vertex needs.
#include <cmath>

#include "dtlab/predicates/error_bounds.hpp"
#include "dtlab/predicates/kernels.hpp"
#include "expansion_ops.hpp"

namespace dtlab::predicates {
namespace {

using detail::add;
using detail::Exp;
using detail::scale;
using detail::sign_of;
using detail::times_squared_length;
using expansion::two_diff_tail;

// Exact insphere from raw coordinates, Shewchuk's sign: the 5x5 determinant with rows
// [x y z x^2+y^2+z^2 1], expanded along the lifting column into five exact orientations:
// -|a|^2 O(bcde) + |b|^2 O(acde) - |c|^2 O(abde) + |d|^2 O(abce) - |e|^2 O(abcd).
int insphere_exact_sign(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                        const Point3& e) {
  const Exp<1152> ta = times_squared_length(detail::orient3d_raw(b, c, d, e), a.x, a.y, a.z, -1.0);
  const Exp<1152> tb = times_squared_length(detail::orient3d_raw(a, c, d, e), b.x, b.y, b.z, 1.0);
  const Exp<1152> tc = times_squared_length(detail::orient3d_raw(a, b, d, e), c.x, c.y, c.z, -1.0);
  const Exp<1152> td = times_squared_length(detail::orient3d_raw(a, b, c, e), d.x, d.y, d.z, 1.0);
  const Exp<1152> te = times_squared_length(detail::orient3d_raw(a, b, c, d), e.x, e.y, e.z, -1.0);
  return add(add(add(ta, tb), add(tc, td)), te).sign();
}

struct Differences {
  double adx, ady, adz, bdx, bdy, bdz, cdx, cdy, cdz, ddx, ddy, ddz;
};

// Stages B, C and D. `dif` holds a - e, b - e, c - e, d - e (named after Shewchuk's code, whose
// "d" column is our fourth point; the query e is the origin).
StagedSign insphere_adapt_shewchuk(const Point3& a, const Point3& b, const Point3& c,
                                   const Point3& d, const Point3& e, const Differences& dif,
                                   double permanent) {
  const double adx = dif.adx, ady = dif.ady, adz = dif.adz;
  const double bdx = dif.bdx, bdy = dif.bdy, bdz = dif.bdz;
  const double cdx = dif.cdx, cdy = dif.cdy, cdz = dif.cdz;
  const double ddx = dif.ddx, ddy = dif.ddy, ddz = dif.ddz;

  // Stage B: the determinant of the rounded differences, exactly.
  const Exp<4> ab = detail::minor2(adx, ady, bdx, bdy);
  const Exp<4> bc = detail::minor2(bdx, bdy, cdx, cdy);
  const Exp<4> cd = detail::minor2(cdx, cdy, ddx, ddy);
  const Exp<4> da = detail::minor2(ddx, ddy, adx, ady);
  const Exp<4> ac = detail::minor2(adx, ady, cdx, cdy);
  const Exp<4> bd = detail::minor2(bdx, bdy, ddx, ddy);
  const Exp<24> abc = add(add(scale(bc, adz), scale(ac, -bdz)), scale(ab, cdz));
  const Exp<24> bcd = add(add(scale(cd, bdz), scale(bd, -cdz)), scale(bc, ddz));
  const Exp<24> cda = add(add(scale(da, cdz), scale(ac, ddz)), scale(cd, adz));
  const Exp<24> dab = add(add(scale(ab, ddz), scale(bd, adz)), scale(da, bdz));
  const Exp<288> adet = times_squared_length(bcd, adx, ady, adz, -1.0);
  const Exp<288> bdet = times_squared_length(cda, bdx, bdy, bdz, 1.0);
  const Exp<288> cdet = times_squared_length(dab, cdx, cdy, cdz, -1.0);
  const Exp<288> ddet = times_squared_length(abc, ddx, ddy, ddz, 1.0);
  const Exp<1152> fin = add(add(adet, bdet), add(cdet, ddet));
  double det = fin.estimate();
  double errbound = bounds::kInsphereB * permanent;
  if (det >= errbound || -det >= errbound) return {sign_of(det), Stage::B};

  const double adxtail = two_diff_tail(a.x, e.x, adx);
  const double adytail = two_diff_tail(a.y, e.y, ady);
  const double adztail = two_diff_tail(a.z, e.z, adz);
  const double bdxtail = two_diff_tail(b.x, e.x, bdx);
  const double bdytail = two_diff_tail(b.y, e.y, bdy);
  const double bdztail = two_diff_tail(b.z, e.z, bdz);
  const double cdxtail = two_diff_tail(c.x, e.x, cdx);
  const double cdytail = two_diff_tail(c.y, e.y, cdy);
  const double cdztail = two_diff_tail(c.z, e.z, cdz);
  const double ddxtail = two_diff_tail(d.x, e.x, ddx);
  const double ddytail = two_diff_tail(d.y, e.y, ddy);
  const double ddztail = two_diff_tail(d.z, e.z, ddz);
  if (adxtail == 0.0 && adytail == 0.0 && adztail == 0.0 && bdxtail == 0.0 && bdytail == 0.0 &&
      bdztail == 0.0 && cdxtail == 0.0 && cdytail == 0.0 && cdztail == 0.0 && ddxtail == 0.0 &&
      ddytail == 0.0 && ddztail == 0.0) {
    return {fin.sign(), Stage::B};  // exact differences: fin is the exact determinant
  }

  // Stage C: first-order correction. Each *eps term is the first-order change of a 2x2 minor
  // caused by the tails, each *3 term the minor's float approximation.
  errbound = bounds::kInsphereC * permanent + bounds::kResultErrBound * std::fabs(det);
  const double ab3 = adx * bdy - bdx * ady;
  const double bc3 = bdx * cdy - cdx * bdy;
  const double cd3 = cdx * ddy - ddx * cdy;
  const double da3 = ddx * ady - adx * ddy;
  const double ac3 = adx * cdy - cdx * ady;
  const double bd3 = bdx * ddy - ddx * bdy;
  const double abeps = (adx * bdytail + bdy * adxtail) - (ady * bdxtail + bdx * adytail);
  const double bceps = (bdx * cdytail + cdy * bdxtail) - (bdy * cdxtail + cdx * bdytail);
  const double cdeps = (cdx * ddytail + ddy * cdxtail) - (cdy * ddxtail + ddx * cdytail);
  const double daeps = (ddx * adytail + ady * ddxtail) - (ddy * adxtail + adx * ddytail);
  const double aceps = (adx * cdytail + cdy * adxtail) - (ady * cdxtail + cdx * adytail);
  const double bdeps = (bdx * ddytail + ddy * bdxtail) - (bdy * ddxtail + ddx * bdytail);
  // First-order change of the four 3x3 minors, and their float approximations.
  const double abc_eps =
      (adz * bceps - bdz * aceps + cdz * abeps) + (adztail * bc3 - bdztail * ac3 + cdztail * ab3);
  const double bcd_eps =
      (bdz * cdeps - cdz * bdeps + ddz * bceps) + (bdztail * cd3 - cdztail * bd3 + ddztail * bc3);
  const double cda_eps =
      (cdz * daeps + ddz * aceps + adz * cdeps) + (cdztail * da3 + ddztail * ac3 + adztail * cd3);
  const double dab_eps =
      (ddz * abeps + adz * bdeps + bdz * daeps) + (ddztail * ab3 + adztail * bd3 + bdztail * da3);
  const double abc3 = adz * bc3 - bdz * ac3 + cdz * ab3;
  const double bcd3 = bdz * cd3 - cdz * bd3 + ddz * bc3;
  const double cda3 = cdz * da3 + ddz * ac3 + adz * cd3;
  const double dab3 = ddz * ab3 + adz * bd3 + bdz * da3;
  const double alift = adx * adx + ady * ady + adz * adz;
  const double blift = bdx * bdx + bdy * bdy + bdz * bdz;
  const double clift = cdx * cdx + cdy * cdy + cdz * cdz;
  const double dlift = ddx * ddx + ddy * ddy + ddz * ddz;
  det += ((blift * cda_eps + dlift * abc_eps) - (alift * bcd_eps + clift * dab_eps)) +
         2.0 * (((bdx * bdxtail + bdy * bdytail + bdz * bdztail) * cda3 +
                 (ddx * ddxtail + ddy * ddytail + ddz * ddztail) * abc3) -
                ((adx * adxtail + ady * adytail + adz * adztail) * bcd3 +
                 (cdx * cdxtail + cdy * cdytail + cdz * cdztail) * dab3));
  if (det >= errbound || -det >= errbound) return {sign_of(det), Stage::C};

  // Stage D: exact from raw coordinates.
  return {insphere_exact_sign(a, b, c, d, e), Stage::D};
}

}  // namespace

StagedSign AdaptiveKernel::insphere_adapt(const Point3& a, const Point3& b, const Point3& c,
                                          const Point3& d, const Point3& e, double permanent) {
  const Differences dif{a.x - e.x, a.y - e.y, a.z - e.z, b.x - e.x, b.y - e.y, b.z - e.z,
                        c.x - e.x, c.y - e.y, c.z - e.z, d.x - e.x, d.y - e.y, d.z - e.z};
  const StagedSign s = insphere_adapt_shewchuk(a, b, c, d, e, dif, permanent);
  return {-s.sign, s.stage};  // dtlab's sign is the negation of Shewchuk's
}

StagedSign AdaptiveKernel::incircle_lifted_staged(const Point3& a, const Point3& b, const Point3& c,
                                                  const Point3& d, int drop) {
  const int u = projection_u(drop);
  const int v = projection_v(drop);
  const double adu = coordinate(a, u) - coordinate(d, u);
  const double adv = coordinate(a, v) - coordinate(d, v);
  const double adw = coordinate(a, drop) - coordinate(d, drop);
  const double bdu = coordinate(b, u) - coordinate(d, u);
  const double bdv = coordinate(b, v) - coordinate(d, v);
  const double bdw = coordinate(b, drop) - coordinate(d, drop);
  const double cdu = coordinate(c, u) - coordinate(d, u);
  const double cdv = coordinate(c, v) - coordinate(d, v);
  const double cdw = coordinate(c, drop) - coordinate(d, drop);
  const double bucv = bdu * cdv, cubv = cdu * bdv;
  const double cuav = cdu * adv, aucv = adu * cdv;
  const double aubv = adu * bdv, buav = bdu * adv;
  const double alift = adu * adu + adv * adv + adw * adw;
  const double blift = bdu * bdu + bdv * bdv + bdw * bdw;
  const double clift = cdu * cdu + cdv * cdv + cdw * cdw;
  const double det = alift * (bucv - cubv) + blift * (cuav - aucv) + clift * (aubv - buav);
  const double permanent = (std::fabs(bucv) + std::fabs(cubv)) * alift +
                           (std::fabs(cuav) + std::fabs(aucv)) * blift +
                           (std::fabs(aubv) + std::fabs(buav)) * clift;
  const double errbound = bounds::kIncircleLiftedA * permanent;
  if (det > errbound || -det > errbound) return {sign_of(det), Stage::A};

  // Exact: det[[u v |p|^2 1]] of the raw points, equal to the difference form for coplanar
  // input; expanded along the lifting column into four exact projected orientations.
  const Exp<144> ta = times_squared_length(detail::orient2d_raw(b, c, d, u, v), a.x, a.y, a.z, 1.0);
  const Exp<144> tb =
      times_squared_length(detail::orient2d_raw(a, c, d, u, v), b.x, b.y, b.z, -1.0);
  const Exp<144> tc = times_squared_length(detail::orient2d_raw(a, b, d, u, v), c.x, c.y, c.z, 1.0);
  const Exp<144> td =
      times_squared_length(detail::orient2d_raw(a, b, c, u, v), d.x, d.y, d.z, -1.0);
  return {add(add(ta, tb), add(tc, td)).sign(), Stage::D};
}

}  // namespace dtlab::predicates
