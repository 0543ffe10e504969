#pragma once
// What dtlab's two star-splaying repairs share (splay_repair.cpp: the engine's mesh after a run;
// list_repair.cpp: `dtlab repair` of a tetrahedron list): equal points named by one index,
// vertices near a point whose star no tetrahedron gives, the four vertices every star's pool
// starts from, and faces keyed by their sorted vertices.
#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <vector>

#include "dtlab/predicates/point.hpp"
#include "mesh/conflict.hpp"
#include "mesh/face_key.hpp"
#include "mesh/shared_mesh.hpp"
#include "repair/vertex_grid.hpp"
#include "support/radix_sort.hpp"

namespace dtlab::engine {

// Vertices near a point, for the star of a point that no tetrahedron uses: a uniform grid over
// the vertices; the shells around the point's cell are scanned until at least 8 vertices were
// seen, then one shell more. (Nearness only helps the first star; correctness comes from the
// consistency enforcement.) Built at the first question, by whichever thread asks first (a
// consistent mesh, every point a vertex, never asks: the grid of 1M uniform points took
// 20-24 ms, timed alone on the development VM).
class NearGrid {
 public:
  NearGrid(const std::vector<Point3>& points, std::function<std::vector<VertexId>()> vertices)
      : points_(points), vertices_(std::move(vertices)) {}

  void near(VertexId x, std::vector<VertexId>& out) const {
    std::call_once(built_, [this] {
      const std::vector<VertexId> vertices = vertices_();
      if (!vertices.empty()) grid_.emplace(points_, vertices);
    });
    if (!grid_) return;
    const std::array<int, 3> c = grid_->cell(points_[x]);
    for (int r = 0; r < grid_->cells(); ++r) {
      const std::size_t before = out.size();
      grid_->for_shell(c, r, [&out](VertexId v) { out.push_back(v); });
      if (before >= 8) return;  // this shell was the one more after reaching 8
    }
  }

 private:
  const std::vector<Point3>& points_;
  std::function<std::vector<VertexId>()> vertices_;
  mutable std::once_flag built_;
  mutable std::optional<VertexGrid> grid_;
};

// 32 bits of a hash of a point's coordinates (-0.0 read as +0.0, since the two are equal): equal
// points hash alike. Knuth's multiplicative hashing (TAOCP vol. 3, 6.4) with the golden ratio,
// 2^64 / phi, folded over the three bit patterns; the high half of the last product is the key.
std::uint64_t coordinate_hash(const Point3& p);

// canonical[x]: the one index that stands for all the points equal to point x in the result:
// the lowest index among those that `is_vertex` (the engine keeps whichever duplicate it met
// first), else the lowest index. Equal points are found by sorting the indices by a hash of the
// coordinates (linear time, stable: each run of equal hashes keeps its indices increasing), then
// comparing exactly inside each run (two different points with one hash only make a run longer).
template <class IsVertex>
std::vector<VertexId> canonical_points(const std::vector<Point3>& points, IsVertex is_vertex) {
  const std::size_t n = points.size();
  std::vector<KeyedId> keyed(n);
  for (std::size_t i = 0; i < n; ++i)
    keyed[i] = {coordinate_hash(points[i]), static_cast<VertexId>(i)};
  {
    std::vector<KeyedId> scratch(n);
    stable_sort_by_key(keyed.data(), scratch.data(), n);
  }
  std::vector<VertexId> canonical(n);
  std::vector<VertexId> run;
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i + 1;
    while (j < n && keyed[j].first == keyed[i].first) ++j;
    run.clear();
    for (std::size_t k = i; k < j; ++k) run.push_back(keyed[k].second);
    i = j;
    if (run.size() > 1) {
      std::stable_sort(run.begin(), run.end(), [&](VertexId a, VertexId b) {
        return predicates::lexicographically_less(points[a], points[b]);
      });
    }
    for (std::size_t a = 0; a < run.size();) {
      std::size_t b = a;
      VertexId chosen = run[a];
      bool found = false;
      for (; b < run.size() && points[run[b]] == points[run[a]]; ++b) {
        if (!found && is_vertex(run[b])) {
          chosen = run[b];
          found = true;
        }
      }
      for (std::size_t k = a; k < b; ++k) canonical[run[k]] = chosen;
      a = b;
    }
  }
  return canonical;
}

// Four affinely independent vertices of `vertices`.
std::array<VertexId, 4> pool_of(const std::vector<Point3>& points,
                                const std::vector<VertexId>& vertices);

}  // namespace dtlab::engine
