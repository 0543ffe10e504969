#pragma once
// Items grouped by a vertex id, for the validator's face and edge lists: one pass of a counting
// sort (a radix sort's digit) into at most kMaxVertexBuckets buckets of 2^shift consecutive ids, on
// `parts` threads. A bucket's items keep the order of their sources whatever `parts` is (each
// thread counts and places one contiguous range of sources, and the ranges are placed in order),
// so the caller's sort inside a bucket and everything after it does not depend on the thread
// count. Few buckets, not one per vertex: the items' order in the sources has nothing to do with
// their vertex ids (the input's order), and a placing pass that writes to a few thousand places
// keeps each place's cache line in cache, where one per vertex missed on nearly every write (at
// 1M uniform points the validator's faces took 4.3 s that way on 2 threads, 1.0 s this way).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "support/parallel_ranges.hpp"

namespace dtlab::engine {

inline constexpr std::size_t kMaxVertexBuckets = 4096;

template <class Item>
struct VertexBuckets {
  std::vector<std::size_t> first;  // bucket b is items[first[b], first[b + 1])
  std::unique_ptr<Item[]> items;   // left uninitialized before the placing pass writes each
  int shift = 0;                   // vertex v is in bucket v >> shift
  [[nodiscard]] std::size_t buckets() const { return first.size() - 1; }
  [[nodiscard]] std::size_t items_count() const { return first.back(); }
};

// `emit(source, sink)` calls `sink(vertex, item)` for each item of source `source` (vertex below
// `vertices`); it is called twice per source (count, then place) and must emit the same items.
template <class Item, class Emit>
VertexBuckets<Item> bucket_by_vertex(std::size_t vertices, std::size_t sources, int parts,
                                     const Emit& emit) {
  int shift = 0;
  while ((vertices >> shift) >= kMaxVertexBuckets) ++shift;
  const std::size_t buckets = (vertices >> shift) + 1;
  std::vector<std::vector<std::size_t>> at(static_cast<std::size_t>(std::max(parts, 1)));
  in_parallel_ranges(sources, parts, [&](std::size_t begin, std::size_t end, std::size_t part) {
    std::vector<std::size_t>& count = at[part];
    count.assign(buckets, 0);
    for (std::size_t s = begin; s < end; ++s) {
      emit(s, [&count, shift](std::uint32_t v, const Item&) { ++count[v >> shift]; });
    }
  });
  // Each part's count becomes where its first item of the bucket goes.
  VertexBuckets<Item> grouped;
  grouped.shift = shift;
  grouped.first.assign(buckets + 1, 0);
  std::size_t next = 0;
  for (std::size_t b = 0; b < buckets; ++b) {
    grouped.first[b] = next;
    for (std::vector<std::size_t>& count : at) {
      if (count.empty()) continue;  // a part that had no range (a short list runs as one)
      const std::size_t here = count[b];
      count[b] = next;
      next += here;
    }
  }
  grouped.first[buckets] = next;
  grouped.items.reset(new Item[next]);
  Item* items = grouped.items.get();
  in_parallel_ranges(sources, parts, [&](std::size_t begin, std::size_t end, std::size_t part) {
    std::vector<std::size_t>& cursor = at[part];
    for (std::size_t s = begin; s < end; ++s) {
      emit(s, [&cursor, items, shift](std::uint32_t v, const Item& item) {
        items[cursor[v >> shift]++] = item;
      });
    }
  });
  return grouped;
}

// Runs work(first_bucket, end_bucket, part) over the buckets cut into `parts` contiguous ranges of
// about equal item counts, one thread each (one range, inline, below kParallelMinimum items). Not
// equal bucket counts: grouped by their lowest vertex, a mesh's faces and edges crowd the low ids
// when ids are random (the input's order), so the first half of the buckets holds about 7/8 of
// the faces. The ranges are in bucket order, so what the parts find, joined in part order, does not
// depend on `parts`.
template <class Item, class Work>
void in_parallel_buckets(const VertexBuckets<Item>& grouped, int parts, Work work) {
  const std::size_t total = grouped.items_count();
  const std::size_t count =
      total < kParallelMinimum ? 1 : static_cast<std::size_t>(std::max(parts, 1));
  std::vector<std::size_t> cut(count + 1, 0);
  cut[count] = grouped.buckets();
  for (std::size_t p = 1; p < count; ++p) {
    const std::size_t target = total * p / count;
    const auto at = std::lower_bound(grouped.first.begin(), grouped.first.end() - 1, target);
    cut[p] = std::max(cut[p - 1], static_cast<std::size_t>(at - grouped.first.begin()));
  }
  in_parallel_ranges(
      count, static_cast<int>(count),
      [&](std::size_t begin, std::size_t end, std::size_t) {
        for (std::size_t p = begin; p < end; ++p) work(cut[p], cut[p + 1], p);
      },
      /*minimum=*/1);
}

// Sorts one bucket (vertices base .. base + 2^shift - 1) by vertex, then by `less` among the items
// of one vertex: a counting sort by vertex into `scratch` and back, then std::sort on each vertex's
// items (a few dozen on a mesh's faces and edges), which is about half the time of std::sort on the
// whole bucket (docs/performance.md, "Measured choices").
template <class Item, class VertexOf, class Less>
void sort_bucket(Item* first, Item* last, std::size_t base, int shift, const VertexOf& vertex_of,
                 const Less& less, std::vector<Item>& scratch, std::vector<std::size_t>& counts) {
  const std::size_t width = std::size_t{1} << shift;
  counts.assign(width + 1, 0);
  for (const Item* i = first; i != last; ++i) ++counts[vertex_of(*i) - base + 1];
  for (std::size_t v = 0; v < width; ++v) counts[v + 1] += counts[v];
  scratch.resize(static_cast<std::size_t>(last - first));
  std::vector<std::size_t>& at = counts;
  for (const Item* i = first; i != last; ++i) scratch[at[vertex_of(*i) - base]++] = *i;
  // at[v] is now where vertex v + 1's items start: the groups are [at[v - 1], at[v]).
  std::size_t begin = 0;
  for (std::size_t v = 0; v < width; ++v) {
    const std::size_t end = at[v];
    std::sort(scratch.begin() + static_cast<std::ptrdiff_t>(begin),
              scratch.begin() + static_cast<std::ptrdiff_t>(end), less);
    begin = end;
  }
  std::copy(scratch.begin(), scratch.end(), first);
}

}  // namespace dtlab::engine
