// A test of the engine's internals: it includes headers from engine/src (dtlab_internal_test).
// The helpers that spread a whole-array step over the run's threads: every index or bucket is
// visited once, and an exception on a helper thread reaches the caller instead of terminating.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <new>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "support/parallel_ranges.hpp"
#include "validate/vertex_buckets.hpp"

namespace dtlab::engine {
namespace {

TEST(InParallelRanges, EveryIndexOnceOnAnyThreadCount) {
  for (const int parts : {1, 2, 3, 7}) {
    std::vector<std::atomic<int>> seen(10000);
    in_parallel_ranges(seen.size(), parts, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t i = begin; i < end; ++i) seen[i].fetch_add(1, std::memory_order_relaxed);
    });
    for (std::size_t i = 0; i < seen.size(); ++i) ASSERT_EQ(seen[i].load(), 1) << parts << " " << i;
  }
}

// A worker's std::bad_alloc (a large mesh) used to escape its std::thread and terminate.
TEST(InParallelRanges, AHelperThreadsExceptionReachesTheCaller) {
  for (const std::size_t failing : {std::size_t{0}, std::size_t{2}, std::size_t{3}}) {
    std::atomic<int> finished{0};
    EXPECT_THROW(in_parallel_ranges(std::size_t{100000}, 4,
                                    [&](std::size_t, std::size_t, std::size_t part) {
                                      if (part == failing) throw std::bad_alloc();
                                      finished.fetch_add(1);
                                    }),
                 std::bad_alloc)
        << failing;
    // Every other part ran to its end before the exception was rethrown.
    EXPECT_EQ(finished.load(), 3) << failing;
  }
  // The lowest failing part's exception is the one rethrown.
  try {
    in_parallel_ranges(std::size_t{100000}, 3, [](std::size_t, std::size_t, std::size_t part) {
      if (part >= 1) throw std::runtime_error("part " + std::to_string(part));
    });
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "part 1");
  }
}

// Items crowded into the low buckets, as a mesh's faces are under their lowest vertex when ids
// are random: the threads' shares are cut by item count, each bucket visited once, in order.
TEST(InParallelBuckets, SharesAreCutByItemCountAndCoverEveryBucketOnce) {
  const std::size_t vertices = 1 << 20;
  const std::size_t sources = 200000;
  // Source s emits one item under vertex (s * s) / sources^2 * vertices: dense near 0.
  auto emit = [&](std::size_t s, const auto& sink) {
    const double x = static_cast<double>(s) / static_cast<double>(sources);
    sink(static_cast<std::uint32_t>(x * x * static_cast<double>(vertices - 1)),
         static_cast<std::uint32_t>(s));
  };
  const VertexBuckets<std::uint32_t> grouped =
      bucket_by_vertex<std::uint32_t>(vertices, sources, 2, emit);
  ASSERT_EQ(grouped.items_count(), sources);
  for (const int parts : {1, 2, 4, 5}) {
    std::vector<std::size_t> items_of(static_cast<std::size_t>(parts), 0);
    std::vector<std::atomic<int>> visits(grouped.buckets());
    std::vector<std::size_t> first_bucket(static_cast<std::size_t>(parts), 0);
    in_parallel_buckets(grouped, parts, [&](std::size_t begin, std::size_t end, std::size_t part) {
      first_bucket[part] = begin;
      for (std::size_t b = begin; b < end; ++b) {
        visits[b].fetch_add(1, std::memory_order_relaxed);
        items_of[part] += grouped.first[b + 1] - grouped.first[b];
      }
    });
    for (std::size_t b = 0; b < visits.size(); ++b) ASSERT_EQ(visits[b].load(), 1) << parts;
    for (std::size_t p = 1; p < first_bucket.size(); ++p) {
      EXPECT_LE(first_bucket[p - 1], first_bucket[p]) << parts;
    }
    EXPECT_EQ(std::accumulate(items_of.begin(), items_of.end(), std::size_t{0}), sources);
    // Within a bucket's worth (a few hundred items here) of an equal share.
    const std::size_t share = sources / static_cast<std::size_t>(parts);
    for (const std::size_t mine : items_of) {
      EXPECT_NEAR(static_cast<double>(mine), static_cast<double>(share), 0.02 * sources) << parts;
    }
  }
}

}  // namespace
}  // namespace dtlab::engine
