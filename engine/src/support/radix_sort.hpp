#pragma once
// A stable sort of (key, id) pairs by key in linear time, for the orders the engine and the repair
// build over every point (the BRIO rounds' Hilbert keys, the repair's grouping of equal points).
#include <cstdint>
#include <utility>

namespace dtlab::engine {

using KeyedId = std::pair<std::uint64_t, std::uint32_t>;

// Sorts items[0, n) by key, stably, with `scratch` of the same size, 8 bits a digit (256
// counters stay in L1); a digit that is the same in every key is skipped. On one thread: least
// significant digit first, one counting pass for all digits. On several (at least
// kParallelMinimum items a thread): split by the most significant varying digit (each thread
// counts and places its own range of the array), then the parts handed to whichever thread is
// free, each sorted by the digits below (split again while it holds over 16,384 items, then least
// significant first, in the cache); when one part would hold more than a thread's share (a far
// outlier's key), every digit's pass goes over the whole array instead, each split over the
// threads. The same order as std::stable_sort by key, whatever `threads`.
void stable_sort_by_key(KeyedId* items, KeyedId* scratch, std::size_t n, int threads = 1);

}  // namespace dtlab::engine
