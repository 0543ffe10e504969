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
// Fast: the run must finish (no crash, no hang) and the validator's report on whatever it gave
// must be computed; validity is not required and abandoned insertions are allowed.
#include <cstdint>
#include <cstdio>
#include <cstdlib>

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
  options.repair = method == 4;
  options.threads = 2 + static_cast<int>(threads);
  options.distribution = distribution != 0 ? dtlab::engine::Distribution::Dynamic
                                           : dtlab::engine::Distribution::Static;
  options.kernel = kKernels[kernel];
  options.stress = true;
  options.seed = size;
  options.watchdog_seconds = 20;  // a hang becomes a TriangulationError, reported below
  const auto points = dtlab::fuzz::points_from_bytes(data + 1, size - 1, 300);
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
    const bool must_be_valid = options.method != Method::Burglary || options.repair;
    if (must_be_valid && !report.valid()) fail("invalid mesh");
    if (result.stats.abandoned_insertions != 0) fail("abandoned insertions");
  } catch (const dtlab::engine::TriangulationError& e) {
    // Refused an input with a tetrahedralization, or the watchdog stopped a stalled run. Also for
    // the fast kernel: its other refusal, a first tetrahedron it sees as flat (start() asks the
    // kernel's orient3d), cannot happen here, because on these inputs (integers of at most 7 bits
    // times one power of two) its floating-point arithmetic is exact.
    if (dimension == 3) fail(e.what());
  }
  return 0;
}
