// Adaptive vs exact on inputs whose signs only the exact stages can decide: integer points with
// 30-bit coordinates that are exactly (or 1 unit off) coplanar, and 20-bit integer points that
// are exactly (or 1 unit off) cospherical. Their differences are exact but their products are not,
// so the answer rests on Two-Product being error-free. Exit 0 when every sign agrees, 1 otherwise.
// Built twice (tests/CMakeLists.txt): against the real predicates target it must pass; against a
// copy compiled with unsafe floating point (contraction and -ffast-math) it must fail, which
// proves that this check notices such a build.
#include <cstdio>
#include <random>

#include "dtlab/predicates/kernels.hpp"

using dtlab::predicates::AdaptiveKernel;
using dtlab::predicates::ExactKernel;
using dtlab::predicates::Point3;
using dtlab::predicates::Stage;

int main() {
  std::mt19937_64 rng(7);
  auto integer = [&](int bits) {
    return static_cast<double>(static_cast<std::int64_t>(rng() >> (64 - bits)) -
                               (std::int64_t{1} << (bits - 1)));
  };
  long wrong = 0;
  long exact_stages = 0;
  const long trials = 20000;
  for (long i = 0; i < trials; ++i) {
    // Coplanar: d = b + c - a, nudged by -1, 0 or +1 in z.
    const Point3 a{integer(30), integer(30), integer(30)};
    const Point3 b{integer(30), integer(30), integer(30)};
    const Point3 c{integer(30), integer(30), integer(30)};
    const Point3 d{b.x + c.x - a.x, b.y + c.y - a.y,
                   b.z + c.z - a.z + static_cast<double>(i % 3 - 1)};
    const auto o = AdaptiveKernel::orient3d_staged(a, b, c, d);
    if (o.stage != Stage::A) ++exact_stages;
    if (o.sign != ExactKernel::orient3d(a, b, c, d)) ++wrong;

    // Cospherical: centre + coordinate permutations and sign changes of one vector.
    const Point3 m{integer(22), integer(22), integer(22)};
    const double x = integer(20), y = integer(20), z = integer(20);
    const Point3 p0{m.x + x, m.y + y, m.z + z};
    const Point3 p1{m.x + y, m.y + z, m.z + x};
    const Point3 p2{m.x + z, m.y + x, m.z + y};
    const Point3 p3{m.x - x, m.y + y, m.z + z};
    const Point3 p4{m.x + x, m.y - y, m.z + z + static_cast<double>(i % 3 - 1)};
    const auto s = AdaptiveKernel::insphere_staged(p0, p1, p2, p3, p4);
    if (s.stage != Stage::A) ++exact_stages;
    if (s.sign != ExactKernel::insphere(p0, p1, p2, p3, p4)) ++wrong;
  }
  std::printf("%ld of %ld signs differ from exact (%ld settled after stage A)\n", wrong, 2 * trials,
              exact_stages);
  return wrong == 0 ? 0 : 1;
}
