// bytes -> a point set (small integers times a power of two, as for the triangulate harness, at
// most 120 points) and then any tetrahedra on it (garbage connectivity: four ids per 4 bytes,
// taken modulo the point count, repeated and inverted ones included) -> dtlab repair by star
// splaying. It must end, and equal CGAL's Delaunay tetrahedralization (the unique perturbed one,
// orientation compared) when CGAL finds one; when CGAL does not, it must refuse with a
// TriangulationError. Then the same for that tetrahedralization with one tetrahedron dropped (the
// last byte picks it): a notch at the hull leaves a consistent list, which the repair takes the
// local path for (docs/design.md, "dtlab repair, locally"), a hole inside does not.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "cgal_reference.hpp"
#include "dtlab/engine/repair.hpp"
#include "dtlab/engine/triangulate.hpp"  // canonical_tetrahedra
#include "fuzz_input.hpp"

namespace {

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "repair_fuzz: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  // First byte: how many bytes describe points (the rest are tetrahedra).
  const std::size_t point_bytes = std::min<std::size_t>(size - 1, 2 + 6 * (data[0] % 121));
  const auto points = dtlab::fuzz::points_from_bytes(data + 1, point_bytes, 120);
  if (points.empty()) return 0;
  std::vector<dtlab::engine::Tetrahedron> tets;
  for (std::size_t i = 1 + point_bytes; i + 4 <= size; i += 4) {
    tets.push_back({static_cast<std::uint32_t>(data[i] % points.size()),
                    static_cast<std::uint32_t>(data[i + 1] % points.size()),
                    static_cast<std::uint32_t>(data[i + 2] % points.size()),
                    static_cast<std::uint32_t>(data[i + 3] % points.size())});
  }
  const int dimension = dtlab::test::cgal_dimension(points);
  dtlab::engine::SplayStats stats;
  try {
    const auto repaired = dtlab::engine::repair(points, tets, stats);
    if (dimension != 3) fail("repaired a point set without a tetrahedralization");
    // The truth is CGAL's, not the engine's own triangulate.
    const auto delaunay = dtlab::test::cgal_delaunay(points);
    if (dtlab::engine::canonical_tetrahedra(repaired) !=
        dtlab::engine::canonical_tetrahedra(delaunay)) {
      fail("the repaired mesh is not the Delaunay tetrahedralization");
    }
    auto dropped = delaunay;
    dropped.erase(dropped.begin() + static_cast<std::ptrdiff_t>(data[size - 1] % dropped.size()));
    dtlab::engine::SplayStats again;
    if (dtlab::engine::canonical_tetrahedra(dtlab::engine::repair(points, dropped, again)) !=
        dtlab::engine::canonical_tetrahedra(delaunay)) {
      fail("the Delaunay mesh less one tetrahedron was not repaired into it");
    }
  } catch (const dtlab::engine::TriangulationError& e) {
    if (dimension == 3) fail(e.what());
  }
  return 0;
}
