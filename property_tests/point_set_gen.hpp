#pragma once
// RapidCheck generators of point sets for every family, built from small integers mapped to
// doubles so that degenerate cases (ties, coplanar and cospherical subsets, duplicates) are
// frequent and shrink toward small counterexamples.
#include <rapidcheck.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ostream>
#include <string>
#include <vector>

#include "dtlab/predicates/point.hpp"

namespace dtlab::property {

using predicates::Point3;

struct PointSetCase {
  std::string family;
  std::vector<Point3> points;
};

// Full precision, one point per line in .xyz form, so a counterexample can be pasted into a
// regression file as it is.
inline void showValue(const PointSetCase& c, std::ostream& os) {
  os << c.family << " (" << c.points.size() << " points):\n";
  char line[96];
  for (const auto& p : c.points) {
    std::snprintf(line, sizeof line, "%.17g %.17g %.17g\n", p.x, p.y, p.z);
    os << line;
  }
}

inline rc::Gen<Point3> small_integer_point(int range) {
  return rc::gen::map(rc::gen::tuple(rc::gen::inRange(0, range), rc::gen::inRange(0, range),
                                     rc::gen::inRange(0, range)),
                      [](const std::tuple<int, int, int>& t) {
                        return Point3{static_cast<double>(std::get<0>(t)),
                                      static_cast<double>(std::get<1>(t)),
                                      static_cast<double>(std::get<2>(t))};
                      });
}

// Every integer point on the sphere x^2 + y^2 + z^2 = 125 (around a hundred): any five of them
// are exactly cospherical, so every insphere call among them is a tie for the perturbation.
inline const std::vector<Point3>& exact_sphere_points() {
  static const std::vector<Point3> points = [] {
    constexpr int r2 = 125;
    std::vector<Point3> v;
    for (int x = -11; x <= 11; ++x) {
      for (int y = -11; y <= 11; ++y) {
        for (int z = -11; z <= 11; ++z) {
          if (x * x + y * y + z * z == r2) {
            v.push_back({static_cast<double>(x), static_cast<double>(y), static_cast<double>(z)});
          }
        }
      }
    }
    return v;
  }();
  return points;
}

// Maps integer points into a family's shape: exact transformations keep the degeneracies (uniform
// and sphere round on purpose, to be nearly degenerate).
inline std::vector<Point3> shape(const std::string& family, std::vector<Point3> pts, int salt) {
  for (auto& p : pts) {
    if (family == "uniform") {
      p = {p.x + 0.001 * std::sin(1.0 + p.y + salt), p.y + 0.001 * std::cos(p.z * 3 + salt),
           p.z + 0.0007 * p.x};
    } else if (family == "planes") {
      if (static_cast<int>(p.x) % 2 == 0) p.z = 2.0;  // half on the plane z = 2
    } else if (family == "sphere") {
      // Integer points scaled onto the unit sphere (rounded): nearly cospherical.
      const double r = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
      if (r > 0) p = {p.x / r, p.y / r, p.z / r};
    } else if (family == "lattice") {
      p = {p.x + 0x1p30, p.y + 0x1p30, p.z + 0x1p30};
    } else if (family == "tiny") {
      // 2^-500 (about 3e-151) and 2^500: powers of two, so the scaling is exact and keeps every
      // tie (a factor like 1e-150 would round k * 1e-150 and break some of them).
      p = {p.x * 0x1p-500, p.y * 0x1p-500, p.z * 0x1p-500};
    } else if (family == "huge") {
      p = {p.x * 0x1p500, p.y * 0x1p500, p.z * 0x1p500};
    } else if (family == "wide") {
      // Magnitudes 2^1076 apart: some x are subnormal (exactly k * 2^-1074), so even after the
      // engine's lossless scaling the input leaves the expansion range and the adaptive and
      // filtered kernels must hand undecided calls to GMP. Nearly coplanar on x = 0 besides.
      if (static_cast<int>(p.y) % 3 == 0) p.x = std::ldexp(p.x, -1074);
    } else if (family == "cospherical") {
      // Exactly cospherical: the integer point picks one of the sphere's (repeats are
      // duplicates, which the engine names by their lowest index).
      const auto& on = exact_sphere_points();
      const auto pick = static_cast<std::size_t>(p.x * 49 + p.y * 7 + p.z) % on.size();
      p = on[pick];
    } else if (family == "near-duplicates") {
      // Away from 0 (exact), so that a few ulps either way are normal numbers; point_set_case
      // then adds nudged copies (near_duplicate_copies).
      p = {p.x + 1.0, p.y + 1.0, p.z + 1.0};
    }
    // "grid" and "duplicates" keep the integers (ties and repeats are already frequent).
  }
  return pts;
}

// v moved by |ulps| units in the last place, up for ulps > 0 and down for ulps < 0.
inline double ulps_away(double v, int ulps) {
  const double toward = ulps > 0 ? HUGE_VAL : -HUGE_VAL;
  for (int i = 0; i < std::abs(ulps); ++i) v = std::nextafter(v, toward);
  return v;
}

// Appends, for every other point, a copy moved by 1 to 3 ulps in one, two or three coordinates,
// up or down (as generators/ does for its near-duplicates family): each copy is a real near
// duplicate of a point of the set, a few ulps away from it, never equal to it.
inline void near_duplicate_copies(std::vector<Point3>& pts, int salt) {
  const std::size_t n = pts.size();
  for (std::size_t i = 0; i < n; i += 2) {
    const int k = static_cast<int>(i / 2) + salt;
    const int ulps = (1 + k % 3) * (k % 2 == 0 ? 1 : -1);
    Point3 q = pts[i];
    q.x = ulps_away(q.x, ulps);
    if (k % 3 != 0) q.y = ulps_away(q.y, -ulps);
    if (k % 4 == 3) q.z = ulps_away(q.z, ulps);
    pts.push_back(q);
  }
}

inline const std::vector<std::string>& families() {
  static const std::vector<std::string> f{"uniform",     "grid",       "planes",         "sphere",
                                          "cospherical", "lattice",    "tiny",           "huge",
                                          "wide",        "duplicates", "near-duplicates"};
  return f;
}

inline rc::Gen<PointSetCase> point_set_case() {
  return rc::gen::mapcat(rc::gen::elementOf(families()), [](const std::string& family) {
    const int range = family == "grid" || family == "duplicates" ? 4 : 7;
    return rc::gen::map(
        rc::gen::pair(rc::gen::container<std::vector<Point3>>(small_integer_point(range)),
                      rc::gen::inRange(0, 100)),
        [family](const std::pair<std::vector<Point3>, int>& v) {
          std::vector<Point3> pts = v.first;
          if (family == "duplicates") {
            const std::size_t n = pts.size();
            for (std::size_t i = 0; i < n; i += 2) pts.push_back(pts[i]);
          }
          pts = shape(family, pts, v.second);
          if (family == "near-duplicates") near_duplicate_copies(pts, v.second);
          return PointSetCase{family, pts};
        });
  });
}

}  // namespace dtlab::property
