#pragma once
// Turns fuzzer bytes into point sets: small integers (so that ties, coplanar and cospherical
// subsets are frequent), scaled by a power of two taken from the input.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "dtlab/predicates/point.hpp"

namespace dtlab::fuzz {

class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  [[nodiscard]] bool empty() const { return pos_ >= size_; }
  std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
  std::int16_t int16() {
    const auto lo = byte();
    const auto hi = byte();
    return static_cast<std::int16_t>(static_cast<std::uint16_t>(lo | (hi << 8)));
  }
  double raw_double() {
    std::uint64_t bits = 0;
    for (int i = 0; i < 8; ++i) bits |= static_cast<std::uint64_t>(byte()) << (8 * i);
    double v = 0;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }
  [[nodiscard]] std::size_t remaining() const { return pos_ < size_ ? size_ - pos_ : 0; }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

// First byte: scale exponent (-64..63); then int16 triples, range reduced by the second byte so
// that small grids (many ties) are common.
inline std::vector<predicates::Point3> points_from_bytes(const std::uint8_t* data, std::size_t size,
                                                         std::size_t max_points) {
  ByteReader in(data, size);
  const int exponent = static_cast<int>(in.byte() % 128) - 64;
  const int modulus = 2 + in.byte() % 64;
  std::vector<predicates::Point3> points;
  while (in.remaining() >= 6 && points.size() < max_points) {
    const double x = in.int16() % modulus;
    const double y = in.int16() % modulus;
    const double z = in.int16() % modulus;
    points.push_back({std::ldexp(x, exponent), std::ldexp(y, exponent), std::ldexp(z, exponent)});
  }
  return points;
}

}  // namespace dtlab::fuzz
