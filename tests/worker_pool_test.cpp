// A test of the engine's internals: it includes headers from engine/src (dtlab_internal_test).
// The run's threads started once (support/worker_pool.hpp): every index of a step runs at once on
// its own thread, worker i runs index i in every step, a job's exception reaches the caller, and
// the parallel helpers take the current pool when it can serve them and start threads otherwise.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "support/parallel_ranges.hpp"
#include "support/radix_sort.hpp"
#include "support/worker_pool.hpp"

namespace dtlab::engine {
namespace {

// Each job waits (up to 10 s, not for ever) until every job of the step has arrived: only jobs
// that run at once all see the whole count (the lock methods' threads wait on each other).
TEST(WorkerPool, EveryIndexRunsAtOnceOnItsOwnThread) {
  WorkerPool pool(5);
  for (const int n : {1, 2, 6, 4}) {
    std::atomic<int> arrived{0};
    std::vector<int> saw_all(static_cast<std::size_t>(n), 0);
    std::vector<std::thread::id> ran_on(static_cast<std::size_t>(n));
    auto job = [&](int i) {
      arrived.fetch_add(1);
      const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
      while (arrived.load() < n && std::chrono::steady_clock::now() < deadline) {
        std::this_thread::yield();
      }
      saw_all[static_cast<std::size_t>(i)] = arrived.load() == n ? 1 : 0;
      ran_on[static_cast<std::size_t>(i)] = std::this_thread::get_id();
    };
    ASSERT_TRUE(pool.can_run(n));
    pool.run(n, job);
    const std::set<std::thread::id> distinct(ran_on.begin(), ran_on.end());
    EXPECT_EQ(distinct.size(), static_cast<std::size_t>(n)) << n;
    EXPECT_EQ(ran_on.back(), std::this_thread::get_id()) << "the last index on the caller";
    for (int i = 0; i < n; ++i) EXPECT_EQ(saw_all[static_cast<std::size_t>(i)], 1) << n << " " << i;
  }
  EXPECT_FALSE(pool.can_run(7));  // more indices than workers and caller
}

// The threads are started once: index i is the same thread in every step (10,000 steps).
TEST(WorkerPool, WorkerIRunsIndexIInEveryStep) {
  WorkerPool pool(3);
  std::vector<std::thread::id> first(4);
  auto record = [&](int i) { first[static_cast<std::size_t>(i)] = std::this_thread::get_id(); };
  pool.run(4, record);
  std::atomic<std::uint64_t> sum{0};
  std::atomic<int> moved{0};
  auto job = [&](int i) {
    sum.fetch_add(static_cast<std::uint64_t>(i) + 1);
    if (first[static_cast<std::size_t>(i)] != std::this_thread::get_id()) moved.fetch_add(1);
  };
  for (int step = 0; step < 10000; ++step) pool.run(4, job);
  EXPECT_EQ(sum.load(), 10000u * (1 + 2 + 3 + 4));
  EXPECT_EQ(moved.load(), 0);
}

// Every job ends before run() returns, and the lowest index's exception is the one rethrown; the
// pool serves the next step as before.
TEST(WorkerPool, TheLowestIndexsExceptionReachesTheCallerAfterAllEnd) {
  WorkerPool pool(3);
  std::atomic<int> ended{0};
  auto failing = [&](int i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20 * (4 - i)));
    ended.fetch_add(1);
    if (i == 1) throw std::runtime_error("one");
    if (i == 3) throw std::runtime_error("three");
  };
  try {
    pool.run(4, failing);
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "one");
  }
  EXPECT_EQ(ended.load(), 4);
  std::atomic<int> ran{0};
  auto counting = [&](int) { ran.fetch_add(1); };
  pool.run(4, counting);
  EXPECT_EQ(ran.load(), 4);
}

// The helpers take the current pool (their parts run on its workers), and start threads of their
// own where it cannot serve them: a step nested in a step, or more parts than it has threads.
TEST(WorkerPool, HelpersTakeTheCurrentPoolWhenItCanServeThem) {
  WorkerPool pool(2);
  // The workers' ids (alive throughout, so no other thread can have one of them).
  std::vector<std::thread::id> workers(3);
  auto record = [&](int i) { workers[static_cast<std::size_t>(i)] = std::this_thread::get_id(); };
  pool.run(3, record);
  PoolScope scope(&pool);
  ASSERT_EQ(WorkerPool::current(), &pool);
  for (int step = 0; step < 2; ++step) {
    std::vector<std::thread::id> ran_on(3);
    in_parallel_ranges(3 * kParallelMinimum, 3, [&](std::size_t, std::size_t, std::size_t part) {
      ran_on[part] = std::this_thread::get_id();
    });
    EXPECT_EQ(ran_on, workers) << "part i on worker i, the last on the caller";
  }
  // The pool's threads: its two workers and the caller.
  const std::set<std::thread::id> pool_threads(workers.begin(), workers.end());
  // Four parts: more than the pool's two workers and the caller; threads of their own (none of
  // the pool's), all four parts done.
  std::vector<std::atomic<int>> seen(4 * kParallelMinimum);
  std::vector<std::thread::id> four(4);
  in_parallel_ranges(seen.size(), 4, [&](std::size_t begin, std::size_t end, std::size_t part) {
    four[part] = std::this_thread::get_id();
    for (std::size_t i = begin; i < end; ++i) seen[i].fetch_add(1);
  });
  for (const auto& s : seen) ASSERT_EQ(s.load(), 1);
  EXPECT_EQ(four[3], std::this_thread::get_id());
  for (std::size_t part = 0; part < 3; ++part) EXPECT_EQ(pool_threads.count(four[part]), 0u);
  // Nested: a part of a step asks for a step of its own, which threads of its own serve (the
  // pool is running the outer step): each inner step's first part on a thread of the pool's
  // neither, its second on the outer part's thread.
  std::vector<std::atomic<int>> inner(2 * 2 * kParallelMinimum);
  std::vector<std::thread::id> outer_on(2);
  std::vector<std::thread::id> inner_on(4);
  in_parallel_ranges(2 * kParallelMinimum, 2, [&](std::size_t, std::size_t, std::size_t part) {
    outer_on[part] = std::this_thread::get_id();
    const std::size_t base = part * 2 * kParallelMinimum;
    in_parallel_ranges(2 * kParallelMinimum, 2, [&](std::size_t b, std::size_t e, std::size_t k) {
      inner_on[2 * part + k] = std::this_thread::get_id();
      for (std::size_t i = b; i < e; ++i) inner[base + i].fetch_add(1);
    });
  });
  for (const auto& s : inner) ASSERT_EQ(s.load(), 1);
  EXPECT_EQ(outer_on[0], workers[0]);
  EXPECT_EQ(outer_on[1], std::this_thread::get_id());
  for (std::size_t part = 0; part < 2; ++part) {
    EXPECT_EQ(pool_threads.count(inner_on[2 * part]), 0u) << part;
    EXPECT_EQ(inner_on[2 * part + 1], outer_on[part]) << part;
  }
  // The radix sort's ranges meet at barriers, so they must run at once: sorted under the pool.
  std::vector<KeyedId> items(3 * kParallelMinimum);
  std::vector<KeyedId> scratch(items.size());
  for (std::size_t i = 0; i < items.size(); ++i) {
    items[i] = {(i * 2654435761u) % 1000, static_cast<std::uint32_t>(i)};
  }
  stable_sort_by_key(items.data(), scratch.data(), items.size(), 3);
  for (std::size_t i = 1; i < items.size(); ++i) {
    ASSERT_TRUE(items[i - 1].first < items[i].first ||
                (items[i - 1].first == items[i].first && items[i - 1].second < items[i].second));
  }
}

// Outside a scope no pool is current; a scope restores the one before it.
TEST(WorkerPool, AScopeRestoresThePoolBeforeIt) {
  EXPECT_EQ(WorkerPool::current(), nullptr);
  WorkerPool outer(1);
  WorkerPool inner(1);
  {
    PoolScope a(&outer);
    {
      PoolScope b(&inner);
      EXPECT_EQ(WorkerPool::current(), &inner);
    }
    EXPECT_EQ(WorkerPool::current(), &outer);
  }
  EXPECT_EQ(WorkerPool::current(), nullptr);
}

}  // namespace
}  // namespace dtlab::engine
