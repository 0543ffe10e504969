// A test of the engine's internals: it includes headers from engine/src (dtlab_internal_test).
// The parallel runs' progress count (one counter a thread) and the watchdog that reads it.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <thread>
#include <vector>

#include "methods/progress_counters.hpp"
#include "methods/watchdog.hpp"

namespace dtlab::test {
namespace {

// The insertions counted on every thread (each on its own counter) add up, whichever thread
// counted them, and a reader meanwhile never sees the sum go down.
TEST(ProgressCounters, TotalIsTheSumOfEveryThreadsCountAndNeverGoesDown) {
  engine::ProgressCounters progress(4);
  EXPECT_EQ(progress.total(), 0u);
  std::atomic<bool> counting{true};
  std::uint64_t decreases = 0;
  std::uint64_t readings = 0;
  std::thread reader([&] {
    std::uint64_t last = 0;
    while (counting.load()) {
      const std::uint64_t now = progress.total();
      if (now < last) ++decreases;
      last = now;
      ++readings;
    }
  });
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&progress, t] {
      for (int k = 0; k < 20000 * (t + 1); ++k) progress.add(t);
    });
  }
  for (std::thread& t : threads) t.join();
  counting.store(false);
  reader.join();
  EXPECT_EQ(progress.total(), 20000u * (1 + 2 + 3 + 4));
  EXPECT_EQ(decreases, 0u);
  EXPECT_GT(readings, 0u);
}

// The watchdog stops a run whose count stands still for its limit (and says so), and leaves
// alone one whose count keeps growing.
TEST(Watchdog, FiresOnlyWhenNoThreadCounts) {
  {
    engine::ProgressCounters progress(2);
    std::atomic<bool> stop{false};
    engine::Watchdog watchdog(0.2, progress, stop);
    const auto start = std::chrono::steady_clock::now();
    while (!stop.load() && std::chrono::steady_clock::now() - start < std::chrono::seconds(10)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    EXPECT_TRUE(stop.load());
    EXPECT_TRUE(watchdog.fired());
  }
  {
    engine::ProgressCounters progress(2);
    std::atomic<bool> stop{false};
    // Three times the limit, counting every 10 ms: a watchdog blind to the count would fire.
    engine::Watchdog watchdog(0.5, progress, stop);
    const auto start = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - start < std::chrono::milliseconds(1500)) {
      progress.add(1);
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    EXPECT_FALSE(stop.load());
    EXPECT_FALSE(watchdog.fired());
  }
}

// Paused (between a run's threaded steps) it does not time the stall, however long; resumed, it
// times it again from then.
TEST(Watchdog, APausedWatchdogDoesNotTimeTheStall) {
  engine::ProgressCounters progress(1);
  std::atomic<bool> stop{false};
  engine::Watchdog watchdog(0.2, progress, stop);
  watchdog.pause();
  std::this_thread::sleep_for(std::chrono::milliseconds(800));  // four times the limit
  EXPECT_FALSE(stop.load());
  const auto resumed = std::chrono::steady_clock::now();
  watchdog.resume();
  while (!stop.load() && std::chrono::steady_clock::now() - resumed < std::chrono::seconds(10)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_TRUE(watchdog.fired());
  EXPECT_GE(std::chrono::steady_clock::now() - resumed, std::chrono::milliseconds(200));
}

}  // namespace
}  // namespace dtlab::test
