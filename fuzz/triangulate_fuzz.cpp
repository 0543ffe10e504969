// bytes -> point set -> triangulate with adaptive predicates -> must validate (or be refused with
// a TriangulationError when it has no tetrahedralization); the filtered kernel must give the same
// tetrahedra (the perturbed Delaunay tetrahedralization is unique).
#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include "dtlab/engine/point_set_info.hpp"
#include "dtlab/engine/triangulate.hpp"
#include "dtlab/engine/validator.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto points = dtlab::fuzz::points_from_bytes(data, size, 400);
  dtlab::engine::TriangulateOptions options;
  options.seed = size;
  const int dimension = dtlab::engine::analyze(points).dimension;
  try {
    const auto result = dtlab::engine::triangulate(points, options);
    if (dimension != 3) std::abort();  // triangulated something without a tetrahedralization
    if (!dtlab::engine::validate(points, result.tetrahedra).valid()) std::abort();
    dtlab::engine::TriangulateOptions filtered = options;
    filtered.kernel = dtlab::engine::KernelKind::Filtered;
    auto sorted = [](std::vector<dtlab::engine::Tetrahedron> tets) {
      for (auto& t : tets) std::sort(t.begin(), t.end());
      std::sort(tets.begin(), tets.end());
      return tets;
    };
    if (sorted(dtlab::engine::triangulate(points, filtered).tetrahedra) !=
        sorted(result.tetrahedra)) {
      std::abort();
    }
  } catch (const dtlab::engine::TriangulationError&) {
    if (dimension == 3) std::abort();  // refused a valid input
  }
  return 0;
}
