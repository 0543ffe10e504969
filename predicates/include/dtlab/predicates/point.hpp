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
// The same order without branches: the perturbation's order compares points that often share a
// coordinate (grids), where the branches above are mispredicted.
inline bool lexicographically_less_branchless(const Point3& a, const Point3& b) {
  const int x_less = static_cast<int>(a.x < b.x);
  const int x_equal = static_cast<int>(a.x == b.x);
  const int y_less = static_cast<int>(a.y < b.y);
  const int y_equal = static_cast<int>(a.y == b.y);
  const int z_less = static_cast<int>(a.z < b.z);
  return (x_less | (x_equal & (y_less | (y_equal & z_less)))) != 0;
}

// Coordinate of `p` along axis 0, 1 or 2.
inline double coordinate(const Point3& p, int axis) {
  return axis == 0 ? p.x : (axis == 1 ? p.y : p.z);
}

}  // namespace dtlab::predicates
