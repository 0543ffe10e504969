// bytes -> (method, threads, distribution, kernel) + point set -> triangulate with the adaptive or
// the filtered kernel on 2-4 threads, with random delays while locks are held. Every method must
// give a sound mesh; every method but burglary a valid one, and burglary a valid one after
// --repair.
#include <cstdint>
#include <cstdlib>

#include "dtlab/engine/point_set_info.hpp"
#include "dtlab/engine/triangulate.hpp"
#include "dtlab/engine/validator.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  using dtlab::engine::Method;
  // First byte: method (3 bits), threads 2-4, distribution, repair, kernel.
  const std::uint8_t config = data[0];
  constexpr Method kMethods[] = {Method::Pessimistic, Method::OptimisticDetect,
                                 Method::OptimisticPrevent, Method::Burglary, Method::Batch};
  dtlab::engine::TriangulateOptions options;
  options.method = kMethods[(config & 7U) % 5];
  options.threads = 2 + static_cast<int>((config >> 3) % 3U);
  options.distribution = (config & 0x20U) != 0 ? dtlab::engine::Distribution::Dynamic
                                               : dtlab::engine::Distribution::Static;
  options.repair = options.method == Method::Burglary && (config & 0x40U) != 0
                       ? dtlab::engine::Repair::Rebuild
                       : dtlab::engine::Repair::None;
  options.kernel = (config & 0x80U) != 0 ? dtlab::engine::KernelKind::Filtered
                                         : dtlab::engine::KernelKind::Adaptive;
  options.stress = true;
  options.seed = size;
  // The watchdog (10 s + 100 us per point by default) turns a hang into a TriangulationError.
  const auto points = dtlab::fuzz::points_from_bytes(data + 1, size - 1, 300);
  const int dimension = dtlab::engine::analyze(points).dimension;
  try {
    const auto result = dtlab::engine::triangulate(points, options);
    if (dimension != 3) std::abort();
    const auto report = dtlab::engine::validate(points, result.tetrahedra);
    if (!report.mesh_consistent()) std::abort();
    const bool must_be_valid =
        options.method != Method::Burglary || options.repair != dtlab::engine::Repair::None;
    if (must_be_valid && !report.valid()) std::abort();
    if (result.stats.abandoned_insertions != 0) std::abort();
  } catch (const dtlab::engine::TriangulationError&) {
    if (dimension == 3) std::abort();  // refused a valid input, or the watchdog fired
  }
  return 0;
}
