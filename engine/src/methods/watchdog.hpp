#pragma once
// The parallel runs' guard against a hang (every method but the sequential one).
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>

#include "dtlab/engine/run_monitor.hpp"
#include "methods/progress_counters.hpp"

namespace dtlab::engine {

// Stops a run in which no insertion finished for too long: a lost wake-up or an undetected
// deadlock becomes a reported failure, not a hang. It also carries a RunMonitor's side of the
// run (run_monitor.hpp): the count of finished insertions out, the cancellation in; the threads
// then see only `stop`, which they already poll.
class Watchdog {
 public:
  Watchdog(double seconds, const ProgressCounters& progress, std::atomic<bool>& stop,
           RunMonitor* monitor = nullptr)
      : seconds_(seconds), progress_(progress), stop_(stop), monitor_(monitor), thread_([this] {
          watch();
        }) {}
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;
  ~Watchdog() {
    {
      std::lock_guard<std::mutex> guard(mutex_);
      done_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }
  // Between a run's threaded steps (a partitioned run's setups, which finish no insertion): the
  // stall is not timed until resume(), which starts its clock again. The monitor is still served.
  void pause() {
    std::lock_guard<std::mutex> guard(mutex_);
    paused_ = true;
  }
  void resume() {
    std::lock_guard<std::mutex> guard(mutex_);
    paused_ = false;
    last_ = progress_.total();
    last_change_ = std::chrono::steady_clock::now();
  }
  [[nodiscard]] bool fired() const { return fired_.load(); }
  [[nodiscard]] bool cancelled() const { return cancelled_.load(); }

 private:
  void watch() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!done_) {
      wake_.wait_for(lock, std::chrono::milliseconds(100));
      const std::uint64_t now = progress_.total();
      if (monitor_ != nullptr) {
        monitor_->done.store(now, std::memory_order_relaxed);
        if (monitor_->cancel.load(std::memory_order_relaxed)) {
          cancelled_ = true;
          stop_ = true;
          return;
        }
      }
      if (paused_) continue;
      if (now != last_) {
        last_ = now;
        last_change_ = std::chrono::steady_clock::now();
      } else if (std::chrono::duration<double>(std::chrono::steady_clock::now() - last_change_)
                     .count() > seconds_) {
        fired_ = true;
        stop_ = true;
        return;
      }
    }
  }
  double seconds_;
  const ProgressCounters& progress_;
  std::atomic<bool>& stop_;
  RunMonitor* monitor_;
  std::atomic<bool> fired_{false};
  std::atomic<bool> cancelled_{false};
  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;  // guarded by mutex_, as are the three below
  bool paused_ = false;
  std::uint64_t last_ = progress_.total();  // the count when it last changed
  std::chrono::steady_clock::time_point last_change_ = std::chrono::steady_clock::now();
  std::thread thread_;  // last: it starts once the members above are set
};

}  // namespace dtlab::engine
