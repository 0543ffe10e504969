#pragma once
// The partitioned method's map from space to threads for one pass (partitioned.cpp): the points'
// keys in the pass (their positions along the pass's Hilbert curve, pass_curve.hpp) cut into
// `parts` arcs, one a part, at the quantiles j / parts of the pass's points (or a sample of them),
// so that each part gets as many points to insert, or for two parts at a key given (the middle of
// a curve laid so that its halves are slabs). Arcs do not wrap around: each is one run of the
// curve, so that a thread inserting its arc's points in curve order walks on from one to the next.
// (A wrapping last arc, from the curve's end to its start, was two runs far apart: the thread's
// walk from the first to the second was stopped at the other parts' border, and with it every later
// walk.)
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace dtlab::engine {

class CurvePartition {
 public:
  // Cuts at the quantiles of `sorted_keys` (keys of the pass's points, or a sample of them,
  // ascending): cut j, j = 1 .. parts - 1, at position floor(j / parts x size).
  void cut(std::span<const std::uint64_t> sorted_keys, int parts) {
    cuts_.clear();
    if (parts <= 1 || sorted_keys.empty()) {
      parts_ = 1;
      return;
    }
    parts_ = parts;
    const double n = static_cast<double>(sorted_keys.size());
    for (int j = 1; j < parts; ++j) {
      const auto at = static_cast<std::size_t>(static_cast<double>(j) / parts * n);
      cuts_.push_back(sorted_keys[std::min(at, sorted_keys.size() - 1)]);
    }
  }

  // Two parts, cut at `key`: the keys below it are part 0's.
  void cut_at(std::uint64_t key) {
    cuts_.assign(1, key);
    parts_ = 2;
  }

  // The part of a point with this key: j when cut j <= key < cut j + 1 (part 0 below cut 1, the
  // last part from the last cut on).
  [[nodiscard]] int part_of(std::uint64_t key) const {
    return static_cast<int>(std::upper_bound(cuts_.begin(), cuts_.end(), key) - cuts_.begin());
  }

  [[nodiscard]] int parts() const { return parts_; }
  // The parts - 1 cuts, ascending.
  [[nodiscard]] std::span<const std::uint64_t> cuts() const { return cuts_; }

 private:
  int parts_ = 1;
  std::vector<std::uint64_t> cuts_;
};

}  // namespace dtlab::engine
