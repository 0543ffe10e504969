#pragma once
// Where an inserting thread of a parallel method takes its next point from.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

namespace dtlab::engine {

// Points not yet inserted by a thread: its own list (static, strips, blocks) or the shared
// index (dynamic), plus the points it gave up, retried after the rest.
class WorkSource {
 public:
  WorkSource(const std::vector<std::uint32_t>* own, std::atomic<std::size_t>* shared_index,
             const std::vector<std::uint32_t>* shared)
      : own_(own), shared_index_(shared_index), shared_(shared) {}
  std::optional<std::uint32_t> next() {
    if (own_ != nullptr && position_ < own_->size()) return (*own_)[position_++];
    if (shared_index_ != nullptr) {
      const std::size_t i = shared_index_->fetch_add(1, std::memory_order_relaxed);
      if (i < shared_->size()) return (*shared_)[i];
    }
    if (retry_position_ < retry_.size()) return retry_[retry_position_++];
    return std::nullopt;
  }
  // Queues v again; false when it was given up more than `limit` times (then the caller
  // abandons it).
  bool retry_later(std::uint32_t v, int limit) {
    if (++attempts_[v] > limit) return false;
    retry_.push_back(v);
    return true;
  }
  // Lock conflicts end when the other thread finishes. A location fails under an exact kernel
  // only while another thread's rollback races the descent; with the back-off
  // (optimistic_worker.hpp), 64 attempts sleep 28 to 56 ms, longer than any insertion takes even
  // under --stress, so a location
  // that fails that often is an inexact kernel's contradiction, which every retry repeats.
  static constexpr int kMaxLockAttempts = 100000;
  static constexpr int kMaxLocationAttempts = 64;

 private:
  const std::vector<std::uint32_t>* own_;
  std::size_t position_ = 0;
  std::atomic<std::size_t>* shared_index_;
  const std::vector<std::uint32_t>* shared_;
  std::vector<std::uint32_t> retry_;
  std::size_t retry_position_ = 0;
  std::unordered_map<std::uint32_t, int> attempts_;
};

}  // namespace dtlab::engine
