// A run watched and cancelled from another thread (dtlab/engine/run_monitor.hpp): the count
// moves, the run stops with RunCancelled soon after the flag, for the sequential engine and the
// parallel methods, and a run nobody cancels ends with done == total. Runs under TSan in CI.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "dtlab/engine/run_monitor.hpp"
#include "dtlab/engine/triangulate.hpp"
#include "dtlab/generators/generators.hpp"

namespace {

using dtlab::engine::Method;
using dtlab::engine::RunCancelled;
using dtlab::engine::RunMonitor;
using dtlab::engine::TriangulateOptions;

TriangulateOptions walk_options(Method method, int threads) {
  TriangulateOptions options;
  options.location = dtlab::engine::Location::Walk;
  options.insertion = dtlab::engine::Insertion::Cavity;
  options.method = method;
  options.threads = threads;
  return options;
}

// Cancels once the monitor has counted some points; returns whether the run said RunCancelled,
// and the count it had reached of the total.
struct CancelOutcome {
  bool cancelled = false;
  std::uint64_t done_when_cancelled = 0;
  std::uint64_t total = 0;
};
CancelOutcome cancel_midway(TriangulateOptions options, std::size_t n) {
  const auto points =
      dtlab::generators::generate("uniform", static_cast<std::int64_t>(n), 1).points;
  RunMonitor monitor;
  options.monitor = &monitor;
  CancelOutcome outcome;
  std::thread watcher([&] {
    while (monitor.done.load(std::memory_order_relaxed) == 0) std::this_thread::yield();
    outcome.done_when_cancelled = monitor.done.load(std::memory_order_relaxed);
    monitor.cancel.store(true, std::memory_order_relaxed);
  });
  try {
    dtlab::engine::triangulate(points, options);
  } catch (const RunCancelled&) {
    outcome.cancelled = true;
  }
  // A run that finished first has set done (the watcher then cancels nothing).
  watcher.join();
  outcome.total = monitor.total.load();
  return outcome;
}

TEST(RunMonitor, CancelsTheSequentialRun) {
  const CancelOutcome o = cancel_midway(walk_options(Method::Sequential, 1), 400000);
  EXPECT_TRUE(o.cancelled);
  EXPECT_EQ(o.total, 400000u);
  EXPECT_LT(o.done_when_cancelled, o.total);
}

TEST(RunMonitor, CancelsEveryParallelMethod) {
  for (const Method method :
       {Method::Pessimistic, Method::OptimisticDetect, Method::OptimisticPrevent, Method::Burglary,
        Method::Batch, Method::Partitioned, Method::LockGrid}) {
    const CancelOutcome o = cancel_midway(walk_options(method, 2), 400000);
    EXPECT_TRUE(o.cancelled) << dtlab::engine::to_string(method);
    EXPECT_LT(o.done_when_cancelled, o.total) << dtlab::engine::to_string(method);
  }
}

TEST(RunMonitor, AFinishedRunHasCountedEveryPoint) {
  const auto points = dtlab::generators::generate("uniform", 20000, 2).points;
  for (const Method method : {Method::Sequential, Method::OptimisticDetect}) {
    RunMonitor monitor;
    TriangulateOptions options = walk_options(method, method == Method::Sequential ? 1 : 2);
    options.monitor = &monitor;
    const auto result = dtlab::engine::triangulate(points, options);
    EXPECT_FALSE(result.tetrahedra.empty());
    EXPECT_EQ(monitor.done.load(), 20000u);
    EXPECT_EQ(monitor.total.load(), 20000u);
  }
}

TEST(RunMonitor, ACancelledRunLeavesTheCallersPointsAsGiven) {
  auto points = dtlab::generators::generate("uniform", 300000, 3).points;
  const auto copy = points;
  RunMonitor monitor;
  monitor.cancel = true;  // before the first insertion: stops at the first look
  TriangulateOptions options = walk_options(Method::Sequential, 1);
  options.monitor = &monitor;
  EXPECT_THROW(dtlab::engine::triangulate(std::move(points), options), RunCancelled);
  ASSERT_EQ(points.size(), copy.size());
  for (std::size_t i = 0; i < copy.size(); ++i) ASSERT_TRUE(points[i] == copy[i]) << i;
}

}  // namespace
