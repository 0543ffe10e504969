#include "dtlab/generators/generators.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <functional>
#include <map>
#include <stdexcept>

#include "dtlab/common/random.hpp"

namespace dtlab::generators {
namespace {

using common::Random;
using Points = std::vector<Point3>;

Point3 uniform_point(Random& rng) {
  return {rng.uniform(), rng.uniform(), rng.uniform()};
}

// A normal coordinate with mean `mean` and deviation `sigma`, redrawn until inside [0, 1].
double normal_in_unit(Random& rng, double mean, double sigma) {
  while (true) {
    const double v = mean + sigma * rng.normal();
    if (v >= 0.0 && v <= 1.0) return v;
  }
}

// k points per side for about n points; the grid spacing is the largest power of two h with
// (k - 1) h <= 1, so every coordinate and every difference is exact and the grid's cospherical
// sets are exactly cospherical.
std::int64_t grid_side(std::int64_t n) {
  return std::max<std::int64_t>(2, std::llround(std::cbrt(static_cast<double>(n))));
}
double grid_spacing(std::int64_t k) {
  return std::ldexp(1.0, -static_cast<int>(std::ceil(std::log2(static_cast<double>(k - 1)))));
}

Points uniform(std::int64_t n, Random& rng) {
  Points p(static_cast<std::size_t>(n));
  for (auto& q : p) q = uniform_point(rng);
  return p;
}

Points normal(std::int64_t n, Random& rng) {
  Points p(static_cast<std::size_t>(n));
  for (auto& q : p) {
    q = {normal_in_unit(rng, 0.5, 0.125), normal_in_unit(rng, 0.5, 0.125),
         normal_in_unit(rng, 0.5, 0.125)};
  }
  return p;
}

Points cluster(std::int64_t n, Random& rng) {
  const std::int64_t groups = std::clamp<std::int64_t>(n / 1000, 1, 10);
  std::vector<Point3> centres(static_cast<std::size_t>(groups));
  for (auto& c : centres)
    c = {0.1 + 0.8 * rng.uniform(), 0.1 + 0.8 * rng.uniform(), 0.1 + 0.8 * rng.uniform()};
  Points p(static_cast<std::size_t>(n));
  for (auto& q : p) {
    const Point3& c = centres[rng.below(static_cast<std::uint64_t>(groups))];
    q = {normal_in_unit(rng, c.x, 0.03), normal_in_unit(rng, c.y, 0.03),
         normal_in_unit(rng, c.z, 0.03)};
  }
  return p;
}

// k x k x k points origin + (i, j, l) * spacing.
Points cube_grid(std::int64_t k, double origin, double spacing) {
  Points p;
  p.reserve(static_cast<std::size_t>(k * k * k));
  for (std::int64_t i = 0; i < k; ++i) {
    for (std::int64_t j = 0; j < k; ++j) {
      for (std::int64_t l = 0; l < k; ++l) {
        p.push_back({origin + static_cast<double>(i) * spacing,
                     origin + static_cast<double>(j) * spacing,
                     origin + static_cast<double>(l) * spacing});
      }
    }
  }
  return p;
}

Points grid(std::int64_t n, Random& /*rng*/) {
  const std::int64_t k = grid_side(n);
  return cube_grid(k, 0.0, grid_spacing(k));
}

Point3 on_sphere(Random& rng, Point3 centre, double radius) {
  while (true) {
    const double x = rng.normal();
    const double y = rng.normal();
    const double z = rng.normal();
    const double r = std::sqrt(x * x + y * y + z * z);
    if (r < 1e-12) continue;
    return {centre.x + radius * x / r, centre.y + radius * y / r, centre.z + radius * z / r};
  }
}

Points sphere(std::int64_t n, Random& rng) {
  Points p(static_cast<std::size_t>(n));
  for (auto& q : p) q = on_sphere(rng, {0.5, 0.5, 0.5}, 0.5);
  return p;
}

// Four planes, two orthogonal to z and one each to x and y, at exact dyadic offsets.
Points planes(std::int64_t n, Random& rng) {
  Points p(static_cast<std::size_t>(n));
  constexpr double kOffsets[4] = {0.25, 0.75, 0.5, 0.5};
  constexpr int kAxis[4] = {2, 2, 0, 1};
  for (std::size_t i = 0; i < p.size(); ++i) {
    const std::size_t plane = i % 4;
    double c[3] = {rng.uniform(), rng.uniform(), rng.uniform()};
    c[kAxis[plane]] = kOffsets[plane];
    p[i] = {c[0], c[1], c[2]};
  }
  return p;
}

// Every integer point with x^2 + y^2 + z^2 == r2.
void integer_sphere(std::int64_t r2, Points& out) {
  const auto r = static_cast<std::int64_t>(std::sqrt(static_cast<double>(r2)));
  for (std::int64_t x = -r; x <= r; ++x) {
    for (std::int64_t y = -r; y <= r; ++y) {
      const std::int64_t rest = r2 - x * x - y * y;
      if (rest < 0) continue;
      const auto z = static_cast<std::int64_t>(std::llround(std::sqrt(static_cast<double>(rest))));
      if (z * z != rest) continue;
      out.push_back({static_cast<double>(x), static_cast<double>(y), static_cast<double>(z)});
      if (z != 0)
        out.push_back({static_cast<double>(x), static_cast<double>(y), static_cast<double>(-z)});
    }
  }
}

// Half: random points on three spheres, as cospherical as rounding allows. Half: integer points
// on concentric spheres x^2+y^2+z^2 = r^2 (exactly cospherical), scaled by a power of two and
// shifted by 1/2 exactly into the unit cube.
Points cospherical(std::int64_t n, Random& rng) {
  const std::int64_t rounded = n - n / 2;
  Points p;
  p.reserve(static_cast<std::size_t>(n));
  const Point3 centres[3] = {{0.5, 0.5, 0.5}, {0.3, 0.4, 0.6}, {0.7, 0.6, 0.4}};
  const double radii[3] = {0.45, 0.25, 0.2};
  for (std::int64_t i = 0; i < rounded; ++i) {
    const auto s = static_cast<std::size_t>(i % 3);
    p.push_back(on_sphere(rng, centres[s], radii[s]));
  }
  Points exact;
  for (std::int64_t r = 5; static_cast<std::int64_t>(exact.size()) < n / 2; r += 4) {
    integer_sphere(r * r, exact);
  }
  double max_abs = 1.0;
  for (const auto& q : exact)
    max_abs = std::max({max_abs, std::fabs(q.x), std::fabs(q.y), std::fabs(q.z)});
  const double scale = std::ldexp(1.0, -static_cast<int>(std::ceil(std::log2(max_abs))) - 1);
  // Take the needed count in a seeded order so that every sphere contributes.
  for (std::size_t i = exact.size(); i > 1; --i) std::swap(exact[i - 1], exact[rng.below(i)]);
  for (std::int64_t i = 0; i < n / 2; ++i) {
    const Point3& q = exact[static_cast<std::size_t>(i)];
    p.push_back({0.5 + q.x * scale, 0.5 + q.y * scale, 0.5 + q.z * scale});
  }
  return p;
}

// n/2 uniform points, each twice (n odd: one more single point), in seeded order.
Points duplicates(std::int64_t n, Random& rng) {
  Points p;
  p.reserve(static_cast<std::size_t>(n));
  for (std::int64_t i = 0; i < n / 2; ++i) {
    const Point3 q = uniform_point(rng);
    p.push_back(q);
    p.push_back(q);
  }
  if (n % 2 != 0) p.push_back(uniform_point(rng));
  for (std::size_t i = p.size(); i > 1; --i) std::swap(p[i - 1], p[rng.below(i)]);
  return p;
}

// Pairs 1 ulp apart in x.
Points near_duplicates(std::int64_t n, Random& rng) {
  Points p;
  p.reserve(static_cast<std::size_t>(n));
  for (std::int64_t i = 0; i < n / 2; ++i) {
    const Point3 q = uniform_point(rng);
    p.push_back(q);
    p.push_back({std::nextafter(q.x, 2.0), q.y, q.z});
  }
  if (n % 2 != 0) p.push_back(uniform_point(rng));
  return p;
}

Points coplanar(std::int64_t n, Random& rng) {
  Points p(static_cast<std::size_t>(n));
  for (auto& q : p) q = {rng.uniform(), rng.uniform(), 0.5};
  return p;
}

Points collinear(std::int64_t n, Random& rng) {
  Points p(static_cast<std::size_t>(n));
  for (auto& q : p) q = {rng.uniform(), 0.5, 0.5};
  return p;
}

// Integer grid k x k x k offset by 2^30 (exact).
Points lattice(std::int64_t n, Random& /*rng*/) {
  return cube_grid(grid_side(n), std::ldexp(1.0, 30), 1.0);
}

Points scaled_uniform(std::int64_t n, Random& rng, double factor) {
  Points p = uniform(n, rng);
  for (auto& q : p) q = {q.x * factor, q.y * factor, q.z * factor};
  return p;
}

using Family = std::function<Points(std::int64_t, Random&)>;

const std::map<std::string, Family>& registry() {
  static const std::map<std::string, Family> families{
      {"uniform", uniform},
      {"normal", normal},
      {"cluster", cluster},
      {"grid", grid},
      {"sphere", sphere},
      {"planes", planes},
      {"cospherical", cospherical},
      {"duplicates", duplicates},
      {"near-duplicates", near_duplicates},
      {"coplanar", coplanar},
      {"collinear", collinear},
      {"lattice", lattice},
      {"tiny", [](std::int64_t n, Random& rng) { return scaled_uniform(n, rng, 1e-150); }},
      {"huge", [](std::int64_t n, Random& rng) { return scaled_uniform(n, rng, 1e150); }},
  };
  return families;
}

}  // namespace

const std::vector<std::string>& families() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const auto& [name, f] : registry()) v.push_back(name);
    return v;
  }();
  return names;
}

GeneratedPoints generate(const std::string& family, std::int64_t n, std::uint64_t seed) {
  const auto it = registry().find(family);
  if (it == registry().end()) {
    std::string known;
    for (const auto& name : families()) known += (known.empty() ? "" : ", ") + name;
    throw std::invalid_argument("unknown generator '" + family + "' (known: " + known + ")");
  }
  if (n < 1 || n > kMaxPoints) {
    throw std::invalid_argument("N = " + std::to_string(n) + " is out of range [1, " +
                                std::to_string(kMaxPoints) + "]");
  }
  if ((family == "grid" || family == "lattice") && n < 8) {
    throw std::invalid_argument(family + " needs N >= 8 (a 2 x 2 x 2 grid)");
  }
  Random rng(seed);
  GeneratedPoints out{it->second(n, rng), {}};
  if (static_cast<std::int64_t>(out.points.size()) != n) {
    const std::int64_t k = grid_side(n);
    out.note = family + ": wrote " + std::to_string(out.points.size()) + " points (" +
               std::to_string(k) + "^3, k = round(cbrt(" + std::to_string(n) + "))) instead of " +
               std::to_string(n);
  }
  return out;
}

bool parse_spec(const std::string& spec, std::string& family, std::int64_t& n) {
  const std::size_t colon = spec.find(':');
  if (colon == std::string::npos || colon == 0) return false;
  const std::string name = spec.substr(0, colon);
  if (registry().count(name) == 0) {
    // Paths such as C:/x.xyz or ./a:b.xyz are files, not specs, when the name is unknown and
    // the rest is not a number.
    const std::string rest = spec.substr(colon + 1);
    const bool numeric = !rest.empty() && rest.find_first_not_of("0123456789") == std::string::npos;
    if (!numeric) return false;
    (void)generate(name, 1, 0);  // throws the unknown-generator message
  }
  const std::string count = spec.substr(colon + 1);
  std::int64_t value = 0;
  const auto [ptr, ec] = std::from_chars(count.data(), count.data() + count.size(), value);
  if (ec != std::errc() || ptr != count.data() + count.size()) {
    throw std::invalid_argument("generator spec '" + spec + "': N must be an integer");
  }
  family = name;
  n = value;
  return true;
}

}  // namespace dtlab::generators
