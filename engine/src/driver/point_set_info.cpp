#include "dtlab/engine/point_set_info.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "dtlab/predicates/kernels.hpp"
#include "dtlab/predicates/valid_range.hpp"

namespace dtlab::engine {

using predicates::ExactKernel;

SimplexSearch find_simplex(const std::vector<Point3>& points,
                           const std::vector<std::uint32_t>& order) {
  SimplexSearch result;
  if (order.empty()) return result;
  std::array<std::uint32_t, 4> s{order[0], 0, 0, 0};
  result.dimension = 0;
  std::size_t i = 1;
  for (; i < order.size() && result.dimension == 0; ++i) {
    if (!(points[order[i]] == points[s[0]])) {
      s[1] = order[i];
      result.dimension = 1;
    }
  }
  for (; i < order.size() && result.dimension == 1; ++i) {
    const Point3& a = points[s[0]];
    const Point3& b = points[s[1]];
    const Point3& c = points[order[i]];
    if (ExactKernel::orient2d(a, b, c, 0) != 0 || ExactKernel::orient2d(a, b, c, 1) != 0 ||
        ExactKernel::orient2d(a, b, c, 2) != 0) {
      s[2] = order[i];
      result.dimension = 2;
    }
  }
  for (; i < order.size() && result.dimension == 2; ++i) {
    if (ExactKernel::orient3d(points[s[0]], points[s[1]], points[s[2]], points[order[i]]) != 0) {
      s[3] = order[i];
      result.dimension = 3;
      result.simplex = s;
    }
  }
  return result;
}

RangeScaling adaptive_range_scaling(double max_abs, double min_abs_nonzero) {
  RangeScaling r;
  if (max_abs == 0.0) return r;
  // Compare exponents, not scaled values: a scaled value could underflow or overflow.
  const int max_exponent = std::ilogb(max_abs);
  r.exponent = predicates::kScaledMaxExponent - 1 - max_exponent;
  const int min_exponent = min_abs_nonzero > 0.0 ? std::ilogb(min_abs_nonzero) : max_exponent;
  // Lossless iff the scaled smallest magnitude stays >= 2^-1022, the smallest normal double.
  r.lossless = min_exponent + r.exponent >= std::numeric_limits<double>::min_exponent - 1;
  // Unscaled, |c| <= 2^kRangeMaxExponent iff its exponent is below it, or c is that power.
  const bool max_in_range = r.lossless || max_exponent < predicates::kRangeMaxExponent ||
                            max_abs == std::ldexp(1.0, predicates::kRangeMaxExponent);
  const int shift = r.lossless ? r.exponent : 0;
  r.within_expansion_range = max_in_range && min_exponent + shift >= predicates::kRangeMinExponent;
  return r;
}

CoordinateMagnitudes coordinate_magnitudes(const std::vector<Point3>& points) {
  CoordinateMagnitudes r;
  for (const Point3& p : points) {
    for (const double c : {p.x, p.y, p.z}) {
      r.finite = r.finite && std::isfinite(c);
      const double m = std::fabs(c);
      r.max_abs = std::max(r.max_abs, m);
      if (m > 0.0 && (r.min_abs_nonzero == 0.0 || m < r.min_abs_nonzero)) r.min_abs_nonzero = m;
    }
  }
  return r;
}

PointSetInfo analyze(const std::vector<Point3>& points) {
  PointSetInfo info;
  info.count = points.size();
  if (points.empty()) return info;
  info.min = info.max = points[0];
  for (const Point3& p : points) {
    info.min = {std::min(info.min.x, p.x), std::min(info.min.y, p.y), std::min(info.min.z, p.z)};
    info.max = {std::max(info.max.x, p.x), std::max(info.max.y, p.y), std::max(info.max.z, p.z)};
  }
  const CoordinateMagnitudes magnitudes = coordinate_magnitudes(points);
  info.max_abs = magnitudes.max_abs;
  info.min_abs_nonzero = magnitudes.min_abs_nonzero;
  std::vector<Point3> sorted = points;
  std::sort(sorted.begin(), sorted.end(), predicates::lexicographically_less);
  info.distinct =
      static_cast<std::uint64_t>(std::unique(sorted.begin(), sorted.end()) - sorted.begin());
  info.duplicates = info.count - info.distinct;
  std::vector<std::uint32_t> order(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::uint32_t>(i);
  info.dimension = find_simplex(points, order).dimension;
  info.within_expansion_range =
      adaptive_range_scaling(info.max_abs, info.min_abs_nonzero).within_expansion_range;
  return info;
}

std::string dimension_name(int dimension) {
  switch (dimension) {
    case 0:
      return "0 (all points coincide)";
    case 1:
      return "1 (all points collinear)";
    case 2:
      return "2 (all points coplanar)";
    case 3:
      return "3";
    default:
      return "none (no points)";
  }
}

}  // namespace dtlab::engine
