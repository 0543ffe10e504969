#pragma once
// Insertion orders. The DAG mode inserts in the paper's random permutation. The walk mode inserts
// in BRIO rounds (Amenta, Choi and Rote 2003: round k is a random sample of about n / 2^k points,
// so the rounds keep the expected cost of a random order) and orders each round along a Hilbert
// curve, so that consecutive points are close and the walk from the last insertion is short.
// Both are functions of the seed alone. docs/design.md ("Walk mode") derives the curve's key.
#include <cstdint>
#include <vector>

#include "dtlab/predicates/point.hpp"
#include "location/hilbert_curve.hpp"

namespace dtlab::engine {

// A uniformly random permutation of 0..n-1.
std::vector<std::uint32_t> random_order(std::size_t n, std::uint64_t seed);

// The position of cell (x, y, z) of a 2^bits grid along the Hilbert curve that fills it
// (bits <= 21, so the key fits 63 bits). Consecutive keys name face-adjacent cells; the key on a
// coarser grid is the finer key's prefix. By the automaton of hilbert_curve.hpp.
inline std::uint64_t hilbert_key(std::uint32_t x, std::uint32_t y, std::uint32_t z, unsigned bits) {
  return kHilbertStates.key(x, y, z, bits);
}

// The cube a Hilbert curve fills: its corner and side.
struct HilbertFrame {
  predicates::Point3 lo;
  double extent;
};

// Reorders `ids` (a random order) into BRIO rounds, each sorted along the Hilbert curve of the
// points' bounding box: the last round is the second half of `ids`, the one before it the
// preceding quarter, and so on down to a first round of at most kFirstRound points. `threads`
// share the keys and the sorts; the order is the same for any number of them. `frame`: that
// box's cube, when the caller has it (hilbert_frame of all the points, when `ids` lists them
// all: a box does not depend on the order its points are read in); else it is found from
// points[ids], which reads them in the random order.
void brio_hilbert_order(const std::vector<predicates::Point3>& points,
                        std::vector<std::uint32_t>& ids, int threads = 1,
                        const HilbertFrame* frame = nullptr);
// The cube around the first `count` points, as brio_hilbert_order takes it for its points.
HilbertFrame hilbert_frame(const std::vector<predicates::Point3>& points, std::size_t count,
                           int threads = 1);
// The walk mode's order's grid: 2^21 cells a side (the most that fits a 63-bit key).
inline constexpr unsigned kHilbertBits = 21;
// p's key on the curve of a 2^bits grid through `frame` (a point outside the cube takes its
// nearest cell; bits <= kHilbertBits).
std::uint64_t hilbert_key_in(const HilbertFrame& frame, const predicates::Point3& p,
                             unsigned bits = kHilbertBits);

inline constexpr std::size_t kFirstRound = 256;

}  // namespace dtlab::engine
