// Exact volumes for the validator's global check (exact_volume.hpp). CGAL's headers stay in this
// translation unit.
#include "validate/exact_volume.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <array>
#include <climits>
#include <cmath>
#include <cstdint>

#include "dtlab/engine/point_set_info.hpp"
#include "dtlab/predicates/kernels.hpp"

namespace dtlab::engine {
namespace {

using Grid3 = std::array<mpz_class, 3>;

mpz_class det3(const Grid3& u, const Grid3& v, const Grid3& w) {
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
         u[2] * (v[0] * w[1] - v[1] * w[0]);
}

Grid3 minus(const Grid3& p, const Grid3& q) {
  return {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
}

// c = m * 2^(e - 53) with an integer m of at most 53 bits (frexp); 0 has no exponent.
int lowest_exponent(double c) {
  int e = 0;
  std::frexp(c, &e);
  return e - 53;
}

}  // namespace

ExactGrid::ExactGrid(const std::vector<predicates::Point3>& points) : unit_exponent_(INT_MAX) {
  for (const predicates::Point3& p : points) {
    for (const double c : {p.x, p.y, p.z}) {
      if (c != 0.0) unit_exponent_ = std::min(unit_exponent_, lowest_exponent(c));
    }
  }
  if (unit_exponent_ == INT_MAX) unit_exponent_ = 0;
}

mpz_class ExactGrid::coordinate(double c) const {
  if (c == 0.0) return 0;
  int e = 0;
  const double m = std::frexp(c, &e);  // c = m 2^e, 0.5 <= |m| < 1
  mpz_class v(static_cast<long>(std::ldexp(m, 53)));
  mpz_mul_2exp(v.get_mpz_t(), v.get_mpz_t(), static_cast<mp_bitcnt_t>(e - 53 - unit_exponent_));
  return v;
}

std::array<mpz_class, 3> ExactGrid::point(const predicates::Point3& p) const {
  return {coordinate(p.x), coordinate(p.y), coordinate(p.z)};
}

mpz_class six_mesh_volume(const std::vector<predicates::Point3>& points,
                          const std::vector<SignedFace>& faces, const ExactGrid& grid) {
  if (points.empty()) return 0;
  const Grid3 o = grid.point(points.front());
  mpz_class sum = 0;
  for (const SignedFace& f : faces) {
    if (f.multiplicity == 0) continue;
    const Grid3 p = minus(grid.point(points[f.key[0]]), o);
    const Grid3 q = minus(grid.point(points[f.key[1]]), o);
    const Grid3 r = minus(grid.point(points[f.key[2]]), o);
    sum += static_cast<long>(f.multiplicity) * det3(p, q, r);
  }
  return sum;
}

mpz_class six_hull_volume(const std::vector<predicates::Point3>& points, const ExactGrid& grid) {
  std::vector<std::uint32_t> order(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::uint32_t>(i);
  if (find_simplex(points, order).dimension < 3) return 0;
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  // The hull of the extreme points in 26 directions lies inside the hull of all points, so a
  // point strictly inside it (exactly on the inner side of each of its facets) is interior to
  // the hull and no vertex of it: leaving those points out changes the hull's running time only.
  std::vector<Kernel::Point_3> extreme;
  for (int dx = -1; dx <= 1; ++dx) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dz = -1; dz <= 1; ++dz) {
        if (dx == 0 && dy == 0 && dz == 0) continue;
        const auto reach = [&](const predicates::Point3& p) {
          return dx * p.x + dy * p.y + dz * p.z;
        };
        const predicates::Point3* best = &points.front();
        for (const predicates::Point3& p : points) {
          if (reach(p) > reach(*best)) best = &p;
        }
        extreme.emplace_back(best->x, best->y, best->z);
      }
    }
  }
  Mesh inner;
  CGAL::convex_hull_3(extreme.begin(), extreme.end(), inner);
  // Each facet of the inner hull and the sign of orient3d for a point on its inner side (that of
  // an inner-hull vertex off the facet's plane); no facets where the extreme points are flat.
  struct Facet {
    std::array<predicates::Point3, 3> corner;
    int inner_sign;
  };
  std::vector<Facet> facets;
  auto to_point = [](const Kernel::Point_3& q) { return predicates::Point3{q.x(), q.y(), q.z()}; };
  bool solid = inner.number_of_faces() >= 4;
  for (const auto face : inner.faces()) {
    Facet f{};
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(inner.halfedge(face), inner)) {
      if (k < 3) f.corner[static_cast<std::size_t>(k)] = to_point(inner.point(v));
      ++k;
    }
    solid = solid && k == 3;
    for (const auto v : inner.vertices()) {
      const int side = predicates::AdaptiveKernel::orient3d(f.corner[0], f.corner[1], f.corner[2],
                                                            to_point(inner.point(v)));
      if (side != 0) f.inner_sign = side;
    }
    solid = solid && f.inner_sign != 0;
    facets.push_back(f);
  }
  auto strictly_inside = [&](const predicates::Point3& p) {
    for (const Facet& f : facets) {
      if (predicates::AdaptiveKernel::orient3d(f.corner[0], f.corner[1], f.corner[2], p) !=
          f.inner_sign) {
        return false;
      }
    }
    return true;
  };
  std::vector<Kernel::Point_3> input;
  for (const predicates::Point3& p : points) {
    if (!solid || !strictly_inside(p)) input.emplace_back(p.x, p.y, p.z);
  }
  Mesh hull;
  CGAL::convex_hull_3(input.begin(), input.end(), hull);
  // The hull's facets are triangles of input points, consistently oriented: the cones from any
  // fixed point add up to +-6 times the volume.
  auto on_grid = [&](const Kernel::Point_3& q) { return grid.point({q.x(), q.y(), q.z()}); };
  const Grid3 apex = grid.point(points.front());
  mpz_class sum = 0;
  for (const auto face : hull.faces()) {
    std::array<Grid3, 3> corner;
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(hull.halfedge(face), hull)) {
      if (k < 3) corner[static_cast<std::size_t>(k)] = on_grid(hull.point(v));
      ++k;
    }
    if (k != 3) return -1;  // not a triangle: impossible for convex_hull_3's output
    sum += det3(minus(corner[0], apex), minus(corner[1], apex), minus(corner[2], apex));
  }
  return abs(sum);
}

}  // namespace dtlab::engine
