// Differential: adaptive vs exact signs on fuzzer-chosen points (raw doubles within the adaptive
// kernel's valid range, or small integers for exact ties), including the perturbed tests.
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "dtlab/predicates/kernels.hpp"
#include "dtlab/predicates/perturbation.hpp"
#include "dtlab/predicates/valid_range.hpp"
#include "fuzz_input.hpp"

using dtlab::predicates::AdaptiveKernel;
using dtlab::predicates::ExactKernel;
using dtlab::predicates::Point3;

namespace {
void require(bool ok) {
  if (!ok) std::abort();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  std::vector<Point3> p;
  if ((data[0] & 1) != 0) {
    dtlab::fuzz::ByteReader in(data + 1, size - 1);
    while (p.size() < 5 && in.remaining() >= 24) {
      const Point3 q{in.raw_double(), in.raw_double(), in.raw_double()};
      if (!dtlab::predicates::in_valid_range(q)) return 0;
      p.push_back(q);
    }
  } else {
    p = dtlab::fuzz::points_from_bytes(data + 1, size - 1, 5);
  }
  if (p.size() < 5) return 0;
  require(AdaptiveKernel::orient3d(p[0], p[1], p[2], p[3]) ==
          ExactKernel::orient3d(p[0], p[1], p[2], p[3]));
  require(AdaptiveKernel::insphere(p[0], p[1], p[2], p[3], p[4]) ==
          ExactKernel::insphere(p[0], p[1], p[2], p[3], p[4]));
  for (int drop = 0; drop < 3; ++drop) {
    require(AdaptiveKernel::orient2d(p[0], p[1], p[2], drop) ==
            ExactKernel::orient2d(p[0], p[1], p[2], drop));
  }
  const dtlab::predicates::Tetrahedron4 t{p[1], p[2], p[3], p[4]};
  require(AdaptiveKernel::orient3d_centroid(p[0], p[1], p[2], t) ==
          ExactKernel::orient3d_centroid(p[0], p[1], p[2], t));
  if (ExactKernel::orient3d(p[0], p[1], p[2], p[3]) != 0) {
    require(dtlab::predicates::insphere_perturbed<AdaptiveKernel>(p[0], p[1], p[2], p[3], p[4]) ==
            dtlab::predicates::insphere_perturbed<ExactKernel>(p[0], p[1], p[2], p[3], p[4]));
  }
  return 0;
}
