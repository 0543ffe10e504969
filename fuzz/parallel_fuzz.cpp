// bytes -> (method, threads, distribution, kernel) + point set -> triangulate on 2-4 threads with
// the adaptive, filtered or fast kernel, with random delays while locks are held.
//
// First byte, config = byte % 108, a mixed-radix number (every one of the 108 configurations is
// reachable, none twice within 0..107):
//   config = method + 6 * (threads - 2) + 18 * distribution + 36 * kernel
//   method:       0 pessimistic, 1 optimistic-detect, 2 optimistic-prevent, 3 burglary,
//                 4 burglary --repair, 5 batch
//   threads:      2, 3, 4
//   distribution: 0 static, 1 dynamic
//   kernel:       0 adaptive, 1 filtered, 2 fast
// (--repair is a method variant: it only exists for burglary.) The rest is a point set as for the
// triangulate harness (fuzz_input.hpp), at most 300 points.
//
// Every kernel: an input that CGAL finds no tetrahedralization for (tests/cgal_reference.hpp, not
// the engine's own code) must be refused with a TriangulationError, and any other input must not
// be: a refusal there, the watchdog's included (a stall), is a failure.
// Adaptive and filtered (exact): every method gives a sound mesh, every method but burglary
// without --repair a valid one, and no insertion is abandoned.
// Fast: the points are divided by 12 (rounded: nearly degenerate and inexact, where the fast kernel
// fails); the run must finish (no crash, no hang, only the refusals the fast kernel may make) and
// the validator's report on whatever it gave must be computed; validity is not required and
// abandoned insertions are allowed.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "cgal_reference.hpp"
#include "dtlab/engine/triangulate.hpp"
#include "dtlab/engine/validator.hpp"
#include "fuzz_input.hpp"

namespace {

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "parallel_fuzz: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  using dtlab::engine::KernelKind;
  using dtlab::engine::Method;
  unsigned config = data[0] % 108U;
  const unsigned method = config % 6;
  config /= 6;
  const unsigned threads = config % 3;
  config /= 3;
  const unsigned distribution = config % 2;
  config /= 2;
  const unsigned kernel = config;  // 0..2
  constexpr Method kMethods[] = {Method::Pessimistic,       Method::OptimisticDetect,
                                 Method::OptimisticPrevent, Method::Burglary,
                                 Method::Burglary,          Method::Batch};
  constexpr KernelKind kKernels[] = {KernelKind::Adaptive, KernelKind::Filtered, KernelKind::Fast};
  dtlab::engine::TriangulateOptions options;
  options.method = kMethods[method];
  // The repair with its rebuild as the reported last resort: the result must be valid, and the
  // rebuild taken exactly when the flips left faces.
  options.repair = method == 4 ? dtlab::engine::Repair::Rebuild : dtlab::engine::Repair::None;
  options.threads = 2 + static_cast<int>(threads);
  options.distribution = distribution != 0 ? dtlab::engine::Distribution::Dynamic
                                           : dtlab::engine::Distribution::Static;
  options.kernel = kKernels[kernel];
  options.stress = true;
  options.seed = size;
  // The watchdog (10 s + 100 us per point by default) turns a hang into a TriangulationError.
  auto points = dtlab::fuzz::points_from_bytes(data + 1, size - 1, 300);
  if (options.kernel == KernelKind::Fast) {
    // Small integers keep the fast kernel's arithmetic exact; a twelfth of them (rounded, as a
    // grid with spacing 1/12 on [0, 1] is) is nearly degenerate and inexact, where it fails.
    for (auto& p : points) p = {p.x / 12, p.y / 12, p.z / 12};
  }
  // The points are small integers times a power of two, so always finite; a non-finite one would
  // have to be refused and is not shown to CGAL.
  const int dimension = dtlab::test::all_finite(points) ? dtlab::test::cgal_dimension(points) : -1;
  try {
    const auto result = dtlab::engine::triangulate(points, options);
    if (dimension != 3) fail("triangulated an input without a tetrahedralization");
    const auto report = dtlab::engine::validate(points, result.tetrahedra);
    if (options.kernel == KernelKind::Fast) {
      // Only that the report could be computed: the fast kernel may be wrong.
      (void)report.valid();
      return 0;
    }
    if (!report.mesh_consistent()) fail("unsound mesh");
    const bool must_be_valid =
        options.method != Method::Burglary || options.repair != dtlab::engine::Repair::None;
    if (must_be_valid && !report.valid()) fail("invalid mesh");
    if (result.stats.abandoned_insertions != 0) fail("abandoned insertions");
    const dtlab::engine::PostCheck& check = result.stats.post_check;
    if (check.repaired && check.rebuilt != (check.non_delaunay_after_flips > 0)) {
      fail("rebuilt without stuck flips, or stuck flips without the rebuild");
    }
  } catch (const dtlab::engine::TriangulationError& e) {
    // Refused an input with a tetrahedralization, or the watchdog stopped a stalled run. The fast
    // kernel may refuse one more way: start() asks its orient3d about the first tetrahedron (found
    // exactly), and on the inexact twelfths it can see that tetrahedron as flat.
    const bool flat_first = std::strstr(e.what(), "flat under this kernel") != nullptr;
    if (dimension == 3 && !(options.kernel == KernelKind::Fast && flat_first)) fail(e.what());
  }
  return 0;
}
