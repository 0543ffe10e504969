// Every generator: deterministic bytes for a seed, its defining property, N handling.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <set>
#include <utility>

#include "dtlab/engine/point_set_info.hpp"
#include "dtlab/generators/generators.hpp"
#include "dtlab/predicates/kernels.hpp"

namespace dtlab::test {
namespace {

using generators::generate;
using predicates::Point3;

std::uint64_t digest(const std::vector<Point3>& p) {
  std::uint64_t h = 1469598103934665603ull;
  for (const Point3& q : p) {
    for (const double c : {q.x, q.y, q.z})
      h = (h ^ std::bit_cast<std::uint64_t>(c)) * 1099511628211ull;
  }
  return h;
}

bool in_unit_cube(const Point3& p) {
  return p.x >= 0 && p.x <= 1 && p.y >= 0 && p.y <= 1 && p.z >= 0 && p.z <= 1;
}

TEST(Generators, DeterministicPerSeedAndDifferentAcrossSeeds) {
  for (const std::string& family : generators::families()) {
    const auto a = generate(family, 1000, 42).points;
    const auto b = generate(family, 1000, 42).points;
    EXPECT_EQ(digest(a), digest(b)) << family;
    if (family != "grid" && family != "lattice") {
      EXPECT_NE(digest(a), digest(generate(family, 1000, 43).points)) << family;
    }
  }
}

TEST(Generators, ExactCountOrANote) {
  for (const std::string& family : generators::families()) {
    const auto g = generate(family, 1001, 1);
    if (family == "grid" || family == "lattice") {
      EXPECT_EQ(g.points.size(), 1000u) << family;  // k = round(cbrt(1001)) = 10
      EXPECT_FALSE(g.note.empty());
    } else {
      EXPECT_EQ(g.points.size(), 1001u) << family;
      EXPECT_TRUE(g.note.empty()) << family;
    }
  }
}

TEST(Generators, PaperDistributionsStayInTheUnitCube) {
  for (const std::string family : {"uniform", "normal", "cluster", "grid", "sphere", "planes",
                                   "cospherical", "duplicates", "coplanar", "collinear"}) {
    for (const Point3& p : generate(family, 2000, 5).points) ASSERT_TRUE(in_unit_cube(p)) << family;
  }
}

TEST(Generators, GridPointsAreOnTheDyadicGrid) {
  const auto p = generate("grid", 125, 1).points;
  ASSERT_EQ(p.size(), 125u);
  const double h = 0.25;  // k = 5: the largest power of two with 4 h <= 1
  std::set<double> xs;
  for (const Point3& q : p) {
    for (const double c : {q.x, q.y, q.z}) {
      EXPECT_EQ(c / h, std::round(c / h));
      EXPECT_LE(c, 1.0);
    }
    xs.insert(q.x);
  }
  EXPECT_EQ(xs.size(), 5u);
}

TEST(Generators, SpherePointsAreOnTheSphereWithinRounding) {
  for (const Point3& q : generate("sphere", 1000, 9).points) {
    const double r = std::sqrt((q.x - 0.5) * (q.x - 0.5) + (q.y - 0.5) * (q.y - 0.5) +
                               (q.z - 0.5) * (q.z - 0.5));
    EXPECT_NEAR(r, 0.5, 1e-15);
  }
}

TEST(Generators, CosphericalIntegerHalfIsExactlyCospherical) {
  const auto p = generate("cospherical", 400, 2).points;
  // The second half lies on concentric spheres around (0.5, 0.5, 0.5): squared radii exact.
  std::set<double> radii;
  for (std::size_t i = 200; i < p.size(); ++i) {
    const double dx = p[i].x - 0.5, dy = p[i].y - 0.5, dz = p[i].z - 0.5;
    radii.insert(dx * dx + dy * dy + dz * dz);
  }
  EXPECT_LE(radii.size(), 4u);
  // Any 5 of them on one sphere are exactly cospherical for the exact kernel: four that span a
  // tetrahedron (searched for, not assumed) and every other point of that sphere.
  std::vector<Point3> same;
  const double r0 = *radii.begin();
  for (std::size_t i = 200; i < p.size(); ++i) {
    const double dx = p[i].x - 0.5, dy = p[i].y - 0.5, dz = p[i].z - 0.5;
    if (dx * dx + dy * dy + dz * dz == r0) same.push_back(p[i]);
  }
  ASSERT_GE(same.size(), 5u);
  std::size_t d = 3;
  while (d < same.size() &&
         predicates::ExactKernel::orient3d(same[0], same[1], same[2], same[d]) == 0) {
    ++d;
  }
  ASSERT_LT(d, same.size()) << "no four points on the sphere span a tetrahedron";
  int checked = 0;
  for (std::size_t e = 3; e < same.size(); ++e) {
    if (e == d) continue;
    EXPECT_EQ(predicates::ExactKernel::insphere(same[0], same[1], same[2], same[d], same[e]), 0);
    ++checked;
  }
  EXPECT_GE(checked, 1);
}

TEST(Generators, DegenerateFamiliesHaveTheirDefiningProperty) {
  EXPECT_EQ(engine::analyze(generate("duplicates", 1000, 1).points).duplicates, 500u);
  const auto near = generate("near-duplicates", 1000, 1).points;
  EXPECT_EQ(near[1].x, std::nextafter(near[0].x, 2.0));
  EXPECT_EQ(engine::analyze(near).duplicates, 0u);
  EXPECT_EQ(engine::analyze(generate("coplanar", 500, 1).points).dimension, 2);
  EXPECT_EQ(engine::analyze(generate("collinear", 500, 1).points).dimension, 1);
  EXPECT_EQ(engine::analyze(generate("planes", 500, 1).points).dimension, 3);
  for (const Point3& q : generate("planes", 400, 1).points) {
    EXPECT_TRUE(q.z == 0.25 || q.z == 0.75 || q.x == 0.5 || q.y == 0.5);
  }
  for (const Point3& q : generate("lattice", 27, 1).points) {
    EXPECT_GE(q.x, 0x1p30);
    EXPECT_EQ(q.x, std::floor(q.x));
  }
  // tiny and huge: the uniform family's points (same seed) times 1e-150 and 1e150, exactly as
  // the double product rounds them.
  const auto unit = generate("uniform", 100, 1).points;
  for (const auto& [family, factor] : {std::pair{"tiny", 1e-150}, std::pair{"huge", 1e150}}) {
    const auto scaled = generate(family, 100, 1).points;
    ASSERT_EQ(scaled.size(), unit.size()) << family;
    for (std::size_t i = 0; i < unit.size(); ++i) {
      EXPECT_EQ(scaled[i].x, unit[i].x * factor) << family << " " << i;
      EXPECT_EQ(scaled[i].y, unit[i].y * factor) << family << " " << i;
      EXPECT_EQ(scaled[i].z, unit[i].z * factor) << family << " " << i;
    }
  }
}

TEST(Generators, BadSpecsAndCounts) {
  EXPECT_THROW(generate("nosuch", 10, 1), std::invalid_argument);
  EXPECT_THROW(generate("uniform", 0, 1), std::invalid_argument);
  EXPECT_THROW(generate("uniform", generators::kMaxPoints + 1, 1), std::invalid_argument);
  std::string family;
  std::int64_t n = 0;
  EXPECT_TRUE(generators::parse_spec("uniform:100", family, n));
  EXPECT_EQ(n, 100);
  EXPECT_FALSE(generators::parse_spec("data/file.xyz", family, n));
  EXPECT_THROW(generators::parse_spec("uniform:abc", family, n), std::invalid_argument);
  EXPECT_THROW(generators::parse_spec("nosuch:100", family, n), std::invalid_argument);
}

}  // namespace
}  // namespace dtlab::test
