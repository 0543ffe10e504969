#pragma once
// The partitioned method's map from space to threads for one pass (partitioned.cpp): the Hilbert
// curve of the points' cube (location/insertion_order.hpp, hilbert_keys) cut into `parts` arcs,
// one a part; the last arc wraps around from the curve's end to its start. The cuts sit at the
// quantiles (j + phase) / parts of the pass's points, so each part gets as many points to insert,
// and a new phase moves every cut for the next pass.
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace dtlab::engine {

class CurvePartition {
 public:
  // Cuts at the quantiles of `sorted_keys` (keys of the pass's points, or a sample of them,
  // ascending): cut j at position floor((j + phase) / parts x size), phase in [0, 1).
  void cut(std::span<const std::uint64_t> sorted_keys, int parts, double phase) {
    cuts_.clear();
    if (parts <= 1 || sorted_keys.empty()) {
      parts_ = 1;
      return;
    }
    parts_ = parts;
    const double n = static_cast<double>(sorted_keys.size());
    for (int j = 0; j < parts; ++j) {
      const auto at = static_cast<std::size_t>((j + phase) / parts * n);
      cuts_.push_back(sorted_keys[std::min(at, sorted_keys.size() - 1)]);
    }
  }

  // The part of a point with this key: j when cut j <= key < cut j + 1; the last part also
  // takes the keys below cut 0 (the wrap).
  [[nodiscard]] int part_of(std::uint64_t key) const {
    if (parts_ == 1) return 0;
    const auto above = std::upper_bound(cuts_.begin(), cuts_.end(), key);
    return above == cuts_.begin() ? parts_ - 1 : static_cast<int>(above - cuts_.begin()) - 1;
  }

  [[nodiscard]] int parts() const { return parts_; }
  [[nodiscard]] std::span<const std::uint64_t> cuts() const { return cuts_; }

 private:
  int parts_ = 1;
  std::vector<std::uint64_t> cuts_;
};

}  // namespace dtlab::engine
