// GMP reference kernel. Every finite double is m * 2^q with an integer m of at most 53 bits, so
// after scaling all coordinates of one call by 2^-min(q) they are integers, the scaling is
// positive and common, and the determinants are evaluated exactly in mpz_class.
#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "dtlab/predicates/kernels.hpp"

namespace dtlab::predicates {
namespace {

template <std::size_t N>
std::array<mpz_class, N> to_common_integers(const std::array<double, N>& values) {
  std::array<std::int64_t, N> mantissa{};
  std::array<int, N> exponent{};
  int min_exponent = 0;
  bool any = false;
  for (std::size_t i = 0; i < N; ++i) {
    if (values[i] == 0.0) continue;
    int e = 0;
    const double m = std::frexp(values[i], &e);  // values[i] = m * 2^e, 0.5 <= |m| < 1
    mantissa[i] = static_cast<std::int64_t>(std::ldexp(m, 53));
    exponent[i] = e - 53;
    min_exponent = any ? std::min(min_exponent, exponent[i]) : exponent[i];
    any = true;
  }
  std::array<mpz_class, N> out;
  for (std::size_t i = 0; i < N; ++i) {
    if (values[i] == 0.0) continue;
    out[i] = mpz_class(static_cast<long>(mantissa[i]));
    mpz_mul_2exp(out[i].get_mpz_t(), out[i].get_mpz_t(),
                 static_cast<mp_bitcnt_t>(exponent[i] - min_exponent));
  }
  return out;
}

int sign_of(const mpz_class& v) {
  return sgn(v);
}

mpz_class det3(const mpz_class& a1, const mpz_class& a2, const mpz_class& a3, const mpz_class& b1,
               const mpz_class& b2, const mpz_class& b3, const mpz_class& c1, const mpz_class& c2,
               const mpz_class& c3) {
  return a1 * (b2 * c3 - b3 * c2) - a2 * (b1 * c3 - b3 * c1) + a3 * (b1 * c2 - b2 * c1);
}

}  // namespace

int ExactKernel::orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  const auto v =
      to_common_integers<12>({a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z, d.x, d.y, d.z});
  // det[b - a; c - a; d - a]
  return sign_of(det3(v[3] - v[0], v[4] - v[1], v[5] - v[2], v[6] - v[0], v[7] - v[1], v[8] - v[2],
                      v[9] - v[0], v[10] - v[1], v[11] - v[2]));
}

int ExactKernel::orient3d_centroid(const Point3& a, const Point3& b, const Point3& c,
                                   const Tetrahedron4& v) {
  const auto w = to_common_integers<21>({a.x,    a.y,    a.z,    b.x,    b.y,    b.z,    c.x,
                                         c.y,    c.z,    v[0].x, v[0].y, v[0].z, v[1].x, v[1].y,
                                         v[1].z, v[2].x, v[2].y, v[2].z, v[3].x, v[3].y, v[3].z});
  // det[b - a; c - a; 4 * centroid - 4 * a], all integers.
  const mpz_class sx = w[9] + w[12] + w[15] + w[18] - 4 * w[0];
  const mpz_class sy = w[10] + w[13] + w[16] + w[19] - 4 * w[1];
  const mpz_class sz = w[11] + w[14] + w[17] + w[20] - 4 * w[2];
  return sign_of(det3(w[3] - w[0], w[4] - w[1], w[5] - w[2], w[6] - w[0], w[7] - w[1], w[8] - w[2],
                      sx, sy, sz));
}

int ExactKernel::insphere(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                          const Point3& e) {
  const auto v = to_common_integers<15>(
      {a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z, d.x, d.y, d.z, e.x, e.y, e.z});
  std::array<std::array<mpz_class, 4>, 4> m;
  for (int r = 0; r < 4; ++r) {
    const mpz_class dx = v[3 * r] - v[12];
    const mpz_class dy = v[3 * r + 1] - v[13];
    const mpz_class dz = v[3 * r + 2] - v[14];
    m[r] = {dx, dy, dz, dx * dx + dy * dy + dz * dz};
  }
  // Shewchuk's determinant det[[p - e, |p - e|^2]] by cofactors along the lifting column.
  mpz_class det = 0;
  for (int r = 0; r < 4; ++r) {
    std::array<int, 3> rows{};
    int k = 0;
    for (int s = 0; s < 4; ++s) {
      if (s != r) rows[k++] = s;
    }
    const mpz_class minor =
        det3(m[rows[0]][0], m[rows[0]][1], m[rows[0]][2], m[rows[1]][0], m[rows[1]][1],
             m[rows[1]][2], m[rows[2]][0], m[rows[2]][1], m[rows[2]][2]);
    const mpz_class term = m[r][3] * minor;
    if ((r + 3) % 2 == 0) {
      det += term;
    } else {
      det -= term;
    }
  }
  return -sign_of(det);  // dtlab's sign is the negation of Shewchuk's
}

int ExactKernel::orient2d(const Point3& a, const Point3& b, const Point3& c, int drop) {
  const int u = projection_u(drop);
  const int v = projection_v(drop);
  const auto w = to_common_integers<6>({coordinate(a, u), coordinate(a, v), coordinate(b, u),
                                        coordinate(b, v), coordinate(c, u), coordinate(c, v)});
  return sign_of((w[0] - w[4]) * (w[3] - w[5]) - (w[1] - w[5]) * (w[2] - w[4]));
}

int ExactKernel::incircle_lifted(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                                 int drop) {
  const int u = projection_u(drop);
  const int v = projection_v(drop);
  const auto w = to_common_integers<12>({coordinate(a, u), coordinate(a, v), coordinate(a, drop),
                                         coordinate(b, u), coordinate(b, v), coordinate(b, drop),
                                         coordinate(c, u), coordinate(c, v), coordinate(c, drop),
                                         coordinate(d, u), coordinate(d, v), coordinate(d, drop)});
  std::array<std::array<mpz_class, 3>, 3> m;
  for (int r = 0; r < 3; ++r) {
    const mpz_class du = w[3 * r] - w[9];
    const mpz_class dv = w[3 * r + 1] - w[10];
    const mpz_class dw = w[3 * r + 2] - w[11];
    m[r] = {du, dv, du * du + dv * dv + dw * dw};
  }
  return sign_of(
      det3(m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2]));
}

}  // namespace dtlab::predicates
