// Differential: every predicate the engine calls, in the adaptive and the filtered kernel, against
// the GMP kernel, on fuzzer-chosen points: raw doubles (any finite value: subnormal, huge, mixed),
// or small integers scaled by a power of two (exact ties). Covers orient3d, insphere, orient2d,
// incircle_lifted, orient3d_centroid and the perturbed finite and infinite insphere tests.
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "dtlab/predicates/kernels.hpp"
#include "dtlab/predicates/perturbation.hpp"
#include "fuzz_input.hpp"

using dtlab::predicates::ExactKernel;
using dtlab::predicates::Point3;

namespace {

void require(bool ok) {
  if (!ok) std::abort();
}

bool finite(const Point3& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

template <class K>
void compare_with_exact(const std::vector<Point3>& p) {
  require(K::orient3d(p[0], p[1], p[2], p[3]) == ExactKernel::orient3d(p[0], p[1], p[2], p[3]));
  require(K::insphere(p[0], p[1], p[2], p[3], p[4]) ==
          ExactKernel::insphere(p[0], p[1], p[2], p[3], p[4]));
  for (int drop = 0; drop < 3; ++drop) {
    require(K::orient2d(p[0], p[1], p[2], drop) == ExactKernel::orient2d(p[0], p[1], p[2], drop));
    require(K::incircle_lifted(p[0], p[1], p[2], p[3], drop) ==
            ExactKernel::incircle_lifted(p[0], p[1], p[2], p[3], drop));
  }
  const dtlab::predicates::Tetrahedron4 t{p[1], p[2], p[3], p[4]};
  require(K::orient3d_centroid(p[0], p[1], p[2], t) ==
          ExactKernel::orient3d_centroid(p[0], p[1], p[2], t));
  if (ExactKernel::orient3d(p[0], p[1], p[2], p[3]) != 0) {
    require(dtlab::predicates::insphere_perturbed<K>(p[0], p[1], p[2], p[3], p[4]) ==
            dtlab::predicates::insphere_perturbed<ExactKernel>(p[0], p[1], p[2], p[3], p[4]));
  }
  if (dtlab::predicates::nondegenerate_projection<ExactKernel>(p[0], p[1], p[2])[1] != 0) {
    require(dtlab::predicates::infinite_insphere_perturbed<K>(p[0], p[1], p[2], p[3]) ==
            dtlab::predicates::infinite_insphere_perturbed<ExactKernel>(p[0], p[1], p[2], p[3]));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  std::vector<Point3> p;
  if ((data[0] & 1) != 0) {
    dtlab::fuzz::ByteReader in(data + 1, size - 1);
    while (p.size() < 5 && in.remaining() >= 24) {
      const Point3 q{in.raw_double(), in.raw_double(), in.raw_double()};
      if (!finite(q)) return 0;
      p.push_back(q);
    }
  } else {
    p = dtlab::fuzz::points_from_bytes(data + 1, size - 1, 5);
  }
  if (p.size() < 5) return 0;
  compare_with_exact<dtlab::predicates::AdaptiveKernel>(p);
  compare_with_exact<dtlab::predicates::FilteredKernel>(p);
  return 0;
}
