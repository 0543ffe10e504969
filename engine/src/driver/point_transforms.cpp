// The driver's whole-array steps (point_transforms.hpp).
#include "driver/point_transforms.hpp"

#include <algorithm>
#include <cmath>

#include "support/parallel_ranges.hpp"
#include "support/populate_pages.hpp"

namespace dtlab::engine {

// Each set of equal input points is named by its lowest index (as SharedMesh::finite_tetrahedra
// does in the engine's own numbering, which the walk mode's renumbering changes).
void name_duplicates_by_lowest_index(const std::vector<Point3>& input,
                                     std::vector<Tetrahedron>& tets) {
  std::vector<std::uint32_t> by_point(input.size());
  for (std::size_t i = 0; i < by_point.size(); ++i) by_point[i] = static_cast<std::uint32_t>(i);
  auto less = [&](std::uint32_t a, std::uint32_t b) {
    const Point3& p = input[a];
    const Point3& q = input[b];
    if (p.x != q.x) return p.x < q.x;
    if (p.y != q.y) return p.y < q.y;
    if (p.z != q.z) return p.z < q.z;
    return a < b;
  };
  std::sort(by_point.begin(), by_point.end(), less);
  std::vector<std::uint32_t> lowest(input.size());
  for (std::size_t i = 0; i < by_point.size(); ++i) {
    const bool same = i > 0 && input[by_point[i]] == input[by_point[i - 1]];
    lowest[by_point[i]] = same ? lowest[by_point[i - 1]] : by_point[i];
  }
  for (auto& t : tets) {
    for (auto& v : t) {
      if (v < lowest.size()) v = lowest[v];
    }
  }
}

// Every coordinate times 2^exponent, for a lossless scaling (RangeScaling::lossless: every result
// a normal double) and its inverse: two multiplications by powers of two that are normal doubles
// (|exponent| <= 1200, so each half is), and exact, since every value between c and c 2^exponent
// keeps c's significand and lies in the range of doubles. The same numbers as std::ldexp, without
// its library call per coordinate.
void scale_points(std::vector<Point3>& points, int exponent, int threads) {
  const double first = std::ldexp(1.0, exponent / 2);
  const double second = std::ldexp(1.0, exponent - exponent / 2);
  in_parallel_ranges(points.size(), threads, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i) {
      Point3& p = points[i];
      p = {(p.x * first) * second, (p.y * first) * second, (p.z * first) * second};
    }
  });
}

// points[i] = old points[from[i]] for a permutation `from`. Through a second array: this runs
// before the store grows or after it is released, below the run's peak either way, and a gather
// is faster than following the permutation's cycles in place (and splits over threads).
void permute(std::vector<Point3>& points, const std::vector<std::uint32_t>& from, int threads) {
  std::vector<Point3> gathered = populated_vector<Point3>(points.size(), threads);
  in_parallel_ranges(points.size(), threads, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i) gathered[i] = points[from[i]];
  });
  points.swap(gathered);
}

// The inverse: points[from[i]] = old points[i] (each thread writes distinct entries).
void unpermute(std::vector<Point3>& points, const std::vector<std::uint32_t>& from, int threads) {
  std::vector<Point3> scattered = populated_vector<Point3>(points.size(), threads);
  in_parallel_ranges(points.size(), threads, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i) scattered[from[i]] = points[i];
  });
  points.swap(scattered);
}

}  // namespace dtlab::engine
