// bytes -> point set -> triangulate with adaptive predicates -> must validate and be CGAL's
// tetrahedra, orientation compared (or be refused with a TriangulationError when it has no
// tetrahedralization: decided by CGAL's dimension, tests/cgal_reference.hpp, not by the engine's
// own code); the filtered kernel, the walk mode and
// its cavity insertion must give the same tetrahedra (the perturbed Delaunay tetrahedralization
// is unique), the cavities with none failing their star check.
#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include "cgal_reference.hpp"
#include "dtlab/engine/triangulate.hpp"
#include "dtlab/engine/validator.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto points = dtlab::fuzz::points_from_bytes(data, size, 400);
  dtlab::engine::TriangulateOptions options;
  options.seed = size;
  // The points are small integers times a power of two, so always finite; a non-finite one would
  // have to be refused and is not shown to CGAL.
  const int dimension = dtlab::test::all_finite(points) ? dtlab::test::cgal_dimension(points) : -1;
  try {
    const auto result = dtlab::engine::triangulate(points, options);
    if (dimension != 3) std::abort();  // triangulated something without a tetrahedralization
    if (!dtlab::engine::validate(points, result.tetrahedra).valid()) std::abort();
    const auto& sorted = dtlab::engine::canonical_tetrahedra;
    if (sorted(result.tetrahedra) != sorted(dtlab::test::cgal_delaunay(points))) std::abort();
    dtlab::engine::TriangulateOptions filtered = options;
    filtered.kernel = dtlab::engine::KernelKind::Filtered;
    if (sorted(dtlab::engine::triangulate(points, filtered).tetrahedra) !=
        sorted(result.tetrahedra)) {
      std::abort();
    }
    dtlab::engine::TriangulateOptions walk = options;
    walk.location = dtlab::engine::Location::Walk;
    if (sorted(dtlab::engine::triangulate(points, walk).tetrahedra) != sorted(result.tetrahedra)) {
      std::abort();
    }
    dtlab::engine::TriangulateOptions cavity = walk;
    cavity.insertion = dtlab::engine::Insertion::Cavity;
    cavity.check_cavities = true;
    const auto by_cavity = dtlab::engine::triangulate(points, cavity);
    if (by_cavity.stats.cavity.fallbacks != 0 ||
        sorted(by_cavity.tetrahedra) != sorted(result.tetrahedra)) {
      std::abort();
    }
  } catch (const dtlab::engine::TriangulationError&) {
    if (dimension == 3) std::abort();  // refused a valid input
  }
  return 0;
}
