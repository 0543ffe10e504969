#pragma once
// The vertices of a point set in a uniform grid of cells over their bounding box, searched in
// shells of cells around a point's cell (the cells at Chebyshev distance r): star splaying's first
// stars for points no tetrahedron uses (NearGrid, splay_common.hpp) and the bridges between
// pieces of agreeing stars (star_pieces.cpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <numeric>
#include <vector>

#include "dtlab/predicates/point.hpp"
#include "mesh/tet_store.hpp"

namespace dtlab::engine {

class VertexGrid {
 public:
  // About 2 vertices a cell, at most 256 cells an axis; `vertices` must not be empty.
  VertexGrid(const std::vector<predicates::Point3>& points, const std::vector<VertexId>& vertices) {
    lo_ = hi_ = points[vertices.front()];
    for (const VertexId v : vertices) {
      const predicates::Point3& p = points[v];
      lo_ = {std::min(lo_.x, p.x), std::min(lo_.y, p.y), std::min(lo_.z, p.z)};
      hi_ = {std::max(hi_.x, p.x), std::max(hi_.y, p.y), std::max(hi_.z, p.z)};
    }
    cells_ =
        std::clamp(static_cast<int>(std::cbrt(static_cast<double>(vertices.size()) / 2)), 1, 256);
    min_width_ = std::numeric_limits<double>::infinity();
    for (const double span : {hi_.x - lo_.x, hi_.y - lo_.y, hi_.z - lo_.z}) {
      if (span > 0 && std::isfinite(span)) min_width_ = std::min(min_width_, span / cells_);
    }
    first_.assign(static_cast<std::size_t>(cells_) * cells_ * cells_ + 1, 0);
    for (const VertexId v : vertices) ++first_[cell_id(cell(points[v])) + 1];
    std::partial_sum(first_.begin(), first_.end(), first_.begin());
    members_.resize(vertices.size());
    std::vector<std::uint32_t> fill(first_.begin(), first_.end() - 1);
    for (const VertexId v : vertices) members_[fill[cell_id(cell(points[v]))]++] = v;
  }

  [[nodiscard]] int cells() const { return cells_; }
  // The narrowest cell along an axis the vertices spread over: a vertex in shell r + 1 or beyond
  // is at least r such widths from any point of the centre cell (less the cells' rounding).
  [[nodiscard]] double min_width() const { return min_width_; }

  [[nodiscard]] std::array<int, 3> cell(const predicates::Point3& p) const {
    auto axis = [&](double x, double l, double h) {
      const double span = h - l;
      if (!(span > 0) || !std::isfinite(span)) return 0;
      const double t = (x - l) / span * cells_;
      return t <= 0 ? 0 : t >= cells_ ? cells_ - 1 : static_cast<int>(t);
    };
    return {axis(p.x, lo_.x, hi_.x), axis(p.y, lo_.y, hi_.y), axis(p.z, lo_.z, hi_.z)};
  }

  // Calls visit(v) for every vertex in the cells at Chebyshev distance r from cell c: the
  // shell's faces only, O(r^2) cells, not the whole cube around it.
  template <class Visit>
  void for_shell(const std::array<int, 3>& c, int r, const Visit& visit) const {
    for (int i = std::max(c[0] - r, 0); i <= std::min(c[0] + r, cells_ - 1); ++i) {
      for (int j = std::max(c[1] - r, 0); j <= std::min(c[1] + r, cells_ - 1); ++j) {
        // Inside the i and j faces only the two k faces are on the shell.
        const bool on_face = std::abs(i - c[0]) == r || std::abs(j - c[1]) == r;
        const int step = on_face ? 1 : 2 * r;
        for (int k = c[2] - r; k <= c[2] + r; k += step) {
          if (k < 0 || k >= cells_) continue;
          const std::size_t id = cell_id({i, j, k});
          for (std::uint32_t m = first_[id]; m < first_[id + 1]; ++m) visit(members_[m]);
        }
      }
    }
  }

 private:
  [[nodiscard]] std::size_t cell_id(const std::array<int, 3>& c) const {
    const auto n = static_cast<std::size_t>(cells_);
    return (static_cast<std::size_t>(c[0]) * n + static_cast<std::size_t>(c[1])) * n +
           static_cast<std::size_t>(c[2]);
  }

  predicates::Point3 lo_{};
  predicates::Point3 hi_{};
  int cells_ = 1;
  double min_width_ = 0.0;
  std::vector<std::uint32_t> first_;
  std::vector<VertexId> members_;
};

}  // namespace dtlab::engine
