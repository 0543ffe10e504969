// The distributions of the points among the threads (paper Sect. 6): static pieces of the random
// order, strips and blocks by median splits.
#include "methods/distribution.hpp"

#include <algorithm>
#include <cassert>

#include "dtlab/engine/options.hpp"

namespace dtlab::engine {
namespace {

using predicates::Point3;

// Splits `ids` (kept in their order) into `parts` groups of equal size by the coordinate `axis`
// (median splits), recursively alternating axes for blocks.
void split_by_median(const std::vector<Point3>& points, std::vector<std::uint32_t> ids, int parts,
                     int axis, int axes, std::vector<std::vector<std::uint32_t>>& out) {
  if (parts <= 1) {
    out.push_back(std::move(ids));
    return;
  }
  const int left_parts = parts / 2;
  std::vector<std::uint32_t> sorted = ids;
  const std::size_t cut =
      ids.size() * static_cast<std::size_t>(left_parts) / static_cast<std::size_t>(parts);
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(cut), sorted.end(),
                   [&](std::uint32_t a, std::uint32_t b) {
                     const double ca = predicates::coordinate(points[a], axis);
                     const double cb = predicates::coordinate(points[b], axis);
                     return ca < cb || (ca == cb && a < b);
                   });
  // Membership by rank, so that each side keeps the random order of `ids`.
  std::vector<char> left(points.size(), 0);
  for (std::size_t i = 0; i < cut; ++i) left[sorted[i]] = 1;
  std::vector<std::uint32_t> a;
  std::vector<std::uint32_t> b;
  for (const std::uint32_t v : ids) (left[v] ? a : b).push_back(v);
  const int next_axis = (axis + 1) % axes;
  split_by_median(points, std::move(a), left_parts, next_axis, axes, out);
  split_by_median(points, std::move(b), parts - left_parts, next_axis, axes, out);
}

}  // namespace

std::vector<std::vector<std::uint32_t>> distribute(const std::vector<Point3>& points,
                                                   const std::vector<std::uint32_t>& order,
                                                   Distribution distribution, int threads) {
  assert(distribution != Distribution::Auto);
  std::vector<std::vector<std::uint32_t>> parts;
  if (distribution == Distribution::Strips || distribution == Distribution::Blocks) {
    split_by_median(points, order, threads, 0, distribution == Distribution::Strips ? 1 : 3, parts);
    return parts;
  }
  // Static: contiguous pieces of the random permutation.
  const std::size_t n = order.size();
  for (int i = 0; i < threads; ++i) {
    const std::size_t begin = n * static_cast<std::size_t>(i) / static_cast<std::size_t>(threads);
    const std::size_t end = n * static_cast<std::size_t>(i + 1) / static_cast<std::size_t>(threads);
    parts.emplace_back(order.begin() + static_cast<std::ptrdiff_t>(begin),
                       order.begin() + static_cast<std::ptrdiff_t>(end));
  }
  return parts;
}

Distribution effective_distribution(const TriangulateOptions& options) {
  if (options.distribution != Distribution::Auto) return options.distribution;
  return options.location == Location::Walk ? Distribution::Blocks : Distribution::Static;
}

}  // namespace dtlab::engine
