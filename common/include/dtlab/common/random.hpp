#pragma once
// Platform-independent random numbers, shared by the engine (its seeded insertion order) and the
// generators: std::mt19937_64's output sequence is fixed by the standard, while
// std::uniform_*_distribution and std::shuffle are not, so dtlab converts the raw 64-bit words
// itself.
#include <cmath>
#include <cstdint>
#include <random>

namespace dtlab::common {

class Random {
  __extension__ using Wide = unsigned __int128;  // GCC and Clang on 64-bit targets

 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  // Uniform in [0, 1): 53 random bits.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  // Uniform integer in [0, bound), bound > 0 (Lemire's multiply-and-reject).
  std::uint64_t below(std::uint64_t bound) {
    while (true) {
      const Wide m = static_cast<Wide>(engine_()) * bound;
      const auto low = static_cast<std::uint64_t>(m);
      if (low >= bound || low >= (-bound) % bound) return static_cast<std::uint64_t>(m >> 64);
    }
  }
  // Standard normal (Box-Muller, both values used).
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u = 0.0;
    do {
      u = uniform();
    } while (u == 0.0);
    const double v = uniform();
    const double r = std::sqrt(-2.0 * std::log(u));
    spare_ = r * std::sin(2.0 * M_PI * v);
    has_spare_ = true;
    return r * std::cos(2.0 * M_PI * v);
  }

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace dtlab::common
