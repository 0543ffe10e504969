#pragma once
// Input families for predicate tests: random, near-degenerate (a few ulps off a plane or a
// sphere), exactly degenerate (grids), large offsets and tiny scales.
#include <rapidcheck.h>

#include <array>
#include <cmath>

#include "dtlab/predicates/point.hpp"

namespace dtlab::test {

using predicates::Point3;

inline Point3 add(const Point3& a, const Point3& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}

// A double in [0, 1) from 30 random bits.
inline rc::Gen<double> unit_double() {
  return rc::gen::map(rc::gen::inRange<int>(0, 1 << 30),
                      [](int v) { return std::ldexp(static_cast<double>(v), -30); });
}

inline rc::Gen<Point3> unit_point() {
  return rc::gen::apply(
      [](double x, double y, double z) {
        return Point3{x, y, z};
      },
      unit_double(), unit_double(), unit_double());
}

// Small integer grid points, so exact ties are frequent.
inline rc::Gen<Point3> grid_point() {
  return rc::gen::map(
      rc::gen::tuple(rc::gen::inRange(-3, 4), rc::gen::inRange(-3, 4), rc::gen::inRange(-3, 4)),
      [](const std::tuple<int, int, int>& t) {
        return Point3{static_cast<double>(std::get<0>(t)), static_cast<double>(std::get<1>(t)),
                      static_cast<double>(std::get<2>(t))};
      });
}

// Moves every coordinate by `ulps` units in the last place.
inline Point3 nudge(Point3 p, int ulps) {
  for (int i = 0; i < std::abs(ulps); ++i) {
    const double dir = ulps > 0 ? INFINITY : -INFINITY;
    p = {std::nextafter(p.x, dir), std::nextafter(p.y, dir), std::nextafter(p.z, dir)};
  }
  return p;
}

// A point near the plane abc (rounded affine combination), nudged by a few ulps.
inline Point3 near_plane(const Point3& a, const Point3& b, const Point3& c, double s, double t,
                         int ulps) {
  const Point3 p{a.x + s * (b.x - a.x) + t * (c.x - a.x), a.y + s * (b.y - a.y) + t * (c.y - a.y),
                 a.z + s * (b.z - a.z) + t * (c.z - a.z)};
  return nudge(p, ulps);
}

// A point near the sphere with centre c and radius r in direction (u, v) (rounded), nudged.
inline Point3 near_sphere(const Point3& c, double r, double u, double v, int ulps) {
  const double theta = 2.0 * M_PI * u;
  const double z = 2.0 * v - 1.0;
  const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
  return nudge({c.x + r * s * std::cos(theta), c.y + r * s * std::sin(theta), c.z + r * z}, ulps);
}

}  // namespace dtlab::test
