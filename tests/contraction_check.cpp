// Adaptive vs exact insphere and orient3d on near-cospherical / near-coplanar inputs far from
// the origin. Exit 0 when every sign agrees, 1 otherwise. Built twice (tests/CMakeLists.txt):
// against the real predicates target it must pass; against a copy compiled with floating point
// contraction it must fail, which proves the check notices a contracted build.
#include <cmath>
#include <cstdio>
#include <random>

#include "dtlab/predicates/kernels.hpp"

using dtlab::predicates::AdaptiveKernel;
using dtlab::predicates::ExactKernel;
using dtlab::predicates::Point3;

int main() {
  std::mt19937_64 rng(7);
  auto unit = [&] { return std::ldexp(static_cast<double>(rng() >> 11), -53); };
  auto on_sphere = [&](Point3 c, double r) {
    const double theta = 2.0 * M_PI * unit();
    const double z = 2.0 * unit() - 1.0;
    const double s = std::sqrt(1.0 - z * z);
    return Point3{c.x + r * s * std::cos(theta), c.y + r * s * std::sin(theta), c.z + r * z};
  };
  long wrong = 0;
  long stage_d = 0;
  const long trials = 200000;
  for (long i = 0; i < trials; ++i) {
    const double offset = std::ldexp(1.0, static_cast<int>(i % 24));
    const Point3 c{offset * (0.5 + unit()), offset * unit(), -offset * unit()};
    const double r = 0.5 + unit();
    const Point3 a = on_sphere(c, r), b = on_sphere(c, r), d = on_sphere(c, r), e = on_sphere(c, r);
    const Point3 f = on_sphere(c, r);
    const auto s = AdaptiveKernel::insphere_staged(a, b, d, e, f);
    if (s.stage == dtlab::predicates::Stage::D) ++stage_d;
    if (s.sign != ExactKernel::insphere(a, b, d, e, f)) ++wrong;
    const Point3 q{a.x + 0.5 * (b.x - a.x) + 0.25 * (d.x - a.x), a.y + 0.5 * (b.y - a.y) + 0.25 * (d.y - a.y),
                   a.z + 0.5 * (b.z - a.z) + 0.25 * (d.z - a.z)};
    if (AdaptiveKernel::orient3d(a, b, d, q) != ExactKernel::orient3d(a, b, d, q)) ++wrong;
  }
  std::printf("%ld of %ld near-degenerate signs differ from exact (%ld insphere calls reached stage D)\n",
              wrong, 2 * trials, stage_d);
  return wrong == 0 ? 0 : 1;
}
