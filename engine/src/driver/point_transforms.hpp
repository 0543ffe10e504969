#pragma once
// The driver's whole-array steps on the points and the output: the exact power-of-two scaling and
// the walk mode's renumbering of the points (undone before they go back to the caller), and the
// naming of equal points by their lowest input index.
#include <cstdint>
#include <vector>

#include "dtlab/engine/tetrahedron.hpp"
#include "dtlab/predicates/point.hpp"

namespace dtlab::engine {

using predicates::Point3;

// Every coordinate times 2^exponent, exactly (a lossless scaling: RangeScaling::lossless).
void scale_points(std::vector<Point3>& points, int exponent, int threads);
// points[i] = old points[from[i]] for a permutation `from`.
void permute(std::vector<Point3>& points, const std::vector<std::uint32_t>& from, int threads);
// The inverse: points[from[i]] = old points[i].
void unpermute(std::vector<Point3>& points, const std::vector<std::uint32_t>& from, int threads);
// Each set of equal input points named by its lowest index in `tets`.
void name_duplicates_by_lowest_index(const std::vector<Point3>& input,
                                     std::vector<Tetrahedron>& tets);

}  // namespace dtlab::engine
