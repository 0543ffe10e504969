// Stage D of the adaptive and filtered kernels: exact expansions of the exact differences.
#include "exact_stage.hpp"

namespace dtlab::predicates::detail {
namespace {

// The exact differences p - q of all three coordinates.
struct ExactVector {
  Fixed<2> x, y, z;
};
ExactVector exact_vector(const Point3& p, const Point3& q) {
  return {exact_difference(p.x, q.x), exact_difference(p.y, q.y), exact_difference(p.z, q.z)};
}

// The same as growable expansions, with the squared length.
struct LiftedVector {
  Bounded x, y, z, lift;
};
LiftedVector lifted_vector(const Point3& p, const Point3& q) {
  const ExactVector v = exact_vector(p, q);
  LiftedVector r{Bounded(v.x), Bounded(v.y), Bounded(v.z), Bounded()};
  r.lift = (r.x * r.x + r.y * r.y) + r.z * r.z;
  return r;
}

Bounded exact_coordinate_difference(const Point3& p, const Point3& q, int axis) {
  return Bounded(exact_difference(coordinate(p, axis), coordinate(q, axis)));
}

}  // namespace

Fixed<192> orient3d_exact(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  const ExactVector u = exact_vector(a, d);
  const ExactVector v = exact_vector(b, d);
  const ExactVector w = exact_vector(c, d);
  // sum over cyclic (r, s, t) of r_x (s_z t_y - s_y t_z)
  const Fixed<16> minor_vw = v.z * w.y - v.y * w.z;
  const Fixed<16> minor_wu = w.z * u.y - w.y * u.z;
  const Fixed<16> minor_uv = u.z * v.y - u.y * v.z;
  return (u.x * minor_vw + v.x * minor_wu) + w.x * minor_uv;
}

int orient3d_exact_sign(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  return orient3d_exact(a, b, c, d).sign();
}

int orient3d_centroid_exact_sign(const Point3& a, const Point3& b, const Point3& c,
                                 const Tetrahedron4& v) {
  return ((orient3d_exact(a, b, c, v[0]) + orient3d_exact(a, b, c, v[1])) +
          (orient3d_exact(a, b, c, v[2]) + orient3d_exact(a, b, c, v[3])))
      .sign();
}

int orient2d_exact_sign(const Point3& a, const Point3& b, const Point3& c, int drop) {
  const int iu = (drop + 1) % 3;
  const int iv = (drop + 2) % 3;
  const Fixed<2> bu = exact_difference(coordinate(b, iu), coordinate(a, iu));
  const Fixed<2> bv = exact_difference(coordinate(b, iv), coordinate(a, iv));
  const Fixed<2> cu = exact_difference(coordinate(c, iu), coordinate(a, iu));
  const Fixed<2> cv = exact_difference(coordinate(c, iv), coordinate(a, iv));
  return (bu * cv - bv * cu).sign();
}

int incircle_lifted_exact_sign(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                               int drop) {
  const int iu = (drop + 1) % 3;
  const int iv = (drop + 2) % 3;
  const Bounded ua = exact_coordinate_difference(a, d, iu);
  const Bounded va = exact_coordinate_difference(a, d, iv);
  const Bounded ub = exact_coordinate_difference(b, d, iu);
  const Bounded vb = exact_coordinate_difference(b, d, iv);
  const Bounded uc = exact_coordinate_difference(c, d, iu);
  const Bounded vc = exact_coordinate_difference(c, d, iv);
  const Bounded lift_a = lifted_vector(a, d).lift;
  const Bounded lift_b = lifted_vector(b, d).lift;
  const Bounded lift_c = lifted_vector(c, d).lift;
  const Bounded det =
      (lift_a * (ub * vc - uc * vb) + lift_b * (uc * va - ua * vc)) + lift_c * (ua * vb - ub * va);
  return det.overflowed() ? kUndecided : det.sign();
}

int insphere_exact_sign(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                        const Point3& e) {
  const LiftedVector r0 = lifted_vector(a, e);
  const LiftedVector r1 = lifted_vector(b, e);
  const LiftedVector r2 = lifted_vector(c, e);
  const LiftedVector r3 = lifted_vector(d, e);
  auto xy = [](const LiftedVector& p, const LiftedVector& q) { return p.x * q.y - q.x * p.y; };
  auto zl = [](const LiftedVector& p, const LiftedVector& q) {
    return p.z * q.lift - q.z * p.lift;
  };
  const Bounded kept = xy(r0, r2) * zl(r1, r3) + xy(r1, r3) * zl(r0, r2);
  const Bounded taken = (xy(r0, r1) * zl(r2, r3) + xy(r2, r3) * zl(r0, r1)) +
                        (xy(r0, r3) * zl(r1, r2) + xy(r1, r2) * zl(r0, r3));
  const Bounded det = kept - taken;
  return det.overflowed() ? kUndecided : det.sign();
}

}  // namespace dtlab::predicates::detail
