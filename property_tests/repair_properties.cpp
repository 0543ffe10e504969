// Star splaying from any list of tetrahedra (engine::repair, `dtlab repair`): part of the
// Delaunay mesh, lone tetrahedra whose vertices meet no other input tetrahedron, and garbage
// (repeated ids, inverted, overlapping) always end in the unique perturbed Delaunay
// tetrahedralization, orientation compared, and a point set without one is refused. The mesh the
// input is cut from and the answer are CGAL's (tests/cgal_reference.hpp), not the engine's.
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>

#include "cgal_reference.hpp"
#include "dtlab/engine/repair.hpp"
#include "dtlab/engine/triangulate.hpp"  // canonical_tetrahedra
#include "dtlab/engine/validator.hpp"
#include "point_set_gen.hpp"

namespace dtlab::property {
namespace {

using engine::Tetrahedron;
using VertexId = std::uint32_t;  // a point's index, as in engine::Tetrahedron

RC_GTEST_PROP(Repair, AnyListOfTetrahedraGivesTheDelaunayMesh, ()) {
  const PointSetCase c = *point_set_case();
  RC_PRE(!c.points.empty());
  // Decided by CGAL, not by the engine's own code.
  const bool tetrahedralizable = test::all_finite(c.points) && test::cgal_dimension(c.points) == 3;
  const auto n = static_cast<VertexId>(c.points.size());
  const int keep_percent = *rc::gen::inRange(0, 101);
  const int lone = *rc::gen::inRange(0, 4);
  const int garbage = *rc::gen::inRange(0, 12);
  std::mt19937_64 random(*rc::gen::inRange<std::uint64_t>(0, 1U << 30));
  std::vector<Tetrahedron> start;
  std::vector<Tetrahedron> delaunay;
  if (tetrahedralizable) {
    delaunay = test::cgal_delaunay(c.points);
    for (const Tetrahedron& t : delaunay) {
      if (static_cast<int>(random() % 100) < keep_percent) start.push_back(t);
    }
  }
  // Lone tetrahedra: the kept ones lose every tetrahedron at their vertices.
  std::vector<char> taken(n, 0);
  for (int i = 0; i < lone && !delaunay.empty(); ++i) {
    const Tetrahedron q = delaunay[random() % delaunay.size()];
    if (std::any_of(q.begin(), q.end(), [&](VertexId v) { return taken[v] != 0; })) continue;
    for (const VertexId v : q) taken[v] = 1;
    std::erase_if(start, [&](const Tetrahedron& t) {
      return std::any_of(t.begin(), t.end(), [&](VertexId v) { return taken[v] != 0; });
    });
    start.push_back(q);
  }
  for (int i = 0; i < garbage; ++i) {
    Tetrahedron t{};
    for (auto& v : t) v = static_cast<VertexId>(random() % n);
    start.push_back(t);
  }
  std::shuffle(start.begin(), start.end(), random);
  engine::SplayStats stats;
  try {
    const auto repaired = engine::repair(c.points, start, stats);
    RC_ASSERT(tetrahedralizable);
    RC_ASSERT(engine::canonical_tetrahedra(repaired) == engine::canonical_tetrahedra(delaunay));
    RC_ASSERT(engine::validate(c.points, repaired).valid());
  } catch (const engine::TriangulationError&) {
    RC_ASSERT(!tetrahedralizable);
  }
}

}  // namespace
}  // namespace dtlab::property
