#pragma once
// A run watched and stopped from another thread (the Python binding's Ctrl-C and progress): the
// engine publishes how many points it has handled and stops soon after `cancel` turns true.
#include <atomic>
#include <cstdint>

namespace dtlab::engine {

struct RunMonitor {
  // Points handled so far (inserted, found duplicate or abandoned), of `total`. Written about
  // every thousand points by the sequential engine and ten times a second by the parallel runs'
  // watchdog, relaxed: a reading for a progress bar, ordered with nothing else.
  std::atomic<std::uint64_t> done{0};
  std::atomic<std::uint64_t> total{0};
  // Set by the watcher; the insertion loop (sequential) or the watchdog (parallel) sees it within
  // a thousand insertions or 100 ms, and triangulate() throws RunCancelled once the run's threads
  // are joined. The repair and the steps before the first insertion do not look at it.
  std::atomic<bool> cancel{false};
};

}  // namespace dtlab::engine
