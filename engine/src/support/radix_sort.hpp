#pragma once
// A stable sort of (key, id) pairs by key in linear time, for the orders the engine and the repair
// build over every point (the BRIO rounds' Hilbert keys, the repair's grouping of equal points).
#include <cstdint>
#include <utility>

namespace dtlab::engine {

using KeyedId = std::pair<std::uint64_t, std::uint32_t>;

// Sorts items[0, n) by key, stably, with `scratch` of the same size, 8 bits a digit (256
// counters stay in L1); a digit that is the same in every key is skipped. A range of at most 4096
// items is sorted least significant digit first; a larger one is first split by its most
// significant varying digit (one counting pass), and each part sorted by the digits below, in the
// cache. On several threads (at least kParallelMinimum items a thread) the split is shared
// (each thread places its own range of the array) and the parts are handed to whichever thread
// is free; when one part would hold more than a thread's share (a far outlier's key), every
// digit's pass goes over the whole array instead, each split over the threads. The same order as
// std::stable_sort by key, whatever `threads`.
void stable_sort_by_key(KeyedId* items, KeyedId* scratch, std::size_t n, int threads = 1);

}  // namespace dtlab::engine
