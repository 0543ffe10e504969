#pragma once
// The partitioned method's pass curves (partitioned.cpp): a pass lays a Hilbert curve of 2^10
// cells a side, in one of the curve's orientations, through a cube twice the input's, its corner
// moved back on each axis by a whole number of cells, at most 2^9 (512 cells span the input's
// side). Every vertex's key is asked in every pass, so a key is made cheap: each point's cell on
// the 2^9 grid over the input's cube is found once, with its coordinates' bits interleaved
// (hilbert_curve.hpp, interleave); a pass's cell is that cell plus the pass's shift, added axis by
// axis in the interleaved form (the bits of the other two axes set to one carry an axis's carries
// over them, then are masked off), and its key is the automaton's on those octants: no point's
// coordinates are read for a key. docs/design.md, "The partitioned method", has the derivation.
#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <vector>

#include "dtlab/predicates/point.hpp"
#include "location/insertion_order.hpp"
#include "support/parallel_ranges.hpp"

namespace dtlab::engine {

// Every axis has an orientation of the curve that splits across it first (lay_halves).
static_assert(kHilbertStates.state_splitting(0) >= 0 && kHilbertStates.state_splitting(1) >= 0 &&
              kHilbertStates.state_splitting(2) >= 0);

class PassCurve {
 public:
  // The pass curve's grid: 2^10 cells a side over twice the input's cube.
  static constexpr unsigned kBits = 10;
  // The input's cube is 2^9 cells across; a shift is at most that on each axis, so a cell plus a
  // shift stays below 2^10.
  static constexpr std::uint32_t kInputCells = 1u << (kBits - 1);
  // The first key of the curve's second half: its cells at 2^9 or above across the axis its
  // orientation splits first (HilbertStates::state_splitting).
  static constexpr std::uint64_t kHalfKey = std::uint64_t{4} << (3 * (kBits - 1));

  // Finds the cells of points[0, points.size()) in `input` (the input's cube); `threads` share it.
  // The cells are found from the input's bounding cube, so every point's is on the grid.
  void find_cells(const std::vector<predicates::Point3>& points, const HilbertFrame& input,
                  int threads) {
    input_ = input;
    cells_.resize(points.size());
    in_parallel_ranges(
        points.size(), threads, [&](std::size_t begin, std::size_t end, std::size_t) {
          for (std::size_t i = begin; i < end; ++i) {
            const predicates::Point3& p = points[i];
            cells_[i] =
                static_cast<std::uint32_t>(interleave(cell(p.x, 0), cell(p.y, 1), cell(p.z, 2)));
          }
        });
  }
  [[nodiscard]] bool has_cells() const { return !cells_.empty(); }
  // Frees the cells (before the output, whose buffers make the run's peak memory).
  void release() { cells_ = {}; }

  // Coordinate c's cell across `axis` (0 x, 1 y, 2 z) on the input's 2^9 grid (find_cells'
  // cube); a coordinate outside the cube takes the nearest cell.
  [[nodiscard]] std::uint32_t cell(double c, int axis) const {
    return on_grid(in_cells(c, axis), kInputCells - 1);  // on_grid truncates: the floor
  }
  // The face of the input's grid across `axis` nearest coordinate c: 0 .. 2^9.
  [[nodiscard]] std::uint32_t nearest_face(double c, int axis) const {
    return on_grid(std::round(in_cells(c, axis)), kInputCells);
  }
  // A length in the grid's cells (divided first: a tiny extent's reciprocal would overflow).
  [[nodiscard]] double cells_in(double length) const {
    return input_.extent > 0 ? length / input_.extent * kInputCells : 0.0;
  }

  // Moves the curve: its cube's corner goes back by shift[a] <= kInputCells cells on axis a, and
  // the curve takes the orientation `root` (a HilbertStates state).
  void move(const std::array<std::uint32_t, 3>& shift, int root = 0) {
    assert(shift[0] <= kInputCells && shift[1] <= kInputCells && shift[2] <= kInputCells);
    assert(root >= 0 && root < kHilbertStates.states());
    shift_ = static_cast<std::uint32_t>(interleave(shift[0], shift[1], shift[2]));
    root_ = root;
    halves_axis_ = -1;
  }
  // Lays the curve so that its two halves are the two sides of the grid's face `face` (0 .. 2^9)
  // across `axis`: the cube centred there across the axis (moved back by 2^9 - face cells; on the
  // other axes by `shift`), in an orientation that fills the half below first. Then a point's
  // key is below kHalfKey exactly when its cell across the axis is below `face`.
  void lay_halves(std::array<std::uint32_t, 3> shift, int axis, std::uint32_t face) {
    assert(face <= kInputCells);
    shift[static_cast<std::size_t>(axis)] = kInputCells - face;
    move(shift, kHilbertStates.state_splitting(axis));
    halves_axis_ = axis;
  }

  // After lay_halves: whether point v's key is kHalfKey or above, known from its cell across the
  // halves' axis alone: that cell plus 2^9 - face reaches 2^9, the axis's top bit, exactly when
  // the cell is at the face or above. One addition instead of the key's five look-ups, for
  // naming the part of every vertex in a pass.
  [[nodiscard]] bool in_second_half(std::uint32_t v) const {
    assert(halves_axis_ >= 0);
    const std::uint32_t axis_bits = kAxisBits[static_cast<std::size_t>(2 - halves_axis_)];
    const std::uint32_t top_bit = axis_bits & (std::uint32_t{7} << (3 * (kBits - 1)));
    return (add_axis(cells_[v], shift_, axis_bits) & top_bit) != 0;
  }

  // Point v's key on the current curve.
  [[nodiscard]] std::uint64_t key(std::uint32_t v) const {
    return kHilbertStates.key_of_octants(add_cells(cells_[v], shift_), kBits, root_);
  }

  // Two interleaved cells added axis by axis (no axis may overflow kBits bits).
  static constexpr std::uint32_t add_cells(std::uint32_t a, std::uint32_t b) {
    std::uint32_t sum = 0;
    for (const std::uint32_t axis : kAxisBits) sum |= add_axis(a, b, axis);
    return sum;
  }

 private:
  // Each axis's bits in an interleaved code of kBits levels: z at 3 b, y at 3 b + 1, x at 3 b + 2.
  static constexpr std::array<std::uint32_t, 3> kAxisBits = {0x09249249u, 0x12492492u, 0x24924924u};

  // The bits `axis_bits` (one axis's) of two interleaved cells added: the other axes' bits, set
  // to one in a, carry the axis's carries over them, and the mask drops what they caught.
  static constexpr std::uint32_t add_axis(std::uint32_t a, std::uint32_t b,
                                          std::uint32_t axis_bits) {
    return ((a | ~axis_bits) + (b & axis_bits)) & axis_bits;
  }

  // c's distance from the cube's lower face across `axis`, in cells.
  [[nodiscard]] double in_cells(double c, int axis) const {
    return cells_in(c - predicates::coordinate(input_.lo, axis));
  }

  // x as a whole number in [0, most], truncated (NaN, from coordinates too far apart to
  // subtract: 0).
  static std::uint32_t on_grid(double x, std::uint32_t most) {
    if (!(x > 0)) return 0;
    return static_cast<std::uint32_t>(std::min(x, static_cast<double>(most)));
  }

  HilbertFrame input_{};              // the input's cube
  std::vector<std::uint32_t> cells_;  // each point's cell on the input's 2^9 grid, interleaved
  std::uint32_t shift_ = 0;           // the current pass's shift, interleaved
  int root_ = 0;                      // the current curve's orientation
  int halves_axis_ = -1;              // the axis its halves lie across (lay_halves), or -1
};

}  // namespace dtlab::engine
