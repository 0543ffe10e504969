#pragma once
// The run's threads over the whole-array steps before the first insertion and after the last
// (the insertion order, the output, the repair's scan): each thread one contiguous range.
#include <algorithm>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

#include "support/worker_pool.hpp"

namespace dtlab::engine {

// Below this many items a step runs on the caller's thread alone: starting a thread costs about
// as much as a few thousand items' work, and waking a parked worker (worker_pool.hpp) and
// waiting for it a few hundred.
inline constexpr std::size_t kParallelMinimum = 4096;

// in_parallel_ranges' parts on threads started for them (no pool serves them).
template <class Guarded>
void start_ranges(std::size_t n, std::size_t count, Guarded& guarded) {
  std::vector<std::thread> helpers;
  helpers.reserve(count - 1);
  try {
    for (std::size_t part = 0; part + 1 < count; ++part) {
      helpers.emplace_back(guarded, n * part / count, n * (part + 1) / count, part);
    }
  } catch (...) {  // a thread that could not start (std::system_error): end the started ones
    for (std::thread& h : helpers) h.join();
    throw;
  }
  guarded(n * (count - 1) / count, n, count - 1);
  for (std::thread& h : helpers) h.join();
}

// Runs work(begin, end, part) over [0, n) cut into `parts` contiguous ranges (at most n), one
// thread each (the caller's thread takes the last; the others are the current WorkerPool's when
// it can serve them, else started here); with parts <= 1, or n below `minimum`, it
// runs inline as part 0 alone. An exception from a part (std::bad_alloc on a large mesh) is held
// until every part has ended, then the lowest part's is rethrown on the caller's thread: an
// exception escaping a std::thread would terminate the process.
template <class Work>
void in_parallel_ranges(std::size_t n, int parts, Work work,
                        std::size_t minimum = kParallelMinimum) {
  const auto count =
      std::min(static_cast<std::size_t>(std::max(parts, 1)), std::max<std::size_t>(n, 1));
  if (count <= 1 || n < minimum) {  // count is at least 1; "<=" tells the analyzer so
    work(std::size_t{0}, n, std::size_t{0});
    return;
  }
  std::vector<std::exception_ptr> failed(count);
  auto guarded = [&work, &failed](std::size_t begin, std::size_t end, std::size_t part) {
    try {
      work(begin, end, part);
    } catch (...) {
      failed[part] = std::current_exception();
    }
  };
  if (WorkerPool* pool = WorkerPool::current(); pool && pool->can_run(static_cast<int>(count))) {
    auto range = [&](int part) {
      const auto p = static_cast<std::size_t>(part);
      guarded(n * p / count, n * (p + 1) / count, p);
    };
    pool->run(static_cast<int>(count), range);
  } else {
    start_ranges(n, count, guarded);
  }
  for (const std::exception_ptr& e : failed) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace dtlab::engine
