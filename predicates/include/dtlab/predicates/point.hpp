#pragma once

namespace dtlab::predicates {

// A point in E3. Plain aggregate so that arrays of points are flat and trivially copyable.
struct Point3 {
  double x;
  double y;
  double z;
};

inline bool operator==(const Point3& a, const Point3& b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

// Lexicographic order (x, then y, then z): the symbolic perturbation ranks points by it.
inline bool lexicographically_less(const Point3& a, const Point3& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

// Coordinate of `p` along axis 0, 1 or 2.
inline double coordinate(const Point3& p, int axis) {
  return axis == 0 ? p.x : (axis == 1 ? p.y : p.z);
}

}  // namespace dtlab::predicates
