// Adaptive orient3d and orient2d (Shewchuk, DCG 18, 1997, Sect. 4.2 and 6).
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
using expansion::two_diff_tail;

// Stages B, C and D of Shewchuk's orient3d, his sign: det[a - d; b - d; c - d].
StagedSign orient3d_adapt_shewchuk(const Point3& a, const Point3& b, const Point3& c,
                                   const Point3& d, double permanent) {
  const double adx = a.x - d.x;
  const double bdx = b.x - d.x;
  const double cdx = c.x - d.x;
  const double ady = a.y - d.y;
  const double bdy = b.y - d.y;
  const double cdy = c.y - d.y;
  const double adz = a.z - d.z;
  const double bdz = b.z - d.z;
  const double cdz = c.z - d.z;

  // Stage B: the determinant of the rounded differences, exactly.
  const Exp<4> bc = detail::minor2(bdx, bdy, cdx, cdy);
  const Exp<4> ca = detail::minor2(cdx, cdy, adx, ady);
  const Exp<4> ab = detail::minor2(adx, ady, bdx, bdy);
  const Exp<24> fin = add(add(scale(bc, adz), scale(ca, bdz)), scale(ab, cdz));
  double det = fin.estimate();
  double errbound = bounds::kOrient3dB * permanent;
  if (det >= errbound || -det >= errbound) return {sign_of(det), Stage::B};

  const double adxtail = two_diff_tail(a.x, d.x, adx);
  const double bdxtail = two_diff_tail(b.x, d.x, bdx);
  const double cdxtail = two_diff_tail(c.x, d.x, cdx);
  const double adytail = two_diff_tail(a.y, d.y, ady);
  const double bdytail = two_diff_tail(b.y, d.y, bdy);
  const double cdytail = two_diff_tail(c.y, d.y, cdy);
  const double adztail = two_diff_tail(a.z, d.z, adz);
  const double bdztail = two_diff_tail(b.z, d.z, bdz);
  const double cdztail = two_diff_tail(c.z, d.z, cdz);
  if (adxtail == 0.0 && bdxtail == 0.0 && cdxtail == 0.0 && adytail == 0.0 && bdytail == 0.0 &&
      cdytail == 0.0 && adztail == 0.0 && bdztail == 0.0 && cdztail == 0.0) {
    return {fin.sign(), Stage::B};  // the differences were exact, so fin is the exact value
  }

  // Stage C: add the first-order effect of the tails.
  errbound = bounds::kOrient3dC * permanent + bounds::kResultErrBound * std::fabs(det);
  det += (adz * ((bdx * cdytail + cdy * bdxtail) - (bdy * cdxtail + cdx * bdytail)) +
          adztail * (bdx * cdy - bdy * cdx)) +
         (bdz * ((cdx * adytail + ady * cdxtail) - (cdy * adxtail + adx * cdytail)) +
          bdztail * (cdx * ady - cdy * adx)) +
         (cdz * ((adx * bdytail + bdy * adxtail) - (ady * bdxtail + bdx * adytail)) +
          cdztail * (adx * bdy - ady * bdx));
  if (det >= errbound || -det >= errbound) return {sign_of(det), Stage::C};

  // Stage D: exact, from the raw coordinates.
  return {detail::orient3d_raw(a, b, c, d).sign(), Stage::D};
}

}  // namespace

StagedSign AdaptiveKernel::orient3d_adapt(const Point3& a, const Point3& b, const Point3& c,
                                          const Point3& d, double permanent) {
  const StagedSign s = orient3d_adapt_shewchuk(a, b, c, d, permanent);
  return {-s.sign, s.stage};  // dtlab's sign is the negation of Shewchuk's
}

StagedSign AdaptiveKernel::orient3d_centroid_staged(const Point3& a, const Point3& b,
                                                    const Point3& c, const Tetrahedron4& v) {
  // Stage A: the four float determinants (Shewchuk's sign) and their permanents. Each is off by
  // at most kOrient3dA * permanent; the three additions add at most 3 eps (1 + eps)^3 times the
  // sum of magnitudes, which the extra 6 eps covers with room for the rounding of the bound.
  double sum = 0.0;
  double permanents = 0.0;
  for (const Point3& d : v) {
    const detail::DeterminantTerms t = detail::orient3d_terms(a, b, c, d);
    sum += t.det;
    permanents += t.permanent;
  }
  const double errbound = (bounds::kOrient3dA + 6.0 * bounds::kEpsilon) * permanents;
  if (sum > errbound || -sum > errbound) return {-sign_of(sum), Stage::A};
  // Exact: the sum of the four exact orientations.
  const Exp<192> first =
      add(detail::orient3d_raw(a, b, c, v[0]), detail::orient3d_raw(a, b, c, v[1]));
  const Exp<192> second =
      add(detail::orient3d_raw(a, b, c, v[2]), detail::orient3d_raw(a, b, c, v[3]));
  return {-add(first, second).sign(), Stage::D};
}

StagedSign AdaptiveKernel::orient2d_staged(const Point3& a, const Point3& b, const Point3& c,
                                           int drop) {
  const int u = projection_u(drop);
  const int v = projection_v(drop);
  const double detleft =
      (coordinate(a, u) - coordinate(c, u)) * (coordinate(b, v) - coordinate(c, v));
  const double detright =
      (coordinate(a, v) - coordinate(c, v)) * (coordinate(b, u) - coordinate(c, u));
  const double det = detleft - detright;
  const double errbound = bounds::kOrient2dA * (std::fabs(detleft) + std::fabs(detright));
  if (det > errbound || -det > errbound) return {sign_of(det), Stage::A};
  return {detail::orient2d_raw(a, b, c, u, v).sign(), Stage::D};
}

}  // namespace dtlab::predicates
