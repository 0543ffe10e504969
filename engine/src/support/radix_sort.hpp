#pragma once
// A stable sort of (key, id) pairs by key in linear time, for the orders the engine and the repair
// build over every point (the BRIO rounds' Hilbert keys, the repair's grouping of equal points).
#include <cstdint>
#include <utility>

namespace dtlab::engine {

using KeyedId = std::pair<std::uint64_t, std::uint32_t>;

// Sorts items[0, n) by key, stably, with `scratch` of the same size: least significant digit
// first, 8 bits a pass (256 counters stay in L1), and a digit that is the same in every key is
// skipped. On one thread one counting pass serves all eight digits; on several, each digit's pass
// counts its own (the counts of a range depend on the previous pass). The same order as
// std::stable_sort by key, whatever `threads`: with more than one (and at least kParallelMinimum
// items a thread), each digit's pass is split over that many threads, each placing its own range of
// the array.
void stable_sort_by_key(KeyedId* items, KeyedId* scratch, std::size_t n, int threads = 1);

}  // namespace dtlab::engine
