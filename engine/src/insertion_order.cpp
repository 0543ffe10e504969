#include "insertion_order.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "dtlab/generators/random.hpp"

namespace dtlab::engine {

std::vector<std::uint32_t> random_order(std::size_t n, std::uint64_t seed) {
  std::vector<std::uint32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(i);
  generators::detail::Random rng(seed);
  for (std::size_t i = n; i > 1; --i) std::swap(order[i - 1], order[rng.below(i)]);
  return order;
}

// Hilbert key by Skilling's method ("Programming the Hilbert curve", 2004): the curve is built
// from the most significant bit down; at each level the sub-cube's frame is a reflection and an
// axis exchange of the parent's, and applying those transformations to the lower bits of the
// coordinates first (the loop over q), then Gray-decoding the bit columns, leaves the "transposed"
// index, whose bits interleaved axis by axis are the distance along the curve.
std::uint64_t hilbert_key(std::uint32_t x, std::uint32_t y, std::uint32_t z, unsigned bits) {
  std::uint32_t axis[3] = {x, y, z};
  const std::uint32_t top = 1u << (bits - 1);
  for (std::uint32_t q = top; q > 1; q >>= 1) {
    const std::uint32_t lower = q - 1;
    for (std::uint32_t& a : axis) {
      if ((a & q) != 0) {
        axis[0] ^= lower;  // reflect the lower bits of the first axis
      } else {
        const std::uint32_t differ = (axis[0] ^ a) & lower;  // exchange with the first axis
        axis[0] ^= differ;
        a ^= differ;
      }
    }
  }
  axis[1] ^= axis[0];
  axis[2] ^= axis[1];
  std::uint32_t flip = 0;
  for (std::uint32_t q = top; q > 1; q >>= 1) {
    if ((axis[2] & q) != 0) flip ^= q - 1;
  }
  for (std::uint32_t& a : axis) a ^= flip;
  std::uint64_t key = 0;
  for (int b = static_cast<int>(bits) - 1; b >= 0; --b) {
    for (const std::uint32_t a : axis) key = (key << 1) | ((a >> b) & 1u);
  }
  return key;
}

namespace {

constexpr unsigned kBits = 21;

// A coordinate's cell on the 2^21 grid over [lo, lo + extent].
std::uint32_t cell(double c, double lo, double extent) {
  if (!(extent > 0)) return 0;
  const double scaled = (c - lo) / extent * static_cast<double>((1u << kBits) - 1);
  return static_cast<std::uint32_t>(
      std::clamp(scaled, 0.0, static_cast<double>((1u << kBits) - 1)));
}

}  // namespace

void brio_hilbert_order(const std::vector<predicates::Point3>& points,
                        std::vector<std::uint32_t>& ids) {
  if (ids.empty()) return;
  predicates::Point3 lo = points[ids[0]];
  predicates::Point3 hi = lo;
  for (const std::uint32_t v : ids) {
    const predicates::Point3& p = points[v];
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  // One scale for the three axes keeps the cells cubes (a flat input stays a flat curve). The
  // halving keeps the extent finite for coordinates near DBL_MAX.
  const double extent =
      2 * std::max({hi.x / 2 - lo.x / 2, hi.y / 2 - lo.y / 2, hi.z / 2 - lo.z / 2});
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const predicates::Point3& p = points[ids[i]];
    keyed[i] = {hilbert_key(cell(p.x, lo.x, extent), cell(p.y, lo.y, extent),
                            cell(p.z, lo.z, extent), kBits),
                ids[i]};
  }
  // Rounds from the end: [n/2, n), [n/4, n/2), ... and a first round [0, end) of at most
  // kFirstRound points. Equal keys keep the random order (ties are broken by position).
  std::size_t end = keyed.size();
  while (end > 0) {
    const std::size_t begin = end <= kFirstRound ? 0 : end / 2;
    std::stable_sort(keyed.begin() + static_cast<std::ptrdiff_t>(begin),
                     keyed.begin() + static_cast<std::ptrdiff_t>(end),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    end = begin;
  }
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = keyed[i].second;
}

}  // namespace dtlab::engine
