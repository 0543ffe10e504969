// A test of the engine's internals: it includes headers from engine/src (dtlab_internal_test).
// The engine's stable radix sort of (key, id) pairs: the order of std::stable_sort by key, on one
// thread and on several, with keys that share digits (skipped passes), many equal keys (stability),
// sizes around the split's minimum, ranges small enough for insertion, and both ways of sorting a
// large array (split by the top digit, or every digit over the whole array when the split would
// crowd into one part).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "support/parallel_ranges.hpp"
#include "support/radix_sort.hpp"

namespace dtlab::test {
namespace {

using engine::KeyedId;

std::vector<KeyedId> sorted_by_std(std::vector<KeyedId> items) {
  std::stable_sort(items.begin(), items.end(),
                   [](const KeyedId& a, const KeyedId& b) { return a.first < b.first; });
  return items;
}

TEST(StableSortByKey, AnyThreadCountGivesStdStableSortsOrder) {
  std::mt19937_64 random(20261125);
  const std::size_t minimum = engine::kParallelMinimum;
  for (const std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{1000}, 2 * minimum - 1,
                              2 * minimum, 3 * minimum + 17, std::size_t{200000}}) {
    // Keys: a few distinct values spread over bytes 1, 3 and 7 (the other bytes never vary, so
    // their passes are skipped); ids number the items, so that stability is visible.
    std::vector<KeyedId> items(n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint64_t r = random() % 97;
      const std::uint64_t key = ((r % 7) << 8) | ((r / 7 % 5) << 24) | ((r % 3) << 56);
      items[i] = {key, static_cast<std::uint32_t>(i)};
    }
    const std::vector<KeyedId> expected = sorted_by_std(items);
    for (const int threads : {1, 2, 3, 8}) {
      std::vector<KeyedId> sorted = items;
      std::vector<KeyedId> scratch(n);
      engine::stable_sort_by_key(sorted.data(), scratch.data(), n, threads);
      EXPECT_EQ(sorted, expected) << "n " << n << ", threads " << threads;
    }
  }
}

TEST(StableSortByKey, FullWidthRandomKeysOnAnyThreadCount) {
  std::mt19937_64 random(7);
  std::vector<KeyedId> items(300000);
  for (std::size_t i = 0; i < items.size(); ++i) {
    items[i] = {random(), static_cast<std::uint32_t>(i)};
  }
  const std::vector<KeyedId> expected = sorted_by_std(items);
  for (const int threads : {1, 2, 5}) {
    std::vector<KeyedId> sorted = items;
    std::vector<KeyedId> scratch(items.size());
    engine::stable_sort_by_key(sorted.data(), scratch.data(), sorted.size(), threads);
    EXPECT_EQ(sorted, expected) << threads;
  }
}

// The smallest ranges are sorted by insertion: a few items alone, and the parts of a split by a
// top digit that takes 256 values over barely two threads' minimum (about 32 items a part), each
// with many equal keys, so that an unstable insertion would show.
TEST(StableSortByKey, SmallRangesAndTinyPartsOfASplitKeepEqualKeysInOrder) {
  std::mt19937_64 random(5);
  for (const std::size_t n : {std::size_t{2}, std::size_t{31}, std::size_t{32}, std::size_t{33},
                              2 * engine::kParallelMinimum + 5}) {
    std::vector<KeyedId> items(n);
    for (std::size_t i = 0; i < n; ++i) {
      items[i] = {((random() % 256) << 16) | (random() % 3), static_cast<std::uint32_t>(i)};
    }
    const std::vector<KeyedId> expected = sorted_by_std(items);
    for (const int threads : {1, 2, 3}) {
      std::vector<KeyedId> sorted = items;
      std::vector<KeyedId> scratch(n);
      engine::stable_sort_by_key(sorted.data(), scratch.data(), n, threads);
      EXPECT_EQ(sorted, expected) << "n " << n << ", threads " << threads;
    }
  }
}

// Which way a large array is sorted follows from its keys and the thread count: the crowded keys
// (all but one in one part of the top digit's split: a far outlier's key alone above them) take
// the per-digit passes over the whole array on 2, 3 and 8 threads; the layered keys (four even
// parts, varying only in the low byte within each) take the split on 2 and 3 threads, each part
// sorted past the digits it shares, and the per-digit passes on 8, where a part holds more than a
// thread's share. One thread sorts both least significant digit first.
TEST(StableSortByKey, CrowdedAndLayeredKeysGiveStdStableSortsOrder) {
  std::mt19937_64 random(11);
  std::vector<KeyedId> crowded(50000);
  for (std::size_t i = 0; i < crowded.size(); ++i) {
    crowded[i] = {random() % 1000 + (i % 9 == 0 ? 0 : 5000), static_cast<std::uint32_t>(i)};
  }
  crowded[123].first = std::uint64_t{1} << 62;
  std::vector<KeyedId> layered(70000);
  for (std::size_t i = 0; i < layered.size(); ++i) {
    layered[i] = {((random() % 4) << 40) | (random() % 50), static_cast<std::uint32_t>(i)};
  }
  for (const auto* items : {&crowded, &layered}) {
    const std::vector<KeyedId> expected = sorted_by_std(*items);
    for (const int threads : {1, 2, 3, 8}) {
      std::vector<KeyedId> sorted = *items;
      std::vector<KeyedId> scratch(items->size());
      engine::stable_sort_by_key(sorted.data(), scratch.data(), sorted.size(), threads);
      EXPECT_EQ(sorted, expected) << items->size() << " " << threads;
    }
  }
}

}  // namespace
}  // namespace dtlab::test
