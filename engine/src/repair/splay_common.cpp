#include "repair/splay_common.hpp"

#include <bit>
#include <stdexcept>

#include "dtlab/engine/point_set_info.hpp"

namespace dtlab::engine {

std::uint64_t coordinate_hash(const Point3& p) {
  constexpr std::uint64_t kGoldenRatio = 0x9E3779B97F4A7C15ULL;  // floor(2^64 / phi), odd
  auto bits = [](double c) { return std::bit_cast<std::uint64_t>(c == 0.0 ? 0.0 : c); };
  std::uint64_t h = 0;
  for (const double c : {p.x, p.y, p.z}) {
    h = (h ^ bits(c)) * kGoldenRatio;
    h ^= h >> 29;  // the high bits back into the low ones, for the next product
  }
  return h >> 32;  // a 32-bit key: the radix sort skips the four zero digits
}

std::array<VertexId, 4> pool_of(const std::vector<Point3>& points,
                                const std::vector<VertexId>& vertices) {
  const SimplexSearch s = find_simplex(points, vertices);
  if (!s.simplex) throw std::invalid_argument("star splaying: the points do not span 3D");
  return *s.simplex;
}

}  // namespace dtlab::engine
