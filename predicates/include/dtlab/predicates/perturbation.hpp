#pragma once
// Symbolic perturbation of the lifting map (Devillers and Teillaud, "Perturbations for Delaunay
// and weighted Delaunay 3D triangulations", CGTA 2011), on top of any kernel.
//
// Scheme: the lifted coordinate |p|^2 of every point p becomes |p|^2 + eps^rank(p), where the
// lexicographically largest point (x, then y, then z) gets the largest perturbation. Points do
// not move in E3, so orientations stay exact and unperturbed: no flat tetrahedron can appear.
// An insphere tie (exactly cospherical points) is then decided by the first nonzero coefficient
// of the perturbed determinant, taken in decreasing perturbation order; each coefficient is an
// orient3d of four of the five points. The order depends on coordinates only, so the resulting
// triangulation does not depend on insertion order, seed, method or thread count.
#include <array>
#include <bit>

#include "dtlab/predicates/point.hpp"

namespace dtlab::predicates {

// Calls visit(i) for the indices i of the N points of a test from the largest perturbation to the
// smallest, until one call returns nonzero, and returns that value (0 when none did). The order
// is found lazily, one largest remaining point at a time, so a tie that an early coefficient
// decides does not pay for a whole sort. No branch depends on the comparisons: on grids, points
// share coordinates, and a sort's branches were mispredicted (9 % of a grid run's samples).
template <std::size_t N, class Visit>
int in_perturbation_order(const std::array<const Point3*, N>& pts, Visit visit) {
  static_assert(N <= 8);
  unsigned left = (1U << N) - 1;
  while (left != 0) {
    int largest = std::countr_zero(left);
    for (unsigned rest = left & (left - 1); rest != 0; rest &= rest - 1) {
      const int i = std::countr_zero(rest);
      const int larger =
          -static_cast<int>(lexicographically_less_branchless(*pts[largest], *pts[i]));
      largest ^= (largest ^ i) & larger;  // largest = i where pts[i] is larger
    }
    if (const int s = visit(largest); s != 0) return s;
    left &= ~(1U << largest);
  }
  return 0;
}

// The perturbed sign of an insphere tie (K::insphere(a, b, c, d, e) == 0): the first nonzero
// coefficient. Kept out of line, so that the callers of insphere_perturbed stay small where ties
// are rare.
template <class K>
[[gnu::noinline]] int insphere_tie_broken(const Point3& a, const Point3& b, const Point3& c,
                                          const Point3& d, const Point3& e) {
  const std::array<const Point3*, 5> pts{&a, &b, &c, &d, &e};
  return in_perturbation_order(pts, [&](int i) {
    switch (i) {
      case 4:
        return -K::orient3d(a, b, c, d);  // raising e's lift moves e outside
      case 3:
        return K::orient3d(a, b, c, e);  // by antisymmetry, swapping d and e
      case 2:
        return K::orient3d(a, b, e, d);
      case 1:
        return K::orient3d(a, e, c, d);
      default:
        return K::orient3d(e, b, c, d);
    }
  });
}

// insphere with ties broken by the perturbation. Never 0 for five distinct points when abcd is
// not flat (0 only for a flat abcd or repeated points).
template <class K>
int insphere_perturbed(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                       const Point3& e) {
  const int s = K::insphere(a, b, c, d, e);
  if (s != 0) return s;
  return insphere_tie_broken<K>(a, b, c, d, e);
}

// A projection (dropped axis) in which triangle abc is not degenerate, and abc's orientation
// there; {-1, 0} when a, b, c are collinear.
template <class K>
std::array<int, 2> nondegenerate_projection(const Point3& a, const Point3& b, const Point3& c) {
  for (const int drop : {2, 0, 1}) {
    const int o = K::orient2d(a, b, c, drop);
    if (o != 0) return {drop, o};
  }
  return {-1, 0};
}

// For d coplanar with the non-collinear triangle abc: +1 if d is strictly inside the circle
// through a, b, c, 0 on it, -1 outside.
template <class K>
int coplanar_incircle(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  const auto [drop, o] = nondegenerate_projection<K>(a, b, c);
  if (o == 0) return 0;
  return K::incircle_lifted(a, b, c, d, drop) * o;
}

// "insphere" of the infinite tetrahedron (a, b, c, inf), whose vertex at infinity lies on the
// positive side of abc (orient3d(a, b, c, p) > 0 for p beyond the face). e conflicts (+1) iff it
// lies strictly beyond the plane abc, or on it and strictly inside the circle abc; cocircular
// ties are broken by the same lifting perturbation as insphere_perturbed, seen as the limit of a
// finite fifth vertex that moves to infinity (its own coefficient vanishes on the plane).
template <class K>
int infinite_insphere_perturbed(const Point3& a, const Point3& b, const Point3& c,
                                const Point3& e) {
  const int side = K::orient3d(a, b, c, e);
  if (side != 0) return side;
  const std::array<int, 2> projection = nondegenerate_projection<K>(a, b, c);
  const int drop = projection[0];  // plain names: a lambda below captures them
  const int o = projection[1];
  if (o == 0) return 0;
  const int in_circle = K::incircle_lifted(a, b, c, e, drop) * o;
  if (in_circle != 0) return in_circle;
  const std::array<const Point3*, 4> pts{&a, &b, &c, &e};
  return in_perturbation_order(pts, [&](int i) {
    switch (i) {
      case 3:
        return -1;  // raising e's lift moves e outside
      case 2:
        return K::orient2d(a, b, e, drop) * o;
      case 1:
        return K::orient2d(a, e, c, drop) * o;
      default:
        return K::orient2d(e, b, c, drop) * o;
    }
  });
}

}  // namespace dtlab::predicates
