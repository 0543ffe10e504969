#pragma once
// The Hilbert curve's key, two ways (docs/design.md, "Walk mode", derives both):
// - hilbert_key_by_transforms: Skilling's construction, the frames' reflections and exchanges
//   applied to the coordinates' lower bits, then a Gray decode: the definition.
// - HilbertStates: the same curve as a finite automaton, derived at compile time from the
//   definition. A cell's sub-curve is its parent's under a symmetry of the cube, and the order in
//   which a cell's curve visits its eight children names that symmetry (only the identity keeps
//   all eight octants in place; a sub-curve run backwards is the curve's image under the
//   reflection that swaps its ends, so it is one of them), so the automaton's states are the
//   children's orders met from the root down, and a key is one table look-up per two levels
//   instead of the transforms of every level. hilbert_key (insertion_order.hpp) uses the
//   automaton; the tests compare the two.
#include <array>
#include <cassert>
#include <cstddef>
#include <cstdint>

namespace dtlab::engine {

// Bit b of v moved to bit 3 b (v < 2^21), by halving steps.
constexpr std::uint64_t spread_bits(std::uint32_t v) {
  std::uint64_t s = v & 0x1FFFFFu;
  s = (s | (s << 32)) & 0x001F00000000FFFFull;
  s = (s | (s << 16)) & 0x001F0000FF0000FFull;
  s = (s | (s << 8)) & 0x100F00F00F00F00Full;
  s = (s | (s << 4)) & 0x10C30C30C30C30C3ull;
  s = (s | (s << 2)) & 0x1249249249249249ull;
  return s;
}

// The octants of every level side by side: x y z's bits interleaved (bit b of x at 3 b + 2, of y
// at 3 b + 1, of z at 3 b), the highest level first.
constexpr std::uint64_t interleave(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
  return (spread_bits(x) << 2) | (spread_bits(y) << 1) | spread_bits(z);
}

// The definition, after Skilling ("Programming the Hilbert curve", 2004): the curve is built from
// the most significant bit down; at each level the sub-cube's frame is a reflection and an axis
// exchange of the parent's, and applying those transformations to the lower bits of the
// coordinates first (the loop over the levels), then Gray-decoding the bit columns, leaves the
// "transposed" index, whose bits interleaved axis by axis are the distance along the curve.
// 1 <= bits <= 21.
constexpr std::uint64_t hilbert_key_by_transforms(std::uint32_t x, std::uint32_t y, std::uint32_t z,
                                                  unsigned bits) {
  assert(bits >= 1 && bits <= 21);
  // Branch-free: each bit's test is a mask (0 or all ones).
  std::array<std::uint32_t, 3> axis{x, y, z};
  for (unsigned level = bits - 1; level > 0; --level) {
    const std::uint32_t lower = (1u << level) - 1;
    for (std::uint32_t& a : axis) {
      const std::uint32_t set = 0u - ((a >> level) & 1u);
      // set: reflect the lower bits of the first axis; clear: exchange them with this axis
      // (nothing when this axis is the first).
      const std::uint32_t differ = (axis[0] ^ a) & lower & ~set;
      axis[0] ^= (lower & set) | differ;
      a ^= differ;
    }
  }
  axis[1] ^= axis[0];
  axis[2] ^= axis[1];
  std::uint32_t flip = 0;
  for (unsigned level = bits - 1; level > 0; --level) {
    flip ^= ((1u << level) - 1) & (0u - ((axis[2] >> level) & 1u));
  }
  for (std::uint32_t& a : axis) a ^= flip;
  // Interleave, most significant first, axis 0 before 1 before 2: bit b of axis k lands at
  // 3 b + 2 - k.
  return interleave(axis[0], axis[1], axis[2]);
}

// The automaton. An octant is x y z's bits at one level, x's highest (0..7); a state's entry for
// two levels' octants (the higher one's in bits 3-5) gives the six key bits of those levels and
// the state after them.
class HilbertStates {
 public:
  // The most states the derivation makes room for: the cube has 48 symmetries.
  static constexpr int kMaxStates = 48;
  struct Step {
    std::uint8_t digits;  // the key's six bits for the two levels
    std::uint8_t next;    // the state below them
  };

  constexpr HilbertStates() {
    // A state is known by the digits its curve gives the eight children of a cell (the child
    // octant's position along the cell's curve), found on a cell that has it; its children's
    // states are those of the children's own children, on the definition's keys one and two
    // levels down (a coarser key is the finer one's prefix: the tests check it).
    std::array<std::array<std::uint8_t, 8>, kMaxStates> order{};
    std::array<std::array<std::uint32_t, 4>, kMaxStates> cell{};  // x, y, z, level
    std::array<std::array<std::uint8_t, 8>, kMaxStates> child{};
    auto orders_of = [](std::uint32_t x, std::uint32_t y, std::uint32_t z, std::uint32_t level) {
      std::array<std::uint8_t, 8> digits{};
      for (std::uint32_t o = 0; o < 8; ++o) {
        digits[o] = static_cast<std::uint8_t>(
            hilbert_key_by_transforms(2 * x + (o >> 2), 2 * y + ((o >> 1) & 1), 2 * z + (o & 1),
                                      level + 1) &
            7);
      }
      return digits;
    };
    order[0] = orders_of(0, 0, 0, 0);  // the root: the whole cube
    cell[0] = {0, 0, 0, 0};
    states_ = 1;
    for (int s = 0; s < states_; ++s) {
      const auto [x, y, z, level] = cell[static_cast<std::size_t>(s)];
      for (std::uint32_t o = 0; o < 8; ++o) {
        const std::uint32_t cx = 2 * x + (o >> 2);
        const std::uint32_t cy = 2 * y + ((o >> 1) & 1);
        const std::uint32_t cz = 2 * z + (o & 1);
        const auto digits = orders_of(cx, cy, cz, level + 1);
        int found = 0;
        while (found < states_ && order[static_cast<std::size_t>(found)] != digits) ++found;
        if (found == states_) {
          // More states than the cube's symmetries cannot be a curve's; the compiler stops here.
          if (states_ == kMaxStates) throw "hilbert_key_by_transforms has over 48 states";
          order[static_cast<std::size_t>(found)] = digits;
          cell[static_cast<std::size_t>(found)] = {cx, cy, cz, level + 1};
          ++states_;
        }
        child[static_cast<std::size_t>(s)][o] = static_cast<std::uint8_t>(found);
      }
    }
    for (std::size_t s = 0; s < static_cast<std::size_t>(states_); ++s) {
      for (std::size_t high = 0; high < 8; ++high) {
        const std::uint8_t middle = child[s][high];
        single_[s][high] = {order[s][high], middle};
        for (std::size_t low = 0; low < 8; ++low) {
          pairs_[s][high * 8 + low] = {
              static_cast<std::uint8_t>((order[s][high] << 3) | order[middle][low]),
              child[middle][low]};
        }
      }
    }
  }

  [[nodiscard]] constexpr int states() const { return states_; }

  // A state whose curve fills the half of its cube below the middle across `axis` (0 x, 1 y,
  // 2 z) before the half above: its first four octants are those with that axis's bit clear.
  // Every axis has one (the states are the curve's orientations; -1 would mean a bad table).
  [[nodiscard]] constexpr int state_splitting(int axis) const {
    const int bit = 2 - axis;  // x's bit is an octant's highest
    for (int s = 0; s < states_; ++s) {
      bool splits = true;
      for (int o = 0; o < 8; ++o) {
        const bool upper = ((o >> bit) & 1) != 0;
        splits = splits &&
                 (single_[static_cast<std::size_t>(s)][static_cast<std::size_t>(o)].digits >= 4) ==
                     upper;
      }
      if (splits) return s;
    }
    return -1;
  }

  // The key of cell (x, y, z) of the 2^bits grid (bits <= 21), as hilbert_key_by_transforms.
  [[nodiscard]] constexpr std::uint64_t key(std::uint32_t x, std::uint32_t y, std::uint32_t z,
                                            unsigned bits) const {
    return key_of_octants(interleave(x, y, z), bits);
  }

  // The same key from the cell's coordinates interleaved (interleave), on the curve whose cube is
  // in orientation `root` (0: the definition's; another state: the curve under a symmetry of the
  // cube, a Hilbert curve too).
  [[nodiscard]] constexpr std::uint64_t key_of_octants(std::uint64_t octants, unsigned bits,
                                                       int root = 0) const {
    assert(bits >= 1 && bits <= 21);  // 3 bits a level in 63
    assert(root >= 0 && root < states_);
    std::uint64_t key = 0;
    auto state = static_cast<std::uint8_t>(root);
    unsigned level = bits;
    if (level % 2 == 1) {  // an odd count: the top level alone
      --level;
      const Step s = single_[state][(octants >> (3 * level)) & 7];
      key = s.digits;
      state = s.next;
    }
    while (level > 0) {
      level -= 2;
      const Step s = pairs_[state][(octants >> (3 * level)) & 63];
      key = (key << 6) | s.digits;
      state = s.next;
    }
    return key;
  }

 private:
  int states_ = 0;
  std::array<std::array<Step, 64>, kMaxStates> pairs_{};
  std::array<std::array<Step, 8>, kMaxStates> single_{};
};

// Built by the compiler: no start-up cost, and a derivation that failed would not compile.
inline constexpr HilbertStates kHilbertStates{};

}  // namespace dtlab::engine
