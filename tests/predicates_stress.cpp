// Stress test of the predicates the engine needs beyond orient3d and insphere, which are not in
// Shewchuk's paper: incircle_lifted (four coplanar points, 3D lift in a 2D projection) and
// orient3d_centroid (the engine's symbolic interior point). N random *inexact* near-degenerate
// inputs each (default 10^7), adaptive and filtered against the GMP kernel; prints the stage
// counts, exits 1 on any disagreement.
//   incircle_lifted: four points on a circle in a random tilted plane, rounded (so nearly
//                    coplanar and nearly cocircular, coordinates far from small integers), every
//                    projection.
//   orient3d_centroid: a random triangle and four points rounded onto its plane, two of them
//                    nudged by an ulp, so the centroid lies within rounding of the plane.
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "dtlab/predicates/kernels.hpp"

using dtlab::predicates::AdaptiveKernel;
using dtlab::predicates::ExactKernel;
using dtlab::predicates::FilteredKernel;
using dtlab::predicates::Point3;
using dtlab::predicates::StagedSign;

namespace {

struct Tally {
  long calls = 0;
  long wrong = 0;
  std::array<long, dtlab::predicates::kStageCount> stages{};
  void record(const StagedSign& s, int exact) {
    ++calls;
    ++stages[static_cast<int>(s.stage)];
    if (s.sign != exact) ++wrong;
  }
  void print(const char* what) const {
    std::printf("%-34s %10ld calls, %ld wrong; stages A %ld B %ld C %ld D %ld gmp %ld\n", what,
                calls, wrong, stages[0], stages[1], stages[2], stages[3], stages[4]);
  }
};

Point3 cross(const Point3& a, const Point3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Point3 normalized(const Point3& a) {
  const double n = std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
  return {a.x / n, a.y / n, a.z / n};
}

}  // namespace

int main(int argc, char** argv) {
  const long n = argc > 1 ? std::atol(argv[1]) : 10'000'000;
  std::mt19937_64 rng(20261122);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  Tally circle_adaptive, circle_filtered, centroid_adaptive, centroid_filtered;
  for (long i = 0; i < n; ++i) {
    // A circle in a random tilted plane: centre, radius and orthonormal in-plane axes.
    const Point3 axis = normalized({normal(rng), normal(rng), normal(rng)});
    const Point3 e1 = normalized(cross(axis, {normal(rng), normal(rng), normal(rng)}));
    const Point3 e2 = cross(axis, e1);
    const Point3 c{10 * unit(rng) - 5, 10 * unit(rng) - 5, 10 * unit(rng) - 5};
    const double r = 0.1 + 3 * unit(rng);
    std::array<Point3, 4> q{};
    for (Point3& p : q) {
      const double t = 2 * M_PI * unit(rng);
      const double cs = r * std::cos(t);
      const double sn = r * std::sin(t);
      p = {c.x + cs * e1.x + sn * e2.x, c.y + cs * e1.y + sn * e2.y, c.z + cs * e1.z + sn * e2.z};
    }
    const int drop = static_cast<int>(i % 3);
    const int exact = ExactKernel::incircle_lifted(q[0], q[1], q[2], q[3], drop);
    circle_adaptive.record(AdaptiveKernel::incircle_lifted_staged(q[0], q[1], q[2], q[3], drop),
                           exact);
    circle_filtered.record(FilteredKernel::incircle_lifted_staged(q[0], q[1], q[2], q[3], drop),
                           exact);

    // The triangle q0 q1 q2 and four points rounded onto its plane.
    dtlab::predicates::Tetrahedron4 v{};
    for (int k = 0; k < 4; ++k) {
      const double s = 2 * unit(rng) - 0.5;
      const double t = 2 * unit(rng) - 0.5;
      Point3 p{q[0].x + s * (q[1].x - q[0].x) + t * (q[2].x - q[0].x),
               q[0].y + s * (q[1].y - q[0].y) + t * (q[2].y - q[0].y),
               q[0].z + s * (q[1].z - q[0].z) + t * (q[2].z - q[0].z)};
      if (k == 1) p.z = std::nextafter(p.z, INFINITY);
      if (k == 3 && i % 2 == 0) p.x = std::nextafter(p.x, -INFINITY);
      v[static_cast<std::size_t>(k)] = p;
    }
    const int exact_c = ExactKernel::orient3d_centroid(q[0], q[1], q[2], v);
    centroid_adaptive.record(AdaptiveKernel::orient3d_centroid_staged(q[0], q[1], q[2], v),
                             exact_c);
    centroid_filtered.record(FilteredKernel::orient3d_centroid_staged(q[0], q[1], q[2], v),
                             exact_c);
  }
  circle_adaptive.print("incircle_lifted adaptive");
  circle_filtered.print("incircle_lifted filtered");
  centroid_adaptive.print("orient3d_centroid adaptive");
  centroid_filtered.print("orient3d_centroid filtered");
  const long wrong = circle_adaptive.wrong + circle_filtered.wrong + centroid_adaptive.wrong +
                     centroid_filtered.wrong;
  std::printf("%ld disagreements with the exact kernel\n", wrong);
  return wrong == 0 ? 0 : 1;
}
