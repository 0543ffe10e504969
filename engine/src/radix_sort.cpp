#include "radix_sort.hpp"

#include <algorithm>
#include <array>
#include <vector>

namespace dtlab::engine {

void stable_sort_by_key(KeyedId* items, KeyedId* scratch, std::size_t n) {
  constexpr int kDigits = 8;
  std::vector<std::array<std::size_t, 256>> count(kDigits);
  for (auto& c : count) c.fill(0);
  for (std::size_t i = 0; i < n; ++i) {
    for (int d = 0; d < kDigits; ++d) ++count[d][(items[i].first >> (8 * d)) & 0xFF];
  }
  auto* from = items;
  auto* to = scratch;
  for (int d = 0; d < kDigits; ++d) {
    auto& c = count[static_cast<std::size_t>(d)];
    if (std::any_of(c.begin(), c.end(), [n](std::size_t k) { return k == n; })) continue;
    std::size_t sum = 0;
    for (auto& k : c) {
      const std::size_t here = k;
      k = sum;
      sum += here;
    }
    for (std::size_t i = 0; i < n; ++i) to[c[(from[i].first >> (8 * d)) & 0xFF]++] = from[i];
    std::swap(from, to);
  }
  if (from != items) std::copy(from, from + n, items);
}

}  // namespace dtlab::engine
