#include "location/insertion_order.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "dtlab/common/random.hpp"
#include "support/parallel_ranges.hpp"
#include "support/populate_pages.hpp"
#include "support/radix_sort.hpp"

namespace dtlab::engine {

std::vector<std::uint32_t> random_order(std::size_t n, std::uint64_t seed) {
  std::vector<std::uint32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(i);
  common::Random rng(seed);
  for (std::size_t i = n; i > 1; --i) std::swap(order[i - 1], order[rng.below(i)]);
  return order;
}

namespace {

// A coordinate's cell on the 2^bits grid over [lo, lo + extent].
std::uint32_t cell(double c, double lo, double extent, unsigned bits) {
  if (!(extent > 0)) return 0;
  const double top = static_cast<double>((1u << bits) - 1);
  const double scaled = (c - lo) / extent * top;
  return static_cast<std::uint32_t>(std::clamp(scaled, 0.0, top));
}

// Points are asked for this far ahead of use.
constexpr std::size_t kAhead = 16;

// The cube the keys are taken in: the bounding box of points[ids[i]] (or of the first `count`
// points when ids is null), its largest side on all three axes, so that cells are cubes (a flat
// input stays a flat curve).
HilbertFrame curve_frame(const std::vector<predicates::Point3>& points,
                         const std::vector<std::uint32_t>* ids, std::size_t count, int threads) {
  const std::size_t n = ids != nullptr ? ids->size() : count;
  auto at = [&](std::size_t i) -> const predicates::Point3& {
    return points[ids != nullptr ? (*ids)[i] : i];
  };
  const std::size_t parts = static_cast<std::size_t>(std::max(threads, 1));
  std::vector<std::pair<predicates::Point3, predicates::Point3>> boxes(parts, {at(0), at(0)});
  in_parallel_ranges(n, threads, [&](std::size_t begin, std::size_t end, std::size_t part) {
    auto [lo, hi] = boxes[part];
    for (std::size_t i = begin; i < end; ++i) {
      // A random order misses the cache at every point unless it is asked for ahead.
      if (ids != nullptr && i + kAhead < n) __builtin_prefetch(&at(i + kAhead));
      const predicates::Point3& p = at(i);
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    boxes[part] = {lo, hi};
  });
  predicates::Point3 lo = boxes[0].first;
  predicates::Point3 hi = boxes[0].second;
  for (const auto& [part_lo, part_hi] : boxes) {
    lo = {std::min(lo.x, part_lo.x), std::min(lo.y, part_lo.y), std::min(lo.z, part_lo.z)};
    hi = {std::max(hi.x, part_hi.x), std::max(hi.y, part_hi.y), std::max(hi.z, part_hi.z)};
  }
  // The halving keeps the extent finite for coordinates near DBL_MAX.
  return {lo, 2 * std::max({hi.x / 2 - lo.x / 2, hi.y / 2 - lo.y / 2, hi.z / 2 - lo.z / 2})};
}

}  // namespace

HilbertFrame hilbert_frame(const std::vector<predicates::Point3>& points, std::size_t count,
                           int threads) {
  if (count == 0) return {{0, 0, 0}, 0};
  return curve_frame(points, nullptr, std::min(count, points.size()), threads);
}

std::uint64_t hilbert_key_in(const HilbertFrame& frame, const predicates::Point3& p,
                             unsigned bits) {
  return hilbert_key(cell(p.x, frame.lo.x, frame.extent, bits),
                     cell(p.y, frame.lo.y, frame.extent, bits),
                     cell(p.z, frame.lo.z, frame.extent, bits), bits);
}

void brio_hilbert_order(const std::vector<predicates::Point3>& points,
                        std::vector<std::uint32_t>& ids, int threads,
                        const HilbertFrame* given_frame) {
  if (ids.empty()) return;
  const HilbertFrame frame =
      given_frame != nullptr ? *given_frame : curve_frame(points, &ids, 0, threads);
  std::vector<KeyedId> keyed = populated_vector<KeyedId>(ids.size(), threads);
  in_parallel_ranges(ids.size(), threads, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i) {
      if (i + kAhead < ids.size()) __builtin_prefetch(&points[ids[i + kAhead]]);
      keyed[i] = {hilbert_key_in(frame, points[ids[i]]), ids[i]};
    }
  });
  // Rounds from the end: [n/2, n), [n/4, n/2), ... and a first round [0, end) of at most
  // kFirstRound points. Equal keys keep the random order (ties are broken by position: the sort
  // is stable, on any number of threads).
  std::vector<KeyedId> scratch = populated_vector<KeyedId>(keyed.size(), threads);
  auto sort_rounds_below = [&](std::size_t end, int sort_threads) {
    while (end > 0) {
      const std::size_t begin = end <= kFirstRound ? 0 : end / 2;
      stable_sort_by_key(keyed.data() + begin, scratch.data() + begin, end - begin, sort_threads);
      end = begin;
    }
  };
  const std::size_t n = keyed.size();
  const std::size_t last_begin = n <= kFirstRound ? 0 : n / 2;
  if (threads < 2 || last_begin == 0) {
    sort_rounds_below(n, threads);
  } else {
    // The last round holds half the points and the rounds before it the other half: half the
    // threads sort the one while the rest sort the others, instead of every round in turn on all
    // of them (at 1M points the rounds' sorts took 10-12 ms that way on two threads, 13-15 ms on
    // one).
    const int last_threads = threads / 2;
    in_parallel_ranges(
        2, 2,
        [&](std::size_t, std::size_t, std::size_t part) {
          if (part == 0) {
            sort_rounds_below(last_begin, threads - last_threads);
          } else {
            stable_sort_by_key(keyed.data() + last_begin, scratch.data() + last_begin,
                               n - last_begin, last_threads);
          }
        },
        /*minimum=*/0);
  }
  in_parallel_ranges(ids.size(), threads, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i) ids[i] = keyed[i].second;
  });
}

}  // namespace dtlab::engine
