// A test of the engine's internals: it includes headers from engine/src (dtlab_internal_test).
// The partitioned method's pass curves: a point's key is the Hilbert key (the automaton's, which
// walk_mode_test checks against the definition) of its cell on the input's 2^9 grid plus the
// pass's shift, found from the interleaved cells by the axis-wise addition; the curve's
// orientations that split across each axis first.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "location/insertion_order.hpp"
#include "methods/pass_curve.hpp"

namespace dtlab::test {
namespace {

using engine::PassCurve;

TEST(PassCurve, InterleavedAdditionAddsEachAxis) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<std::uint32_t> below(0, PassCurve::kInputCells - 1);
  for (int i = 0; i < 100000; ++i) {
    const std::array<std::uint32_t, 3> a{below(rng), below(rng), below(rng)};
    const std::array<std::uint32_t, 3> b{below(rng), below(rng), below(rng)};
    const auto sum =
        PassCurve::add_cells(static_cast<std::uint32_t>(engine::interleave(a[0], a[1], a[2])),
                             static_cast<std::uint32_t>(engine::interleave(b[0], b[1], b[2])));
    ASSERT_EQ(sum, engine::interleave(a[0] + b[0], a[1] + b[1], a[2] + b[2]))
        << a[0] << " " << a[1] << " " << a[2] << " + " << b[0] << " " << b[1] << " " << b[2];
  }
  // The largest sums: the last cell and the largest shift (a slab's, 2^9), every bit carrying.
  const std::uint32_t top = PassCurve::kInputCells - 1;
  const std::uint32_t most = PassCurve::kInputCells;
  EXPECT_EQ(PassCurve::add_cells(static_cast<std::uint32_t>(engine::interleave(top, top, top)),
                                 static_cast<std::uint32_t>(engine::interleave(most, most, most))),
            engine::interleave(top + most, top + most, top + most));
}

TEST(PassCurve, KeyIsTheHilbertKeyOfTheShiftedCell) {
  // A box that is not a cube, off the origin: the cells are cubes of its largest side / 2^9.
  const engine::HilbertFrame frame{{-3.0, 10.0, 0.5}, 8.0};
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> x(-3.0, 5.0);
  std::uniform_real_distribution<double> y(10.0, 14.0);
  std::uniform_real_distribution<double> z(0.5, 2.5);
  std::vector<predicates::Point3> points;
  for (int i = 0; i < 20000; ++i) points.push_back({x(rng), y(rng), z(rng)});
  points.push_back({-3.0, 10.0, 0.5});  // the cube's corners: the first cell and the last
  points.push_back({5.0, 18.0, 8.5});
  points.push_back({-100.0, 1e9, 0.5});  // outside: the nearest cells
  PassCurve curve;
  curve.find_cells(points, frame, 2);
  auto cell = [&](double c, double lo) {
    const double scaled = (c - lo) / frame.extent * PassCurve::kInputCells;
    return static_cast<std::uint32_t>(
        std::clamp(scaled, 0.0, static_cast<double>(PassCurve::kInputCells - 1)));
  };
  for (const std::array<std::uint32_t, 3> shift :
       {std::array<std::uint32_t, 3>{0, 0, 0}, {511, 511, 511}, {256, 17, 400}, {512, 3, 512}}) {
    // The definition's orientation (hilbert_key's), and another.
    for (const int root : {0, engine::kHilbertStates.state_splitting(1)}) {
      curve.move(shift, root);
      for (std::size_t v = 0; v < points.size(); ++v) {
        const predicates::Point3& p = points[v];
        const std::uint32_t x = cell(p.x, frame.lo.x) + shift[0];
        const std::uint32_t y = cell(p.y, frame.lo.y) + shift[1];
        const std::uint32_t z = cell(p.z, frame.lo.z) + shift[2];
        const std::uint64_t key = curve.key(static_cast<std::uint32_t>(v));
        ASSERT_EQ(key, engine::kHilbertStates.key_of_octants(engine::interleave(x, y, z),
                                                             PassCurve::kBits, root))
            << "point " << v << ", orientation " << root;
        if (root == 0) {
          ASSERT_EQ(key, engine::hilbert_key(x, y, z, PassCurve::kBits)) << "point " << v;
        }
      }
    }
  }
  // The corners' and the outsider's cells, as the clamp gives them.
  curve.move({0, 0, 0});
  EXPECT_EQ(curve.key(20000), engine::hilbert_key(0, 0, 0, PassCurve::kBits));
  EXPECT_EQ(curve.key(20001), engine::hilbert_key(511, 511, 511, PassCurve::kBits));
  EXPECT_EQ(curve.key(20002), engine::hilbert_key(0, 511, 0, PassCurve::kBits));
}

// Every axis has an orientation of the curve that fills the half of its cube below the middle
// across that axis first (the partitioned method's slabs, each one arc): with it a cell's key is
// below half the keys exactly when its coordinate across the axis is, and the keys still trace
// a Hilbert curve: every cell once, consecutive keys on face-adjacent cells.
TEST(PassCurve, EachAxisHasAnOrientationWhoseHalvesAreSlabs) {
  for (int axis = 0; axis < 3; ++axis) {
    const int root = engine::kHilbertStates.state_splitting(axis);
    ASSERT_GE(root, 0) << axis;
    constexpr unsigned kBits = 3;
    constexpr std::uint32_t kSide = 1u << kBits;
    std::vector<std::array<std::uint32_t, 3>> cell_at(kSide * kSide * kSide, {kSide, 0, 0});
    for (std::uint32_t x = 0; x < kSide; ++x) {
      for (std::uint32_t y = 0; y < kSide; ++y) {
        for (std::uint32_t z = 0; z < kSide; ++z) {
          const std::uint64_t key =
              engine::kHilbertStates.key_of_octants(engine::interleave(x, y, z), kBits, root);
          ASSERT_LT(key, cell_at.size());
          cell_at[key] = {x, y, z};
          const std::array<std::uint32_t, 3> c{x, y, z};
          EXPECT_EQ(key < cell_at.size() / 2, c[static_cast<std::size_t>(axis)] < kSide / 2)
              << axis << ": " << x << " " << y << " " << z;
        }
      }
    }
    for (std::size_t k = 0; k < cell_at.size(); ++k) {
      ASSERT_LT(cell_at[k][0], kSide) << axis << ": key " << k << " names no cell";
      if (k == 0) continue;
      std::uint32_t steps = 0;
      for (std::size_t a = 0; a < 3; ++a) {
        steps += cell_at[k][a] > cell_at[k - 1][a] ? cell_at[k][a] - cell_at[k - 1][a]
                                                   : cell_at[k - 1][a] - cell_at[k][a];
      }
      EXPECT_EQ(steps, 1u) << axis << ": keys " << k - 1 << " and " << k;
    }
    // The pass curve's grid: below kHalfKey exactly below 2^9 across the axis.
    std::mt19937 rng(3);
    std::uniform_int_distribution<std::uint32_t> any(0, 2 * PassCurve::kInputCells - 1);
    for (int i = 0; i < 10000; ++i) {
      const std::array<std::uint32_t, 3> c{any(rng), any(rng), any(rng)};
      const std::uint64_t key = engine::kHilbertStates.key_of_octants(
          engine::interleave(c[0], c[1], c[2]), PassCurve::kBits, root);
      ASSERT_EQ(key < PassCurve::kHalfKey,
                c[static_cast<std::size_t>(axis)] < PassCurve::kInputCells)
          << axis;
    }
  }
}

// lay_halves: the curve's halves are the two sides of the face given, across the axis given,
// whatever the other axes' shifts, for every face from the grid's first to its last, and
// in_second_half names them without the key; the nearest face; the cells of coordinates on a
// cube too small for the reciprocal of its side.
TEST(PassCurve, HalvesAreTheSidesOfTheFaceGiven) {
  const engine::HilbertFrame frame{{0.0, 0.0, 0.0}, 1.0};
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<predicates::Point3> points(20000);
  for (auto& p : points) p = {unit(rng), unit(rng), unit(rng)};
  PassCurve curve;
  curve.find_cells(points, frame, 2);
  for (int axis = 0; axis < 3; ++axis) {
    for (const std::uint32_t face : {0u, 1u, 200u, 511u, 512u}) {
      curve.lay_halves({301, 77, 5}, axis, face);
      std::size_t below = 0;
      for (std::size_t v = 0; v < points.size(); ++v) {
        const predicates::Point3& p = points[v];
        const double c = predicates::coordinate(p, axis);
        const bool lower = curve.cell(c, axis) < face;
        below += lower ? 1 : 0;
        ASSERT_EQ(curve.key(static_cast<std::uint32_t>(v)) < PassCurve::kHalfKey, lower)
            << "axis " << axis << ", face " << face << ", point " << v;
        ASSERT_EQ(curve.in_second_half(static_cast<std::uint32_t>(v)), !lower)
            << "axis " << axis << ", face " << face << ", point " << v;
      }
      if (face == 0) {
        EXPECT_EQ(below, 0u);
      }
      if (face == 512) {
        EXPECT_EQ(below, points.size());
      }
      if (face == 200) {
        EXPECT_NEAR(static_cast<double>(below) / points.size(), 200.0 / 512, 0.02);
      }
    }
  }
  EXPECT_EQ(curve.nearest_face(0.0, 0), 0u);
  EXPECT_EQ(curve.nearest_face(0.5, 1), 256u);
  EXPECT_EQ(curve.nearest_face(0.5 + 0.4 / 512, 2), 256u);
  EXPECT_EQ(curve.nearest_face(0.5 + 0.6 / 512, 2), 257u);
  EXPECT_EQ(curve.nearest_face(1.0, 0), 512u);
  EXPECT_EQ(curve.nearest_face(7.0, 0), 512u);
  EXPECT_EQ(curve.nearest_face(-7.0, 0), 0u);
  // A cube whose side's reciprocal overflows: the cells are still on the grid, in order.
  const double tiny = 1e-310;
  PassCurve small;
  small.find_cells({{0, 0, 0}, {tiny, tiny, tiny}}, {{0, 0, 0}, tiny}, 1);
  EXPECT_EQ(small.cell(0.0, 0), 0u);
  EXPECT_EQ(small.cell(tiny / 2, 1), 256u);
  EXPECT_EQ(small.cell(tiny, 2), 511u);
  EXPECT_EQ(small.nearest_face(tiny, 2), 512u);
}

}  // namespace
}  // namespace dtlab::test
