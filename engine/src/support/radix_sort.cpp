#include "support/radix_sort.hpp"

#include <algorithm>
#include <array>
#include <barrier>
#include <thread>
#include <vector>

#include "support/parallel_ranges.hpp"

namespace dtlab::engine {

namespace {

constexpr int kDigits = 8;

std::size_t digit_of(const KeyedId& item, int d) {
  return static_cast<std::size_t>((item.first >> (8 * d)) & 0xFF);
}

void sort_on_one_thread(KeyedId* items, KeyedId* scratch, std::size_t n) {
  std::vector<std::array<std::size_t, 256>> count(kDigits);
  for (auto& c : count) c.fill(0);
  for (std::size_t i = 0; i < n; ++i) {
    for (int d = 0; d < kDigits; ++d) ++count[static_cast<std::size_t>(d)][digit_of(items[i], d)];
  }
  auto* from = items;
  auto* to = scratch;
  for (int d = 0; d < kDigits; ++d) {
    auto& c = count[static_cast<std::size_t>(d)];
    if (std::any_of(c.begin(), c.end(), [n](std::size_t k) { return k == n; })) continue;
    std::size_t sum = 0;
    for (auto& k : c) {
      const std::size_t here = k;
      k = sum;
      sum += here;
    }
    for (std::size_t i = 0; i < n; ++i) to[c[digit_of(from[i], d)]++] = from[i];
    std::swap(from, to);
  }
  if (from != items) std::copy(from, from + n, items);
}

}  // namespace

void stable_sort_by_key(KeyedId* items, KeyedId* scratch, std::size_t n, int threads) {
  // Each thread at least kParallelMinimum items: below that the barriers cost more than the work.
  const std::size_t parts =
      std::min(static_cast<std::size_t>(std::max(threads, 1)), n / kParallelMinimum);
  if (parts <= 1) {
    sort_on_one_thread(items, scratch, n);
    return;
  }
  // Each thread owns one range of the array; per digit it counts its range's items by digit,
  // then (after a barrier) places them after every item of a lower digit and every item of its
  // own digit in a lower range: the order of equal digits is the array's, so the sort is stable.
  // Per range: the bits set in all its keys, and those set in any.
  std::vector<std::uint64_t> set_in_all(parts, ~std::uint64_t{0});
  std::vector<std::uint64_t> set_in_any(parts, 0);
  std::vector<std::array<std::size_t, 256>> count(parts);
  std::barrier<> step(static_cast<std::ptrdiff_t>(parts));
  auto work = [&](std::size_t part) {
    const std::size_t begin = n * part / parts;
    const std::size_t end = n * (part + 1) / parts;
    std::uint64_t in_all = ~std::uint64_t{0};
    std::uint64_t in_any = 0;
    for (std::size_t i = begin; i < end; ++i) {
      in_all &= items[i].first;
      in_any |= items[i].first;
    }
    set_in_all[part] = in_all;  // once: the ranges' entries share a cache line
    set_in_any[part] = in_any;
    step.arrive_and_wait();
    // The bits that differ between two keys somewhere; a digit without one is skipped (every
    // thread reads the same answer, so all take the same barriers).
    std::uint64_t in_all_keys = ~std::uint64_t{0};
    std::uint64_t in_any_key = 0;
    for (std::size_t p = 0; p < parts; ++p) {
      in_all_keys &= set_in_all[p];
      in_any_key |= set_in_any[p];
    }
    const std::uint64_t varying = in_all_keys ^ in_any_key;
    KeyedId* from = items;
    KeyedId* to = scratch;
    for (int d = 0; d < kDigits; ++d) {
      if (((varying >> (8 * d)) & 0xFF) == 0) continue;
      auto& mine = count[part];
      mine.fill(0);
      for (std::size_t i = begin; i < end; ++i) ++mine[digit_of(from[i], d)];
      step.arrive_and_wait();
      std::array<std::size_t, 256> next{};
      std::size_t sum = 0;
      for (std::size_t k = 0; k < 256; ++k) {
        for (std::size_t p = 0; p < parts; ++p) {
          if (p == part) next[k] = sum;
          sum += count[p][k];
        }
      }
      for (std::size_t i = begin; i < end; ++i) to[next[digit_of(from[i], d)]++] = from[i];
      // Every range placed (and every count read) before the next digit is counted.
      step.arrive_and_wait();
      std::swap(from, to);
    }
    if (from != items) std::copy(from + begin, from + end, items + begin);
  };
  std::vector<std::thread> helpers;
  helpers.reserve(parts - 1);
  for (std::size_t part = 0; part + 1 < parts; ++part) helpers.emplace_back(work, part);
  work(parts - 1);
  for (std::thread& h : helpers) h.join();
}

}  // namespace dtlab::engine
