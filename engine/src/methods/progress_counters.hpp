#pragma once
// The parallel runs' count of finished insertions, for the watchdog and a RunMonitor: one counter
// a thread, each on its own cache line and written by its thread alone (a plain load and store,
// relaxed), summed by the reader. One shared counter, added to at every insertion, sent its cache
// line from core to core at every insertion of every thread.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace dtlab::engine {

class ProgressCounters {
 public:
  explicit ProgressCounters(int threads) : counts_(static_cast<std::size_t>(threads)) {}

  // One more insertion finished on `thread` (its own counter: no other thread writes it).
  void add(int thread) {
    std::atomic<std::uint64_t>& count = counts_[static_cast<std::size_t>(thread)].value;
    count.store(count.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
  }
  // The insertions finished on every thread: each counter's value at some moment of the call,
  // so a count never goes down and stops growing only when every thread stops adding.
  [[nodiscard]] std::uint64_t total() const {
    std::uint64_t sum = 0;
    for (const Count& c : counts_) sum += c.value.load(std::memory_order_relaxed);
    return sum;
  }

 private:
  struct alignas(64) Count {
    std::atomic<std::uint64_t> value{0};
  };
  std::vector<Count> counts_;
};

}  // namespace dtlab::engine
