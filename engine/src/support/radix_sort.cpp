#include "support/radix_sort.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <barrier>
#include <vector>

#include "support/parallel_ranges.hpp"

namespace dtlab::engine {

namespace {

constexpr int kDigits = 8;
// A range of at most this many items is sorted by its lower digits least significant first: its
// items and their scratch (512 KiB, this machine's L2 cache a core) stay near the core across the
// passes. A larger range is first split by its most significant varying digit, so that every
// later pass works on such a small range: a least-significant-first pass over the whole array
// scatters to 256 places in tens of megabytes, eight times for a Hilbert key. (At 4096 items, a
// pass curve's 30-bit keys were split twice, the second time into parts of a few dozen items:
// 500,000 of them took 11.0 ms on 2 threads, 5.8 ms at 16384; performance-log.md, fifteenth
// session.)
constexpr std::size_t kInCache = 16384;
// A range of at most this many items is sorted by insertion.
constexpr std::size_t kInsertionSort = 32;

std::size_t digit_of(const KeyedId& item, int d) {
  return static_cast<std::size_t>((item.first >> (8 * d)) & 0xFF);
}

// Whether one digit value holds all n items (the digit does not vary: its pass is skipped).
bool all_in_one(const std::array<std::size_t, 256>& count, std::size_t n) {
  return std::any_of(count.begin(), count.end(), [n](std::size_t k) { return k == n; });
}

// Counts by digit value become each value's first position (exclusive prefix sums).
void counts_to_starts(std::array<std::size_t, 256>& count) {
  std::size_t sum = 0;
  for (auto& k : count) {
    const std::size_t here = k;
    k = sum;
    sum += here;
  }
}

// Sorts a[0, n) by key, stably, by insertion: for the few items a split's part may hold, where
// a counting pass's 256 counters cost more than the items.
KeyedId* insertion_sort(KeyedId* a, std::size_t n) {
  for (std::size_t i = 1; i < n; ++i) {
    const KeyedId item = a[i];
    std::size_t j = i;
    for (; j > 0 && a[j - 1].first > item.first; --j) a[j] = a[j - 1];
    a[j] = item;
  }
  return a;
}

// Sorts a[0, n) by digits [0, top) of the keys, stably, least significant first, passing between
// a and b (one counting pass serves every digit; a digit the same in all n keys is skipped).
// Returns a or b, whichever holds the result.
KeyedId* sort_low_digits(KeyedId* a, KeyedId* b, std::size_t n, int top) {
  // By the whole key: wherever a range is sorted by its digits below `top`, the digits from
  // `top` up are the same in all its keys (the whole array's top ones, and a split's digit).
  if (n <= kInsertionSort) return insertion_sort(a, n);
  // Only the counters of the digits sorted by are cleared: a split's part, sorted by its two
  // lowest digits, cleared all eight (16 KiB) for a few dozen items (2 threads sorting 500,000
  // 30-bit keys took longer than one).
  std::array<std::array<std::size_t, 256>, kDigits> count;  // rows [0, top) cleared below
  for (int d = 0; d < top; ++d) count[static_cast<std::size_t>(d)].fill(0);
  for (std::size_t i = 0; i < n; ++i) {
    for (int d = 0; d < top; ++d) ++count[static_cast<std::size_t>(d)][digit_of(a[i], d)];
  }
  KeyedId* from = a;
  KeyedId* to = b;
  for (int d = 0; d < top; ++d) {
    auto& c = count[static_cast<std::size_t>(d)];
    if (all_in_one(c, n)) continue;
    counts_to_starts(c);
    for (std::size_t i = 0; i < n; ++i) to[c[digit_of(from[i], d)]++] = from[i];
    std::swap(from, to);
  }
  return from;
}

KeyedId* sort_by_digits_below(KeyedId* a, KeyedId* b, std::size_t n, int top);

// Part k of a split by one digit (its items placed from placed[start[k]] on, n items in all)
// sorted by the digits below `digit`, its result in home[start[k]] on, while still in the cache.
void sort_split_part(const std::array<std::size_t, 256>& start, std::size_t n, std::size_t k,
                     KeyedId* placed, KeyedId* home, int digit) {
  const std::size_t size = (k + 1 < 256 ? start[k + 1] : n) - start[k];
  if (size == 0) return;
  KeyedId* const to = home + start[k];
  const KeyedId* sorted = sort_by_digits_below(placed + start[k], to, size, digit);
  if (sorted != to) std::copy(sorted, sorted + size, to);
}

// Where range `part`'s items of each digit value go in a stable counting pass over several
// ranges: after every item of a lower value, and after those of its own value in lower ranges.
void range_starts(const std::vector<std::array<std::size_t, 256>>& count, std::size_t part,
                  std::array<std::size_t, 256>& next) {
  std::size_t sum = 0;
  for (std::size_t k = 0; k < 256; ++k) {
    for (std::size_t p = 0; p < count.size(); ++p) {
      if (p == part) next[k] = sum;
      sum += count[p][k];
    }
  }
}

// Sorts a[0, n) by digits [0, top) of the keys, stably, with b (n more) as scratch; returns a or
// b, whichever holds the result. Small: least significant digit first. Large: split by digit
// top - 1 (a counting pass from a into b, stable), then each part sorted by the digits below, its
// result moved back into a (when it ended in b) while it is still in the cache.
KeyedId* sort_by_digits_below(KeyedId* a, KeyedId* b, std::size_t n, int top) {
  if (n <= kInCache || top <= 1) return sort_low_digits(a, b, n, top);
  const int d = top - 1;
  std::array<std::size_t, 256> start{};
  for (std::size_t i = 0; i < n; ++i) ++start[digit_of(a[i], d)];
  if (all_in_one(start, n)) return sort_by_digits_below(a, b, n, d);
  counts_to_starts(start);
  std::array<std::size_t, 256> next = start;
  for (std::size_t i = 0; i < n; ++i) b[next[digit_of(a[i], d)]++] = a[i];
  for (std::size_t k = 0; k < 256; ++k) sort_split_part(start, n, k, b, a, d);
  return a;
}

}  // namespace

void stable_sort_by_key(KeyedId* items, KeyedId* scratch, std::size_t n, int threads) {
  // Each thread at least kParallelMinimum items: below that the barriers cost more than the work.
  const std::size_t parts =
      std::min(static_cast<std::size_t>(std::max(threads, 1)), n / kParallelMinimum);
  if (parts <= 1) {
    // One thread: least significant digit first over the whole range, one counting pass for all
    // digits. (Split by the top digit first, it was no faster here: 31.5 ms against 28.4, the
    // medians of 8 alternating runs of the BRIO rounds' sorts at 1M points; on two threads
    // the split is what pays, performance-log.md, "eleventh session".)
    const KeyedId* sorted = sort_low_digits(items, scratch, n, kDigits);
    if (sorted != items) std::copy(sorted, sorted + n, items);
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
  std::atomic<std::size_t> next_part{0};  // the split's parts handed out (relaxed: the barrier
                                          // before orders the placing, the step's end (the
                                          // pool's, or the join) the sorting)
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
    if (varying == 0) return;                             // every key equal: already in order
    const int top = (63 - __builtin_clzll(varying)) / 8;  // the most significant varying digit
    // Split by the top digit first, when no part of the split holds more than a thread's share
    // (so that the parts, each sorted on one thread, in the cache, keep every thread busy).
    auto& mine = count[part];
    mine.fill(0);
    for (std::size_t i = begin; i < end; ++i) ++mine[digit_of(items[i], top)];
    step.arrive_and_wait();
    std::array<std::size_t, 256> start{};  // of each part of the split
    std::size_t largest = 0;
    std::size_t sum = 0;
    for (std::size_t k = 0; k < 256; ++k) {
      start[k] = sum;
      for (std::size_t p = 0; p < parts; ++p) sum += count[p][k];
      largest = std::max(largest, sum - start[k]);
    }
    std::array<std::size_t, 256> next{};  // where this range's items of each part go
    range_starts(count, part, next);
    if (largest * parts <= n) {
      for (std::size_t i = begin; i < end; ++i) scratch[next[digit_of(items[i], top)]++] = items[i];
      step.arrive_and_wait();  // every range placed
      // The parts of the split, taken by whichever thread is free (any thread may sort any
      // part: the result is the same), each sorted by the lower digits back into items.
      for (std::size_t k = next_part.fetch_add(1, std::memory_order_relaxed); k < 256;
           k = next_part.fetch_add(1, std::memory_order_relaxed)) {
        sort_split_part(start, n, k, scratch, items, top);
      }
      return;
    }
    // Skewed (a far outlier, say): every varying digit's pass over the whole array, split over
    // the threads, least significant first. The counts just read are rewritten below.
    step.arrive_and_wait();
    KeyedId* from = items;
    KeyedId* to = scratch;
    for (int d = 0; d < kDigits; ++d) {
      if (((varying >> (8 * d)) & 0xFF) == 0) continue;
      mine.fill(0);
      for (std::size_t i = begin; i < end; ++i) ++mine[digit_of(from[i], d)];
      step.arrive_and_wait();
      range_starts(count, part, next);
      for (std::size_t i = begin; i < end; ++i) to[next[digit_of(from[i], d)]++] = from[i];
      // Every range placed (and every count read) before the next digit is counted.
      step.arrive_and_wait();
      std::swap(from, to);
    }
    if (from != items) std::copy(from + begin, from + end, items + begin);
  };
  // One range a thread, all at once (the barriers): the run's pool, or threads started for them.
  in_parallel_ranges(
      parts, static_cast<int>(parts),
      [&work](std::size_t, std::size_t, std::size_t part) { work(part); }, /*minimum=*/0);
}

}  // namespace dtlab::engine
