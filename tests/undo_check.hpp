#pragma once
// Give-ups after writes, undone (methods/local_undo_log.hpp): a mesh built by flips through a lock
// policy, then each further point tried once with the policy refusing some tetrahedra. After each
// give-up the store must be exactly as it was before the attempt (every slot's aliveness, every
// live record's vertices and references); the point then goes in with nothing refused, and the
// mesh at the end is the unique Delaunay tetrahedralization.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "dtlab/engine/point_set_info.hpp"
#include "dtlab/engine/triangulate.hpp"
#include "insertion/inserter.hpp"
#include "insertion/sync.hpp"
#include "mesh/shared_mesh.hpp"
#include "mesh/slot_reclaimer.hpp"

namespace dtlab::test {

// `points` with four affinely independent ones first (check_give_ups_undo's first tetrahedron:
// a grid's first four points lie in one plane), the others in their order.
inline std::vector<predicates::Point3> simplex_first(std::vector<predicates::Point3> points) {
  std::vector<std::uint32_t> order(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::uint32_t>(i);
  const auto simplex = engine::find_simplex(points, order).simplex.value();
  std::vector<predicates::Point3> reordered;
  reordered.reserve(points.size());
  for (const std::uint32_t v : simplex) reordered.push_back(points[v]);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (std::find(simplex.begin(), simplex.end(), i) == simplex.end())
      reordered.push_back(points[i]);
  }
  return reordered;
}

// Every slot's aliveness and every live record.
struct StoreSnapshot {
  std::vector<bool> alive;
  std::vector<engine::Tet> records;  // a dead slot's entry is left empty
};

inline StoreSnapshot snapshot_of(const engine::SharedMesh& mesh) {
  StoreSnapshot s;
  const std::size_t n = mesh.tets.size();
  s.alive.resize(n);
  s.records.resize(n);
  for (std::size_t t = 0; t < n; ++t) {
    const auto id = static_cast<engine::TetId>(t);
    s.alive[t] = mesh.tets.is_alive(id);
    if (s.alive[t]) s.records[t] = mesh.tets[id];
  }
  return s;
}

// The first difference between the store and `before`, in words; empty when there is none.
// Slots taken since are compared as dead before.
inline std::string store_difference(const engine::SharedMesh& mesh, const StoreSnapshot& before) {
  const std::size_t n = std::max(mesh.tets.size(), before.alive.size());
  for (std::size_t t = 0; t < n; ++t) {
    const auto id = static_cast<engine::TetId>(t);
    const bool was = t < before.alive.size() && before.alive[t];
    const bool is = t < mesh.tets.size() && mesh.tets.is_alive(id);
    if (was != is) return "slot " + std::to_string(t) + (is ? " came alive" : " died");
    if (!is) continue;
    if (mesh.tets[id].vertex != before.records[t].vertex) {
      return "slot " + std::to_string(t) + ": vertices changed";
    }
    for (int f = 0; f < 4; ++f) {
      const auto k = static_cast<std::size_t>(f);
      if (mesh.tets[id].neighbor[k] != before.records[t].neighbor[k]) {
        return "slot " + std::to_string(t) + ": reference " + std::to_string(f) + " changed";
      }
    }
  }
  return {};
}

struct UndoCounts {
  int give_ups = 0;
  int after_flips = 0;       // give-ups that undid flips (a split and at least one flip)
  int after_s44_or_s22 = 0;  // of those, the ones that undid an S44 or S22 (degenerate input)
};

// Builds the mesh of points [0, built) through `sync` (points 0 to 3 affinely independent) with
// nothing refused (refuse(v, false)), then tries each further point v once with refuse(v, true) and
// checks every give-up's undo; v then goes in with refuse(v, false). The store must be set up as
// the policy's method sets it up, and `reclaimer` given where the method's threads have one (slots
// reused after the epochs).
template <class Sync, class Refuse>
UndoCounts check_give_ups_undo(const std::vector<predicates::Point3>& points,
                               engine::SharedMesh& mesh, Sync& sync, std::size_t built,
                               Refuse&& refuse, engine::SlotReclaimer* reclaimer = nullptr) {
  using Dt = engine::IncrementalDelaunay<predicates::AdaptiveKernel, Sync>;
  engine::TriangulateOptions options;
  options.location = engine::Location::Walk;
  options.insertion = engine::Insertion::Flips;
  engine::TriangulationStats start_stats;
  engine::NoSync no_sync;
  engine::IncrementalDelaunay<predicates::AdaptiveKernel, engine::NoSync>(mesh, options,
                                                                          start_stats, no_sync)
      .start(0, 1, 2, 3);
  engine::TriangulationStats stats;
  Dt dt(mesh, options, stats, sync, reclaimer);
  UndoCounts counts;
  const auto degenerate_flips = [&stats] { return stats.flips.s22 + stats.flips.s44; };
  const auto flips = [&] { return stats.flips.s23 + stats.flips.s32 + degenerate_flips(); };
  for (std::size_t i = 4; i < points.size(); ++i) {
    const auto v = static_cast<engine::VertexId>(i);
    if (i >= built) {
      const StoreSnapshot before = snapshot_of(mesh);
      const std::uint64_t flips_before = flips();
      const std::uint64_t degenerate_before = degenerate_flips();
      refuse(v, true);
      const auto outcome = dt.insert(v);
      refuse(v, false);
      if (outcome == Dt::Outcome::Inserted) continue;
      EXPECT_EQ(outcome, Dt::Outcome::GaveUp) << "point " << i;
      ++counts.give_ups;
      if (flips() > flips_before) ++counts.after_flips;
      if (degenerate_flips() > degenerate_before) ++counts.after_s44_or_s22;
      const std::string difference = store_difference(mesh, before);
      EXPECT_TRUE(difference.empty()) << "point " << i << ": " << difference;
      if (!difference.empty()) return counts;  // the mesh is broken: no use going on
    }
    refuse(v, false);
    EXPECT_EQ(dt.insert(v), Dt::Outcome::Inserted) << "point " << i;
  }
  const auto expected = engine::canonical_tetrahedra(engine::triangulate(points, {}).tetrahedra);
  EXPECT_EQ(engine::canonical_tetrahedra(
                dt.finite_tetrahedra(static_cast<engine::VertexId>(points.size()))),
            expected);
  return counts;
}

}  // namespace dtlab::test
