#pragma once
// The validator's global check (docs/design.md, "Validation"): six times the exact volume of the
// convex hull of the input, computed independently of the mesh (CGAL's convex_hull_3 with exact
// predicates: its facets are triangles of input points), against six times the exact sum of the
// tetrahedra's signed volumes. Both are integers on one power-of-two grid that holds every input
// coordinate exactly, so the comparison is exact for every finite double.
#include <gmpxx.h>

#include <array>
#include <vector>

#include "dtlab/engine/tetrahedron.hpp"
#include "dtlab/predicates/point.hpp"

namespace dtlab::engine {

class ExactGrid {
 public:
  // The grid unit is the smallest 2^k that divides every coordinate (finite input only).
  explicit ExactGrid(const std::vector<predicates::Point3>& points);
  [[nodiscard]] std::array<mpz_class, 3> point(const predicates::Point3& p) const;

 private:
  [[nodiscard]] mpz_class coordinate(double c) const;
  int unit_exponent_ = 0;
};

// 6 * det[b - a; c - a; d - a] summed over the tetrahedra marked usable.
mpz_class six_mesh_volume(const std::vector<predicates::Point3>& points,
                          const std::vector<Tetrahedron>& tets, const std::vector<bool>& usable,
                          const ExactGrid& grid);

// 6 * the volume of the convex hull of the points (0 when their affine dimension is below 3).
mpz_class six_hull_volume(const std::vector<predicates::Point3>& points, const ExactGrid& grid);

}  // namespace dtlab::engine
