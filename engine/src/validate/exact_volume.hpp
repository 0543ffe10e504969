#pragma once
// The validator's global check (docs/design.md, "Validation"): six times the exact volume of the
// convex hull of the input, computed independently of the mesh (CGAL's convex_hull_3 with exact
// predicates: its facets are triangles of input points), against six times the exact sum of the
// tetrahedra's signed volumes. Both are integers on one power-of-two grid that holds every input
// coordinate exactly, so the comparison is exact for every finite double.
#include <gmpxx.h>

#include <array>
#include <cstdint>
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

// A face of the mesh by its sorted vertex ids, and the sum over the tetrahedra that have it of +1
// where their outward triple (kFaceVertex) is an even permutation of `key`, -1 where it is odd.
struct SignedFace {
  std::array<std::uint32_t, 3> key;
  std::int32_t multiplicity;
};

// 6 * the sum of the tetrahedra's signed volumes det[b - a; c - a; d - a], from their faces: each
// such determinant is the sum of det[p - o; q - o; r - o] over the tetrahedron's four outward
// triples (p, q, r), for any fixed point o, so the total is the sum over the distinct faces of
// multiplicity * det[key - o]. A face of two consistent tetrahedra has multiplicity 0: only the
// boundary and the broken faces are computed (docs/design.md, "The validator").
mpz_class six_mesh_volume(const std::vector<predicates::Point3>& points,
                          const std::vector<SignedFace>& faces, const ExactGrid& grid);

// 6 * the volume of the convex hull of the points (0 when their affine dimension is below 3).
mpz_class six_hull_volume(const std::vector<predicates::Point3>& points, const ExactGrid& grid);

}  // namespace dtlab::engine
